"""Hostile input, round three (issue #35), from Python: array layouts, threads writing one
path, Ctrl-C during writes, chains past 1x1, endless iterators."""

import itertools
import os
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

import bumpmap


def layouts(a):
    """The same values in other memory layouts: Fortran order, a strided view, negative strides."""
    wide = np.zeros((a.shape[0], 2 * a.shape[1]) + a.shape[2:], a.dtype)
    wide[:, ::2] = a
    flipped = np.ascontiguousarray(a[::-1, ::-1])[::-1, ::-1]
    return [np.asfortranarray(a), wide[:, ::2], flipped]


def test_every_layout_gives_the_bytes_of_its_c_contiguous_copy(tmp_path):
    heights = bumpmap.read_height_field("dimples@32")
    expected = bumpmap.normal_map(np.ascontiguousarray(heights))
    for view in layouts(heights):
        assert not view.flags.c_contiguous
        assert np.array_equal(bumpmap.normal_map(view), expected)
    # write_texture: each level in every layout, the same file.
    chain = bumpmap.mip_chain(heights)
    bumpmap.write_texture(tmp_path / "c.ktx2", [np.ascontiguousarray(level) for level in chain])
    for i in range(3):
        levels = [layouts(level)[i] if min(level.shape[:2]) > 1 else level for level in chain]
        bumpmap.write_texture(tmp_path / f"l{i}.ktx2", levels)
        assert (tmp_path / f"l{i}.ktx2").read_bytes() == (tmp_path / "c.ktx2").read_bytes(), i
    # tangents: rows of a transposed array and of a strided one.
    positions = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], np.float32)
    normals = np.tile(np.array([0, 0, 1], np.float32), (4, 1))
    uvs = positions[:, :2].copy()
    indices = np.array([0, 1, 2, 0, 2, 3], np.uint32)
    want = bumpmap.tangents(positions, normals, uvs, indices)
    for p, n, u in zip(layouts(positions), layouts(normals), layouts(uvs)):
        got = bumpmap.tangents(p, n, u, indices)
        for key in want:
            assert np.array_equal(got[key], want[key]), key


def test_eight_threads_writing_one_path_leave_one_whole_file_from_one_call(tmp_path):
    presets = ["bricks", "dimples", "noise:1", "noise:2", "noise:3", "noise:4", "noise:5", "noise:6"]
    chains = [bumpmap.mip_chain(bumpmap.read_height_field(f"{p}@64")) for p in presets]
    alone = []
    for k, chain in enumerate(chains):
        bumpmap.write_texture(tmp_path / f"alone{k}.ktx2", chain, format="bc7")
        alone.append((tmp_path / f"alone{k}.ktx2").read_bytes())
    assert len(set(alone)) == 8
    target = tmp_path / "shared" / "n.ktx2"
    errors = []

    def write(chain):
        try:
            bumpmap.write_texture(target, chain, format="bc7")
        except Exception as e:  # noqa: BLE001 - any failure is the finding
            errors.append(e)

    for _ in range(3):
        threads = [threading.Thread(target=write, args=(c,)) for c in chains]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert errors == []
        assert target.read_bytes() in alone, "one call's file, whole"
        assert os.listdir(target.parent) == ["n.ktx2"], "no temporary file left"


SCRIPT = """
import os, signal, sys, threading, time
# Python's own Ctrl-C handler, whatever the runner left (a shell's `cmd &` ignores SIGINT).
signal.signal(signal.SIGINT, signal.default_int_handler)
import numpy as np
import bumpmap
out = sys.argv[1]
what = sys.argv[2]
if what == "write_texture":
    chain = bumpmap.mip_chain(bumpmap.read_height_field("noise:3@2048"))
    call = lambda: bumpmap.write_texture(os.path.join(out, "n.dds"), chain, format="bc7")
    delay = 0.2
else:
    call = lambda: bumpmap.compare(os.path.join(out, "report"), size=48, spp=64, techniques="kilgard")
    delay = 1.0
sent = []
def interrupt():
    time.sleep(delay)
    sent.append(time.monotonic())
    os.kill(os.getpid(), signal.SIGINT)
# The timer starts once the inputs are made: the signal comes during the call itself.
threading.Thread(target=interrupt, daemon=True).start()
try:
    call()
    print("finished before the interrupt")
except KeyboardInterrupt:
    print(f"interrupted after {time.monotonic() - sent[0]:.3f}")
"""


@pytest.mark.parametrize("what", ["write_texture", "compare"])
def test_ctrl_c_leaves_nothing_and_writes_nothing_within_half_a_second(tmp_path, what):
    out = tmp_path / "out"
    out.mkdir()
    script = tmp_path / "interrupt.py"
    script.write_text(textwrap.dedent(SCRIPT))
    done = subprocess.run([sys.executable, str(script), str(out), what], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    said = done.stdout.strip()
    assert said.startswith("interrupted after"), f"{said} {done.stderr}"
    assert float(said.split()[-1]) < 0.5, said
    # The script ended right after the interrupt, while the work still ran: nothing was put
    # in place, and the files it had staged are gone too.
    leftovers = [os.path.join(d, f) for d, dirs, files in os.walk(out) for f in files + dirs]
    assert leftovers == [], leftovers


def test_levels_past_1x1_are_refused():
    chain = bumpmap.mip_chain(bumpmap.read_height_field("bricks@8"))
    assert chain[-1].shape[:2] == (1, 1)
    with pytest.raises(ValueError, match=r"5 levels for a 8x8 level 0: its chain ends at 1x1 after 4 levels"):
        bumpmap.write_texture("never.ktx2", chain + [chain[-1]])
    assert not os.path.exists("never.ktx2")


def test_an_endless_iterator_as_an_option_value_is_an_error():
    with pytest.raises(ValueError, match="light takes at most 4096 values"):
        bumpmap.render(light=itertools.repeat("1,1,1"), size=16)
    with pytest.raises(ValueError, match="the number of lights must be at most 64"):
        bumpmap.render(light=["1,1,1"] * 65, size=16)
