"""tangents against `bumpmap tangents`: the same mesh out, byte for byte, read from the GLB it
writes; and the arrays it refuses."""

import numpy as np
import pytest

import bumpmap
from conftest import read_glb, wavy_grid, write_gltf


@pytest.mark.parametrize("mode", ["ours", "mikktspace"])
def test_tangents_equal_the_cli(tmp_path, cli, mode):
    positions, normals, uvs, indices = wavy_grid()
    write_gltf(tmp_path / "grid.gltf", positions, normals, uvs, indices)
    cli("tangents", tmp_path / "grid.gltf", "-o", tmp_path / "grid.glb", "--mode", mode)
    theirs = read_glb(tmp_path / "grid.glb")
    ours = bumpmap.tangents(positions, normals, uvs, indices, mode=mode)
    assert ours["tangents"].dtype == np.float32 and ours["tangents"].shape[1] == 4
    assert np.array_equal(ours["positions"], theirs["POSITION"])
    assert np.array_equal(ours["normals"], theirs["NORMAL"])
    assert np.array_equal(ours["uvs"], theirs["TEXCOORD_0"])
    assert np.array_equal(ours["tangents"], theirs["TANGENT"])
    assert np.array_equal(ours["indices"], theirs["indices"])
    # The mirrored half has glTF's w = -1, the rest +1: both occur.
    assert set(np.unique(ours["tangents"][:, 3])) == {-1.0, 1.0}
    # "mirrored" counts the triangles mirrored as the image is displayed, as the command says it:
    # those whose corners carry glTF's w = -1 (the report once counted the others).
    first_w = ours["tangents"][ours["indices"][:, 0], 3]
    assert ours["report"]["mirrored"] == int(np.sum(first_w == -1.0))
    assert 0 < ours["report"]["mirrored"] < len(ours["indices"])


def test_mirrored_counts_the_triangles_mirrored_as_displayed():
    # The grid's last quarter of columns mirrors its texture in u (v runs down the image, as glTF's
    # does): a quarter of the triangles show the image mirrored, glTF's w = -1 on them.
    positions, normals, uvs, indices = wavy_grid(mirror_half=False)
    x = positions[:, 0]
    uvs[:, 0] = np.where(x > 0.75, 1.5 - x, x)
    out = bumpmap.tangents(positions, normals, uvs, indices)
    assert out["report"]["mirrored"] == len(indices) // 4
    first_w = out["tangents"][out["indices"][:, 0], 3]
    assert int(np.sum(first_w == -1.0)) == len(indices) // 4


def test_split_vertices_and_computed_normals():
    positions, normals, uvs, indices = wavy_grid()
    out = bumpmap.tangents(positions, None, uvs, indices)
    assert out["report"]["normals_computed"]
    # The mirror seam splits the vertices on it: the mesh out has more vertices than in.
    assert out["report"]["vertices_split"] > 0
    assert len(out["positions"]) == len(positions) + out["report"]["vertices_split"]
    t = out["tangents"][:, :3]
    assert np.allclose(np.linalg.norm(t, axis=1), 1, atol=1e-5)
    assert np.abs(np.sum(t * out["normals"], axis=1)).max() < 1e-4, "tangents are perpendicular to the normals"
    # Flat indices are the same triangles.
    flat = bumpmap.tangents(positions, None, uvs, indices.reshape(-1))
    assert np.array_equal(flat["tangents"], out["tangents"])


def test_arrays_it_refuses():
    positions, normals, uvs, indices = wavy_grid(4, 4)
    with pytest.raises(TypeError, match=r"indices must be uint32, got int64: use indices.astype\(numpy.uint32\)"):
        bumpmap.tangents(positions, normals, uvs, indices.astype(np.int64))
    with pytest.raises(TypeError, match=r"positions must be float32, got float64"):
        bumpmap.tangents(positions.astype(np.float64), normals, uvs, indices)
    with pytest.raises(ValueError, match=r"uvs must have shape \(N, 2\)"):
        bumpmap.tangents(positions, normals, positions, indices)
    with pytest.raises(ValueError, match=r"normals has 24 rows, positions 25"):
        bumpmap.tangents(positions, normals[:-1], uvs, indices)
    bad = indices.copy()
    bad[3, 1] = 1000
    with pytest.raises(ValueError, match="1000"):
        bumpmap.tangents(positions, normals, uvs, bad)
    with pytest.raises(ValueError, match=r"split_angle must be in \[0, 180\], got 200"):
        bumpmap.tangents(positions, normals, uvs, indices, split_angle=200)
    with pytest.raises(ValueError, match=r"'exact'.*possible values: ours, mikktspace"):
        bumpmap.tangents(positions, normals, uvs, indices, mode="exact")
