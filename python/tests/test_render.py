"""render against `bumpmap render` on the CPU backend, byte for byte; the catalogue; errors."""

import numpy as np
import pytest

import bumpmap
from conftest import read_png

CASES = [
    ({"size": 64}, ["--size", "64"]),
    ({"scene": "sphere", "technique": "single-pass", "size": 48, "light": [(3, -2, 4), "dir:-1,0,1@0.3,0.3,0.6"],
      "height_field": "dimples", "bump_scale": 8, "shininess": 32},
     ["--scene", "sphere", "--technique", "single-pass", "--size", "48", "--light", "3,-2,4",
      "--light", "dir:-1,0,1@0.3,0.3,0.6", "--height-field", "dimples", "--bump-scale", "8", "--shininess", "32"]),
    ({"scene": "wall", "technique": "emboss", "width": 40, "height": 24, "eye": (0.5, -0.3, 3), "no_self_shadow": True},
     ["--scene", "wall", "--technique", "emboss", "--width", "40", "--height", "24", "--eye", "0.5,-0.3,3",
      "--no-self-shadow"]),
    ({"technique": "reference", "size": 32, "spp": 4}, ["--technique", "reference", "--size", "32", "--spp", "4"]),
]


@pytest.mark.parametrize("options, flags", CASES)
def test_render_equals_the_cli(tmp_path, cli, options, flags):
    out = tmp_path / "r.png"
    cli("render", "--backend", "cpu", "-o", out, *flags)
    expected = read_png(out)
    got = bumpmap.render(backend="cpu", **options)
    assert got.dtype == np.uint8 and got.shape == expected.shape[:2] + (4,)
    assert np.array_equal(got[..., :3], expected)
    assert (got[..., 3] == 255).all()
    # Not a black image: the lit surface covers part of the frame.
    assert (got[..., :3].max(axis=2) > 40).mean() > 0.05


def test_a_normal_map_file_renders(tmp_path, cli):
    normals = bumpmap.normal_map(bumpmap.read_height_field("pinwheel@64"), scale=6)
    (path,) = bumpmap.write_texture(tmp_path / "pinwheel.png", normals)
    cli("render", "--size", "48", "--scene", "patch", "--technique", "single-pass", "--normal-map", path,
        "-o", tmp_path / "r.png")
    got = bumpmap.render(size=48, scene="patch", technique="single-pass", normal_map=path)
    assert np.array_equal(got[..., :3], read_png(tmp_path / "r.png"))


def test_every_technique_of_the_catalogue_draws():
    names = [name for name, _, _ in bumpmap.techniques()]
    assert len(names) == 24 and names[0] == "kilgard" and "reference" in names and "toksvig" in names
    assert "pom" in names and "height-exact" in names and "reference-displaced" in names
    assert "roughness-map" in names and "lean" in names and "clean" in names
    flat = bumpmap.render(size=32, technique="no-bump")
    for name in names:
        image = bumpmap.render(size=32, technique=name, spp=1)
        assert image.shape == (32, 32, 4)
        assert image[..., :3].max() > 40, name
        if name not in ("no-bump", "mip-renormalized"):
            assert not np.array_equal(image, flat), f"{name} shows bumps"


def test_errors_name_the_keyword():
    with pytest.raises(ValueError, match=r"'phong'.*technique.*possible values: kilgard"):
        bumpmap.render(technique="phong")
    with pytest.raises(ValueError, match=r"technique kilgard cannot do shininess 16") as e:
        bumpmap.render(size=16, shininess=16)
    assert "--" not in str(e.value)
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'output'"):
        bumpmap.render(output="x.png")
    with pytest.raises(TypeError, match=r"no_self_shadow is True or False, got int"):
        bumpmap.render(no_self_shadow=1)
    with pytest.raises(ValueError, match=r"eye"):
        bumpmap.render(eye=(0, 0))
    with pytest.raises(ValueError, match=r"size"):
        bumpmap.render(size=0)
    with pytest.raises(ValueError, match=r"size.*width|width.*size"):
        bumpmap.render(size=16, width=8, height=8)
    with pytest.raises(FileNotFoundError, match="missing.png"):
        bumpmap.render(size=16, normal_map="missing.png")
