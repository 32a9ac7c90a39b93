"""Horizon maps, ambient occlusion and bent normals from Python: horizon_maps() against the files
`bumpmap normalmap --horizon-out --ao-out --bent-normals-out` writes (read by pypng and NumPy, not
by bumpmap), the ORM texture's occlusion in red as glTF reads it, bent normals pointing the way
their Y convention says, and the horizon technique's render."""

import numpy as np
import pytest

import bumpmap
from conftest import read_png


@pytest.fixture
def bricks():
    return bumpmap.read_height_field("bricks@64")


def test_horizon_maps_are_the_files_the_command_writes(tmp_path, cli, bricks):
    cli("normalmap", "bricks@64", "-o", tmp_path / "n.png", "--mips", "--horizon-out", tmp_path / "hz.png",
        "--ao-out", tmp_path / "ao.png", "--bent-normals-out", tmp_path / "bent.png",
        "--roughness-out", tmp_path / "orm.png", "--roughness-layout", "gltf")
    maps = bumpmap.horizon_maps(bricks)
    horizons, ao, bent = maps["horizons"], maps["ambient_occlusion"], maps["bent_normals"]
    assert [h.shape for h in horizons[:2]] == [(64, 64, 8), (32, 32, 8)] and len(horizons) == 7
    assert ao.shape == (64, 64) and ao.dtype == np.float32 and bent.shape == (64, 64, 4)
    # The horizon files: directions 0-3 then 4-7, each value rounded to 8 bits.
    stored = np.concatenate([read_png(tmp_path / "hz.png"), read_png(tmp_path / "hz.dirs4-7.png")], axis=2)
    assert np.array_equal(stored, np.round(horizons[0] * 255).astype(np.uint8))
    assert np.array_equal(read_png(tmp_path / "hz.mip1.png"), np.round(horizons[1][..., :4] * 255).astype(np.uint8))
    # Ambient occlusion: one gray channel, as an engine's occlusion map reads it.
    assert np.array_equal(read_png(tmp_path / "ao.png")[..., 0], np.round(ao * 255).astype(np.uint8))
    assert 0.3 < ao.min() < 0.95 and ao.max() == 1.0
    # glTF's ORM: occlusion in R (the same values), roughness in G, metallic 0 in B.
    orm = read_png(tmp_path / "orm.png")
    assert np.array_equal(orm[..., 0], np.round(ao * 255).astype(np.uint8))
    assert orm[..., 2].max() == 0 and orm[..., 1].min() > 0
    # Bent normals: the file is the array, unit vectors leaning out of the mortar.
    assert np.array_equal(read_png(tmp_path / "bent.png"), bent)
    n = bent[..., :3].astype(np.float64) / 127.5 - 1
    assert np.allclose(np.linalg.norm(n, axis=2), 1, atol=0.02) and n[..., 2].min() > 0.5


def test_bent_normals_lean_away_from_a_wall_as_their_y_convention_says():
    # A wall along the top rows of the image: the sky is open down the image, away from it.
    heights = np.zeros((32, 32), np.float32)
    heights[:8] = 1.0
    for convention, down_is_green_up in [("opengl", False), ("directx", True)]:
        bent = bumpmap.horizon_maps(heights, y_convention=convention)["bent_normals"]
        g = bent[12, 16, 1] / 127.5 - 1
        # OpenGL's green is up the image: leaning down is negative green; DirectX's the reverse.
        assert (g > 0.05) == down_is_green_up and abs(g) > 0.05, (convention, g)
        # Far from the wall the sky is open all round.
        assert abs(bent[24, 16, 1] / 127.5 - 1) < abs(g)


def test_the_horizon_technique_renders_shadows_the_single_pass_lacks():
    light = "dir:0.9,0.3,0.34"
    plain = bumpmap.render(scene="wall", technique="single-pass", size=64, light=light)
    shadowed = bumpmap.render(scene="wall", technique="horizon", size=64, light=light)
    pom = bumpmap.render(scene="wall", technique="pom", parallax_shadow="horizon", size=64, light=light)
    assert shadowed[..., :3].mean() > 20, "not black"
    assert shadowed[..., :3].mean() < plain[..., :3].mean() and pom[..., :3].mean() < plain[..., :3].mean()
    assert ("horizon" in [t[0] for t in bumpmap.techniques()])


def test_bad_heights_raise():
    with pytest.raises(ValueError, match="NaN"):
        bumpmap.horizon_maps(np.full((8, 8), np.nan, np.float32))
    with pytest.raises(TypeError):
        bumpmap.horizon_maps(np.zeros((8, 8), np.float32), depth=3)
