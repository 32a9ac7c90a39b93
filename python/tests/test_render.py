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


def _quads_gltf(path, maps, double_sided=False):
    """Quads side by side, one primitive and one material each, material i with normal
    texture `maps[i]` (PNG bytes), as a glTF whose buffer and images are data URIs."""
    import base64
    import json

    bin_, views, accessors, prims = bytearray(), [], [], []

    def accessor(data, component, count, kind, **extra):
        while len(bin_) % 4:
            bin_.append(0)
        views.append({"buffer": 0, "byteOffset": len(bin_), "byteLength": len(data)})
        bin_.extend(data)
        accessors.append({"bufferView": len(views) - 1, "componentType": component, "count": count, "type": kind, **extra})
        return len(accessors) - 1

    for i in range(len(maps)):
        x0 = 2.2 * i - 1.1 * (len(maps) - 1)
        p = np.array([[x0 - 1, -1, 0], [x0 + 1, -1, 0], [x0 + 1, 1, 0], [x0 - 1, 1, 0]], "<f4")
        prims.append({
            "attributes": {
                "POSITION": accessor(p.tobytes(), 5126, 4, "VEC3", min=p.min(0).tolist(), max=p.max(0).tolist()),
                "NORMAL": accessor(np.tile(np.array([0, 0, 1], "<f4"), 4).tobytes(), 5126, 4, "VEC3"),
                "TEXCOORD_0": accessor(np.array([0, 1, 1, 1, 1, 0, 0, 0], "<f4").tobytes(), 5126, 4, "VEC2"),
            },
            "indices": accessor(np.array([0, 1, 2, 0, 2, 3], "<u2").tobytes(), 5123, 6, "SCALAR"),
            "material": i,
        })
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": prims}],
        "materials": [{"normalTexture": {"index": i}, "doubleSided": double_sided} for i in range(len(maps))],
        "textures": [{"source": i} for i in range(len(maps))],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(m).decode()} for m in maps],
        "buffers": [{"byteLength": len(bin_), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(bin_)).decode()}],
        "bufferViews": views, "accessors": accessors,
    }
    path.write_text(json.dumps(doc))


def test_a_gltf_of_two_materials_renders_each_part_with_its_own_map(tmp_path, cli):
    # Two normal maps made here: ridges across and along; each quad of the file reads its own.
    pngs = []
    for name, h in [("across", lambda x, y: np.sin(x / 4)), ("along", lambda x, y: np.sin(y / 4))]:
        heights = np.fromfunction(h, (64, 64), dtype=np.float32).T.astype(np.float32) * 0.5 + 0.5
        (path,) = bumpmap.write_texture(tmp_path / f"{name}.png", bumpmap.normal_map(heights, scale=6))
        pngs.append(path.read_bytes())
    scene = tmp_path / "two.gltf"
    _quads_gltf(scene, pngs)
    args = dict(scene=f"mesh:{scene}", technique="single-pass", width=96, height=48, eye=(0, 0, 4.5),
                light=["dir:-1,0.6,0.5"], specular=0)
    got = bumpmap.render(backend="cpu", **args)
    out = tmp_path / "two.png"
    done = cli("render", "--backend", "cpu", "--scene", f"mesh:{scene}", "--technique", "single-pass",
               "--width", "96", "--height", "48", "--eye", "0,0,4.5", "--light", "dir:-1,0.6,0.5",
               "--specular", "0", "-o", out)
    assert "2 primitive(s) drawn with 2 material(s)" in done.stderr, done.stderr
    assert np.array_equal(got[..., :3], read_png(out))
    # Each half shows its own ridges: the left varies across its columns, the right down its rows.
    left, right = got[14:34, 23:45, :3].astype(float), got[14:34, 51:73, :3].astype(float)
    assert left.std(axis=1).mean() > 3 * left.std(axis=0).mean()
    assert right.std(axis=0).mean() > 3 * right.std(axis=1).mean()
