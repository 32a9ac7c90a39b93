"""A batch of 50 items (a normal map, tangents and a render each) through a process pool
started by `fork` after the parent has used bumpmap, through a forked child that forks again,
and through threads calling at once: each finishes with the same arrays as one call at a time.

rayon's global pool does not survive fork (the child has its registry, none of its threads):
before the package ran its work on a pool of its own per process, the child's first parallel
loop waited for ever. Each way runs in a process group of its own (`batch_work.py`), killed
after a timeout, so a regression fails instead of hanging the suite.
"""

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).with_name("batch_work.py")
# Minutes of margin over the seconds each batch takes on a 2-core machine.
TIMEOUT_S = int(os.environ.get("BUMPMAP_BATCH_TIMEOUT_S", "180"))


def run_batch(way):
    proc = subprocess.Popen([sys.executable, str(SCRIPT), way], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, start_new_session=True)
    try:
        out, _ = proc.communicate(timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, _ = proc.communicate()
        pytest.fail(f"{way}: still running after {TIMEOUT_S} s (hung):\n{out}")
    print(out)
    assert proc.returncode == 0, f"{way}:\n{out}"


@pytest.mark.parametrize("way", ["fork", "nested", "threads"])
def test_a_batch_finishes_with_the_same_arrays(way):
    run_batch(way)


def test_a_batch_through_dask_distributed_finishes():
    # scripts/test_python.sh installs dask.distributed: missing, the test fails, not skips.
    import dask.distributed  # noqa: F401

    run_batch("dask")
