"""The interpreter exiting while daemon threads are inside bumpmap calls.

Before the module's exit hook gave up on running work and waited for it, a daemon thread inside
a GPU render when the main thread returned crashed the process in about a third of the runs of
the script below with the GPU backend (SIGSEGV: the exit tore down the Vulkan driver under the render), and a daemon
thread that took the GIL back during the exit aborted it ("FATAL: exception not rethrown"). Now
the process exits with 0 every time, daemon threads print nothing, and an `atexit` function
that runs after the hook (registered before `import bumpmap`) still calls in.
"""

import subprocess
import sys

import pytest

SCRIPT = r"""
import atexit, random, sys, threading, time

def late():
    try:
        bumpmap.normal_map(heights)
        print("late call ran")
    except RuntimeError as e:
        print("late call refused:", e)

if sys.argv[3] == "late":
    # Registered before bumpmap's own hook, so it runs after it.
    atexit.register(late)
import numpy as np
import bumpmap

heights = np.zeros((64, 64), np.float32)

def work():
    while True:
        bumpmap.render(scene="torus", technique="single-pass", size=256, backend=sys.argv[1])

for _ in range(3):
    threading.Thread(target=work, daemon=True).start()
# Anywhere from inside the first frames (the GPU device opening) to some frames later.
time.sleep(random.Random(int(sys.argv[2])).uniform(0.05, 0.6))
"""


def run(backend, seed, late=False):
    proc = subprocess.run([sys.executable, "-c", SCRIPT, backend, str(seed), "late" if late else "-"],
                          capture_output=True, text=True, timeout=120)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, f"run {seed}: exit status {proc.returncode}\n{out}"
    # A thread whose render failed (no GPU adapter) would leave nothing to test.
    assert "Exception in thread" not in out, out
    return out


@pytest.mark.parametrize("backend", ["gpu", "cpu"])
def test_the_interpreter_exits_with_0_while_daemon_threads_render(backend):
    for seed in range(12):
        run(backend, seed)


def test_an_atexit_function_after_the_hook_still_calls_in():
    # On the exiting thread itself a call runs as before; daemon threads' calls made after the
    # hook never start (they wait for the process to end, so nothing is printed for them).
    assert "late call ran" in run("cpu", 0, late=True)
