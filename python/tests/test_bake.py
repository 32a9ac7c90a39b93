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
    # The waves' mean curvature, half the Laplacian of z: about 7.7 at its peaks, 0 on average.
    curvature = ours["curvature"]
    assert curvature.shape == (48, 48) and 5.0 < curvature.max() < 9.0 and abs(curvature.mean()) < 0.5
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


def square_mesh(n, height):
    """square_obj's square as a bumpmap.Mesh (uvs as glTF stores them: t grows with y here)."""
    x, y = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    positions = np.stack([x, y, height(x, y) + 0 * x], axis=-1).reshape(-1, 3).astype(np.float32)
    uvs = np.stack([x, y], axis=-1).reshape(-1, 2).astype(np.float32)
    a = (np.arange(n)[None, :] + (n + 1) * np.arange(n)[:, None]).ravel()
    b, c, d = a + 1, a + n + 2, a + n + 1
    indices = np.concatenate([np.stack([a, b, c], -1), np.stack([a, c, d], -1)]).astype(np.uint32)
    return bumpmap.Mesh(positions, uvs, indices)


def test_bake_from_mesh_objects_equals_from_files(tmp_path):
    square_obj(tmp_path / "high.obj", 32, waves, uvs=False)
    square_obj(tmp_path / "low.obj", 1, lambda x, y: 0.0)
    from_files = bumpmap.bake(tmp_path / "high.obj", tmp_path / "low.obj", size=32, spp=1)
    high, low = square_mesh(32, waves), square_mesh(1, lambda x, y: 0.0)
    from_meshes = bumpmap.bake(high, low, size=32, spp=1)
    assert np.ptp(from_meshes["levels"][0][..., 0].astype(int)) > 20, "not a flat map"
    difference = np.abs(from_meshes["levels"][0].astype(int) - from_files["levels"][0].astype(int)).max()
    assert difference <= 1, difference
    # A file for one and a Mesh for the other.
    mixed = bumpmap.bake(tmp_path / "high.obj", low, size=32, spp=1)
    assert np.abs(mixed["levels"][0].astype(int) - from_files["levels"][0].astype(int)).max() <= 1
    with pytest.raises(TypeError, match="high must be a mesh file's path or a bumpmap.Mesh"):
        bumpmap.bake(42, low)
    broken = bumpmap.Mesh(low.positions, low.uvs, np.array([[0, 1, 9]], dtype=np.uint32))
    with pytest.raises(ValueError, match="<low Mesh>: triangle 0 uses vertex 9"):
        bumpmap.bake(high, broken, size=16)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["high.obj", "low.obj"]


def test_match_names_needs_named_parts(tmp_path):
    square_obj(tmp_path / "high.obj", 8, waves, uvs=False)
    low = square_mesh(1, lambda x, y: 0.0)
    with pytest.raises(ValueError, match="match_names: <low Mesh>: pairing parts by name needs named parts"):
        bumpmap.bake(tmp_path / "high.obj", low, size=8, match_names=True)
