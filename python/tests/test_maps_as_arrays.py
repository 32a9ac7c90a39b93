"""`roughness_map` and `lean_moments`: the maps `bumpmap normalmap --roughness-out` and
`--lean-out` write, as arrays. Each is compared level for level with the command's files, read
by pypng and by hand from the DDS header (not by bumpmap), from the same heights and options."""

import numpy as np
import pytest

import bumpmap
from conftest import read_png
from test_lean import read_float_dds


def test_roughness_map_is_the_roughness_out_chain(cli, tmp_path):
    heights = bumpmap.read_height_field("dimples@64")
    cli("normalmap", "dimples@64", "--mips", "-o", tmp_path / "n.png", "--scale", "6",
        "--roughness-out", tmp_path / "r.png", "--roughness", "0.3", "--roughness-layout", "gltf")
    levels = bumpmap.roughness_map(heights, scale=6, roughness=0.3, roughness_layout="gltf")
    assert len(levels) == 7
    for k, level in enumerate(levels):
        name = "r.png" if k == 0 else f"r.mip{k}.png"
        stored = read_png(tmp_path / name)
        assert level.dtype == np.uint8 and level.shape == (64 >> k, 64 >> k, 4)
        assert np.array_equal(level, stored), f"level {k}"
    # glTF's layout: roughness in green, metallic 0 in blue; the bumps make level 1 rougher than
    # the surface's own 0.3 somewhere (the normals it averages spread).
    assert (levels[0][..., 2] == 0).all() and levels[1][..., 1].max() > round(0.3 * 0.3 * 255)


def test_lean_moments_are_the_lean_out_files(cli, tmp_path):
    heights = bumpmap.read_height_field("bricks@32")
    cli("normalmap", "bricks@32", "--mips", "-o", tmp_path / "n.png", "--kernel", "sobel3",
        "--lean-out", tmp_path / "l.dds")
    moments, mxy_j = bumpmap.lean_moments(heights, kernel="sobel3")
    files = read_float_dds(tmp_path / "l.dds"), read_float_dds(tmp_path / "l.mxy-j.dds")
    for mine, stored in zip((moments, mxy_j), files):
        assert len(mine) == len(stored) == 6
        for k, (a, b) in enumerate(zip(mine, stored)):
            assert a.dtype == np.float32 and a.shape == b.shape == (32 >> k, 32 >> k, 4)
            assert np.array_equal(a, b), f"level {k}"
    # J = 1/Nz³ ≥ 1 everywhere; bricks tilt some normals, so Bx is not all zero.
    assert (mxy_j[0][..., 1] >= 1).all() and np.abs(moments[0][..., 0]).max() > 0.1


@pytest.mark.parametrize("function", [bumpmap.roughness_map, bumpmap.lean_moments])
def test_bad_input_raises(function):
    with pytest.raises(TypeError, match="complex|dtype"):
        function(np.zeros((8, 8), np.complex64))
    with pytest.raises(TypeError, match="unexpected keyword argument 'bits'"):
        function(np.zeros((8, 8), np.float32), bits=16)
    with pytest.raises(ValueError):
        function(np.zeros((8, 8, 3), np.float32))


def test_roughness_out_of_range_is_a_value_error():
    with pytest.raises(ValueError, match="roughness"):
        bumpmap.roughness_map(np.zeros((8, 8), np.float32), roughness=1.5)
