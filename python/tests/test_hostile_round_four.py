"""Hostile input, round four (issue #57), from Python: inputs too big for the memory the process
may have are refused with what they would need, never an abort."""

import os
import subprocess
import sys
import textwrap


def run_limited(code: str, limit_gib: float):
    """`code` in a fresh interpreter whose address space is limited to `limit_gib` (and two malloc
    arenas, so that the limit measures the work rather than the threads' reserved arenas)."""
    env = dict(os.environ, MALLOC_ARENA_MAX="2", RAYON_NUM_THREADS="2")
    prelude = textwrap.dedent(f"""
        import resource
        limit = int({limit_gib} * (1 << 30))
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    """)
    return subprocess.run([sys.executable, "-c", prelude + textwrap.dedent(code)],
                          capture_output=True, text=True, env=env, timeout=600)


def test_maps_of_a_legal_16384_field_are_refused_with_the_memory_they_need():
    done = run_limited("""
        import numpy as np
        import bumpmap
        heights = np.zeros((16384, 16384), np.uint8)
        for name in ["roughness_map", "height_mips", "horizon_maps", "lean_moments"]:
            try:
                getattr(bumpmap, name)(heights)
                print(name, "made")
            except MemoryError as e:
                print(name, "refused:", e)
    """, 4.5)
    assert done.returncode == 0, done.stderr[-2000:]
    lines = done.stdout.splitlines()
    assert len(lines) == 4, done.stdout + done.stderr[-2000:]
    for line in lines:
        assert "refused:" in line and "not enough memory" in line and "GiB" in line, line


def test_read_texture_of_a_16384_png_tests_its_convention_on_the_centre_only(tmp_path):
    import numpy as np
    import png

    n = 16384
    path = tmp_path / "flat16k.png"
    row = np.tile(np.array([128, 128, 255], np.uint8), n)
    with open(path, "wb") as f:
        png.Writer(n, n, greyscale=False, bitdepth=8, compression=1).write(f, (row for _ in range(n)))
    done = run_limited(f"""
        import bumpmap
        t = bumpmap.read_texture({str(path)!r})
        print(t["levels"][0].shape, t["y_convention"])
    """, 4.5)
    assert done.returncode == 0, done.stderr[-2000:]
    # A flat map: nothing to decide from, and no abort converting all of it to decide it.
    assert done.stdout.strip() == "(16384, 16384, 4) None", done.stdout


def test_a_progress_function_that_raises_stops_the_work_not_only_the_call():
    """The call ended with the exception at once before too; the render then ran on to its end
    on every core. Now it stops at its next tile: the second after the call uses no CPU."""
    import time

    import pytest

    import bumpmap

    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop(f"{done}/{total}")

    with pytest.raises(Stop):
        bumpmap.render(technique="reference", size=512, spp=256, progress=stop)
    time.sleep(0.3)
    before = time.process_time()
    time.sleep(1.0)
    used = time.process_time() - before
    assert used < 0.5, f"the render went on: {used:.2f} s of CPU in the second after the call"
