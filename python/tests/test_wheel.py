"""The wheel installs anywhere and runs the fastest build the processor allows: it is tagged
manylinux2014 (auditwheel reads its symbols), holds the native module built for baseline x86-64
and for x86-64-v3, loads the second here (where the processor has AVX2 and FMA) and the first
when told to or on a processor without them (an emulated Westmere, through qemu), and both give
the same bytes. The command line, built for x86-64-v3, refuses such a processor in words instead
of dying of an illegal instruction."""

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

import bumpmap
from bumpmap import _bumpmap
from conftest import cli_path

WHEEL = os.environ.get("BUMPMAP_WHEEL")
QEMU = shutil.which("qemu-x86_64")
# x86-64-v2 (SSE4.2, POPCNT: what NumPy 2 needs) without AVX: the processors x86-64-v3 leaves out.
OLD_CPU = "Westmere"
LINUX_X86_64 = sys.platform == "linux" and os.uname().machine == "x86_64"

# What both builds make, written as .npy files by a child process.
MAKE = """
import sys
import numpy as np
import bumpmap
out = sys.argv[1]
heights = bumpmap.read_height_field("bricks@128")
np.save(f"{out}/normal8.npy", bumpmap.normal_map(heights, scale=4, kernel="sobel3"))
np.save(f"{out}/normal16.npy", bumpmap.normal_map(heights, scale=6, bits=16))
for k, level in enumerate(bumpmap.mip_chain(heights)):
    np.save(f"{out}/mip{k}.npy", level)
for technique in ["kilgard", "single-pass", "pom", "toksvig", "emboss"]:
    np.save(f"{out}/{technique}.npy", bumpmap.render(technique=technique, size=96, backend="cpu"))
print(bumpmap.native_build)
"""


def make(tmp_path, name, env=None, prefix=()):
    out = tmp_path / name
    out.mkdir()
    done = subprocess.run([*prefix, sys.executable, "-c", MAKE, str(out)], capture_output=True, text=True,
                          env={**os.environ, **(env or {})}, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    return out, done.stdout.split()[-1]


def same_files(a, b):
    names = sorted(p.name for p in a.glob("*.npy"))
    assert len(names) >= 12 and names == sorted(p.name for p in b.glob("*.npy"))
    for name in names:
        x, y = np.load(a / name), np.load(b / name)
        assert x.dtype == y.dtype and np.array_equal(x, y), f"{name} differs between the builds"
    # Not a pair of blank images: the renders light something.
    assert np.load(a / "kilgard.npy")[..., :3].max() > 100


needs_wheel = pytest.mark.skipif(not WHEEL or not LINUX_X86_64,
                                 reason="BUMPMAP_WHEEL (set by scripts/test_python.sh) names the x86-64 Linux wheel")


@needs_wheel
def test_the_wheel_is_manylinux2014_with_both_builds():
    done = subprocess.run([sys.executable, "-m", "auditwheel", "show", WHEEL], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    text = " ".join(done.stdout.split())
    assert '"manylinux_2_17_x86_64"' in text, text
    names = zipfile.ZipFile(WHEEL).namelist()
    assert "bumpmap/_bumpmap.abi3.so" in names and "bumpmap/_bumpmap_x86_64_v3.abi3.so" in names, names
    tags = Path(WHEEL).name.removesuffix(".whl").split("-")[-1].split(".")
    assert sorted(tags) == ["manylinux2014_x86_64", "manylinux_2_17_x86_64"], tags


@needs_wheel
def test_this_processor_gets_the_fast_build_and_the_baseline_gives_the_same_bytes(tmp_path):
    assert _bumpmap.runs_x86_64_v3(), "this test machine has AVX2 and FMA"
    assert bumpmap.native_build == "x86-64-v3"
    fast, fast_build = make(tmp_path, "fast")
    base, base_build = make(tmp_path, "base", {"BUMPMAP_CPU": "x86-64"})
    assert (fast_build, base_build) == ("x86-64-v3", "x86-64")
    same_files(fast, base)


@needs_wheel
@pytest.mark.skipif(not QEMU and not os.environ.get("CI"), reason="qemu-x86_64 (Debian: qemu-user) emulates an older processor")
def test_a_processor_without_avx_loads_the_baseline_build(tmp_path):
    assert QEMU, "qemu-x86_64 is missing (Debian: qemu-user); .ci/run installs it"
    fast, _ = make(tmp_path, "fast")
    old, build = make(tmp_path, "old", prefix=(QEMU, "-cpu", OLD_CPU))
    assert build == "x86-64"
    same_files(fast, old)
    # Insisting on the fast build there fails at import, in words.
    done = subprocess.run([QEMU, "-cpu", OLD_CPU, sys.executable, "-c", "import bumpmap"], capture_output=True,
                          text=True, env={**os.environ, "BUMPMAP_CPU": "x86-64-v3"}, timeout=300)
    assert done.returncode == 1 and "this processor lacks x86-64-v3" in done.stderr, done.stderr[-2000:]


@pytest.mark.skipif(not QEMU and not os.environ.get("CI"), reason="qemu-x86_64 (Debian: qemu-user) emulates an older processor")
def test_the_cli_refuses_a_processor_without_avx_in_words():
    assert QEMU, "qemu-x86_64 is missing (Debian: qemu-user); .ci/run installs it"
    done = subprocess.run([QEMU, "-cpu", OLD_CPU, str(cli_path()), "normalmap", "bricks@64", "-o", "/dev/null"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 1, (done.returncode, done.stderr[-2000:])
    assert "built for x86-64-v3" in done.stderr and "target-cpu=x86-64" in done.stderr, done.stderr[-2000:]


def test_an_unknown_bumpmap_cpu_is_an_import_error():
    done = subprocess.run([sys.executable, "-c", "import bumpmap"], capture_output=True, text=True,
                          env={**os.environ, "BUMPMAP_CPU": "avx512"}, timeout=120)
    assert done.returncode == 1 and "BUMPMAP_CPU='avx512': expected one of auto, x86-64, x86-64-v3" in done.stderr
