"""blend_normals against `bumpmap blend`: the same result from the same maps, read back by pypng;
mixed inputs converted and said; bad values raised."""

import warnings

import numpy as np
import pytest

import bumpmap
from conftest import read_png


def test_blend_normals_equals_the_cli(tmp_path, cli):
    cli("normalmap", "bricks@128", "-o", tmp_path / "base.png", "--bits", "16")
    cli("normalmap", "noise:3@32", "-o", tmp_path / "detail.png", "--scale", "2", "--bits", "16")
    cli("blend", tmp_path / "base.png", tmp_path / "detail.png", "-o", tmp_path / "out.png",
        "--detail-repeat", "4", "--method", "whiteout")
    base, detail = read_png(tmp_path / "base.png"), read_png(tmp_path / "detail.png")
    ours = bumpmap.blend_normals(base, detail, detail_repeat=4, method="whiteout")
    assert len(ours) == 1 and ours[0].dtype == np.uint16 and ours[0].shape == (128, 128, 4)
    assert np.array_equal(ours[0], read_png(tmp_path / "out.png"))
    # The detail shows: the result differs from the base by more than rounding.
    assert np.abs(ours[0].astype(int) - base.astype(int)).max() > 2000
    chain = bumpmap.blend_normals(base, detail, detail_repeat=4, mips=True)
    assert [level.shape[0] for level in chain] == [128, 64, 32, 16, 8, 4, 2, 1]


def test_a_flat_detail_leaves_the_base_and_mixed_inputs_are_said():
    base = bumpmap.normal_map(bumpmap.read_height_field("dimples@64"), scale=4)
    flat = np.zeros((16, 16, 4), dtype=np.uint16)
    flat[..., 2] = 65535
    flat[..., :2] = 32768
    with pytest.warns(bumpmap.BumpmapWarning, match="the base is 8-bit and the detail 16-bit: the result is 16-bit"):
        out = bumpmap.blend_normals(base, flat, method="partial-derivative")
    assert out[0].dtype == np.uint16
    assert np.abs((out[0] >> 8).astype(int) - base.astype(int))[..., :3].max() <= 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        eight = bumpmap.blend_normals(base, flat, method="partial-derivative", bits=8)
    assert eight[0].dtype == np.uint8
    # A detail whose green points down, said and flipped: the same as flipping it ourselves.
    tilted = bumpmap.normal_map(bumpmap.read_height_field("noise:5@64"), scale=3)
    flipped = tilted.copy()
    flipped[..., 1] = 255 - flipped[..., 1]
    with pytest.warns(bumpmap.BumpmapWarning, match="green points down"):
        said = bumpmap.blend_normals(base, flipped, detail_y_convention="directx")
    assert np.abs(said[0].astype(int) - bumpmap.blend_normals(base, tilted)[0].astype(int)).max() <= 1


def test_bad_values_raise():
    base = bumpmap.normal_map(bumpmap.read_height_field("dimples@32"))
    with pytest.raises(ValueError, match="detail_strength"):
        bumpmap.blend_normals(base, base, detail_strength=-1)
    with pytest.raises(ValueError, match="detail_repeat"):
        bumpmap.blend_normals(base, base, detail_repeat=0)
    with pytest.raises(ValueError, match="method"):
        bumpmap.blend_normals(base, base, method="sum")
    with pytest.raises(TypeError, match="detail"):
        bumpmap.blend_normals(base, base.astype(np.int64))
    with pytest.raises(TypeError):
        bumpmap.blend_normals(base, base, no_such_option=1)


def test_a_detail_map_at_render_time_from_an_array_or_a_file(tmp_path, cli):
    detail = bumpmap.normal_map(bumpmap.read_height_field("noise:3@32"), scale=2)
    common = dict(scene="wall", technique="single-pass", size=64)
    plain = bumpmap.render(**common)
    ours = bumpmap.render(**common, detail_map=detail, detail_repeat=3, detail_method="partial-derivative")
    assert np.abs(ours.astype(int) - plain.astype(int)).max() > 30, "the detail shows"
    # Strength 0 is no detail at all.
    assert np.array_equal(bumpmap.render(**common, detail_map=detail, detail_strength=0), plain)
    # The same map from a file draws the same frame as the command line.
    cli("normalmap", "noise:3@32", "-o", tmp_path / "d.png", "--scale", "2")
    cli("render", "--scene", "wall", "--technique", "single-pass", "--size", "64", "-o", tmp_path / "r.png",
        "--detail-map", tmp_path / "d.png", "--detail-repeat", "3", "--detail-method", "partial-derivative")
    from_file = bumpmap.render(**common, detail_map=str(tmp_path / "d.png"), detail_repeat=3,
                               detail_method="partial-derivative")
    assert np.array_equal(from_file[..., :3], read_png(tmp_path / "r.png")[..., :3])
    assert np.array_equal(from_file, ours)
    with pytest.raises(ValueError, match="technique single-pass"):
        bumpmap.render(scene="wall", size=32, detail_map=detail)
    with pytest.raises(ValueError, match="detail_map"):
        bumpmap.render(**common, detail_repeat=3)
    with pytest.raises(ValueError, match="detail_method"):
        bumpmap.render(**common, detail_map=detail, detail_method="sum")
