"""bake against `bumpmap bake`: the same normal map from the same meshes and options, read back
by pypng; what it refuses, raised (nothing written, no flat map)."""

import numpy as np
import pytest

import bumpmap
from conftest import read_png


def square_obj(path, n, height, uvs=True):
    """The unit square, z = height(x, y), n quads a side, with vt (v up, as OBJ has it)."""
    lines = []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = i / n, j / n
            lines.append(f"v {x} {y} {height(x, y)}")
            if uvs:
                lines.append(f"vt {x} {1 - y}")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            b, c, d = a + 1, a + n + 2, a + n + 1
            tri = (lambda *v: " ".join(f"{k}/{k}" for k in v)) if uvs else (lambda *v: " ".join(map(str, v)))
            lines.append(f"f {tri(a, b, c)}")
            lines.append(f"f {tri(a, c, d)}")
    path.write_text("\n".join(lines) + "\n")


def waves(x, y):
    return 0.03 * np.sin(2 * np.pi * 2 * x) * np.cos(2 * np.pi * 3 * y)


def test_bake_equals_the_cli(tmp_path, cli):
    square_obj(tmp_path / "high.obj", 64, waves, uvs=False)
    square_obj(tmp_path / "low.obj", 1, lambda x, y: 0.0)
    cli("bake", tmp_path / "high.obj", tmp_path / "low.obj", "-o", tmp_path / "n.png", "--size", "48", "--spp", "1")
    seen = []
    ours = bumpmap.bake(tmp_path / "high.obj", tmp_path / "low.obj", size=48, spp=1, progress=lambda d, t: seen.append((d, t)))
    level0 = ours["levels"][0]
    assert level0.shape == (48, 48, 4) and level0.dtype == np.uint8
    assert np.array_equal(level0, read_png(tmp_path / "n.png"))
    assert ours["hit"].all() and ours["covered"].all()
    assert ours["object_space"].shape == (48, 48, 3)
    assert abs(ours["displacement"]).max() == pytest.approx(0.03, abs=0.005)
    assert seen and seen[-1] == (48, 48)
    # The waves tilt the normals: not a flat map.
    assert np.ptp(level0[..., 0].astype(int)) > 20
    assert "occlusion" not in ours, "no occlusion unless asked for"
    shaded = bumpmap.bake(tmp_path / "high.obj", tmp_path / "low.obj", size=16, spp=1, ao_rays=16)
    assert shaded["occlusion"].shape == (16, 16) and shaded["occlusion"].dtype == np.float32
    assert 0.5 < shaded["occlusion"].min() <= shaded["occlusion"].max() <= 1.0


def test_a_cage_file_starts_the_rays(tmp_path):
    square_obj(tmp_path / "high.obj", 32, waves, uvs=False)
    square_obj(tmp_path / "low.obj", 1, lambda x, y: 0.0)
    square_obj(tmp_path / "cage.obj", 1, lambda x, y: 0.1)
    caged = bumpmap.bake(tmp_path / "high.obj", tmp_path / "low.obj", size=16, spp=1, cage=tmp_path / "cage.obj")
    extruded = bumpmap.bake(tmp_path / "high.obj", tmp_path / "low.obj", size=16, spp=1, extrude=0.1)
    difference = np.abs(caged["levels"][0].astype(int) - extruded["levels"][0].astype(int)).max()
    assert difference <= 1, "a cage 0.1 out is extrude=0.1"


def test_what_cannot_be_baked_raises(tmp_path):
    square_obj(tmp_path / "high.obj", 8, waves, uvs=False)
    square_obj(tmp_path / "low.obj", 1, lambda x, y: 0.0)
    square_obj(tmp_path / "bare.obj", 1, lambda x, y: 0.0, uvs=False)
    square_obj(tmp_path / "far.obj", 8, lambda x, y: 5.0, uvs=False)
    with pytest.raises(OSError, match="bare.obj: has no texture coordinates"):
        bumpmap.bake(tmp_path / "high.obj", tmp_path / "bare.obj", size=16)
    with pytest.raises(ValueError, match="met the high-poly mesh nowhere"):
        bumpmap.bake(tmp_path / "far.obj", tmp_path / "low.obj", size=16)
    with pytest.raises(ValueError, match="spp"):
        bumpmap.bake(tmp_path / "high.obj", tmp_path / "low.obj", spp=0)
    with pytest.raises(TypeError):
        bumpmap.bake(tmp_path / "high.obj", tmp_path / "low.obj", no_such_option=1)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bare.obj", "far.obj", "high.obj", "low.obj"]
