"""write_texture against `bumpmap normalmap -o`: the same file bytes for every container and
format, all files or none, and the levels it refuses."""

import os

import numpy as np
import pytest

import bumpmap
from conftest import read_png


@pytest.fixture(scope="module")
def chain():
    return bumpmap.mip_chain(bumpmap.read_height_field("bricks@64"))


@pytest.mark.parametrize("ext, fmt", [("dds", "rgba8"), ("dds", "bc5"), ("dds", "bc7"), ("ktx2", "rgba8"), ("ktx2", "bc7")])
def test_containers_equal_the_cli_byte_for_byte(tmp_path, cli, chain, ext, fmt):
    ours = tmp_path / f"ours.{ext}"
    theirs = tmp_path / f"cli.{ext}"
    cli("normalmap", "bricks@64", "-o", theirs, "--mips", "--format", fmt)
    written = bumpmap.write_texture(ours, chain, format=fmt)
    assert [os.fspath(p) for p in written] == [os.fspath(ours)]
    assert ours.read_bytes() == theirs.read_bytes()


def test_sixteen_bit_ktx2_equals_the_cli(tmp_path, cli):
    levels = bumpmap.mip_chain(bumpmap.read_height_field("dimples@32"), bits=16)
    assert levels[0].dtype == np.uint16
    cli("normalmap", "dimples@32", "-o", tmp_path / "cli.ktx2", "--mips", "--bits", "16")
    bumpmap.write_texture(tmp_path / "ours.ktx2", levels)
    assert (tmp_path / "ours.ktx2").read_bytes() == (tmp_path / "cli.ktx2").read_bytes()


def test_png_chain_is_written_beside_level_0(tmp_path, chain):
    written = bumpmap.write_texture(tmp_path / "sub" / "n.png", chain)
    assert len(written) == len(chain) == 7
    for k, level in enumerate(chain):
        path = tmp_path / "sub" / ("n.png" if k == 0 else f"n.mip{k}.png")
        assert np.array_equal(read_png(path), level)


def test_one_array_is_one_level(tmp_path, chain):
    (path,) = bumpmap.write_texture(tmp_path / "n.png", chain[0])
    assert np.array_equal(read_png(path), chain[0])


def test_levels_it_refuses(tmp_path, chain):
    with pytest.raises(ValueError, match=r"level 2 must have shape \(16, 16, 4\)"):
        bumpmap.write_texture(tmp_path / "x.dds", [chain[0], chain[1], chain[3]])
    with pytest.raises(TypeError, match=r"level 1 is uint16.*every level must be uint8"):
        bumpmap.write_texture(tmp_path / "x.dds", [chain[0], chain[1].astype(np.uint16)])
    with pytest.raises(ValueError, match=r"uint16 levels cannot be stored as format BC5"):
        bumpmap.write_texture(tmp_path / "x.dds", chain[0].astype(np.uint16), format="bc5")
    with pytest.raises(ValueError, match=r"\.dds or \.ktx2"):
        bumpmap.write_texture(tmp_path / "x.png", chain, format="bc7")
    with pytest.raises(OSError, match=r"unsupported output format"):
        bumpmap.write_texture(tmp_path / "x.jpg", chain)
    with pytest.raises(ValueError, match="levels is empty"):
        bumpmap.write_texture(tmp_path / "x.png", [])
    with pytest.raises(ValueError, match=r"level 0 must be \(H, W, 4\)"):
        bumpmap.write_texture(tmp_path / "x.png", np.zeros((4, 4, 3), np.uint8))
    assert list(tmp_path.iterdir()) == [], "nothing written by a refused call"


def test_a_set_is_all_or_nothing(tmp_path, chain):
    # The third level's name is taken by a folder: the write fails, and the first two files,
    # written before it, are not left behind.
    (tmp_path / "n.mip2.png").mkdir()
    with pytest.raises(OSError, match="n.mip2.png"):
        bumpmap.write_texture(tmp_path / "n.png", chain)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["n.mip2.png"]
