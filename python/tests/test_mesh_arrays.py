"""A `bumpmap.Mesh` made of arrays is a scene: it draws exactly as the same mesh read from a file
(an OBJ written here with the same vertices, its texture coordinates kept as they are), with the
tangents made the same way or given; and what is wrong with its arrays is a clear exception."""

import numpy as np
import pytest

import bumpmap


def grid(n=6):
    """A bumpy (n-1)² quad grid in the x–y plane, facing +z."""
    u, v = np.meshgrid(np.linspace(0, 1, n, dtype=np.float32), np.linspace(0, 1, n, dtype=np.float32))
    positions = np.stack([2 * u - 1, 2 * v - 1, 0.15 * np.sin(3 * u) * np.cos(2 * v)], axis=-1).reshape(-1, 3)
    uvs = np.stack([u, v], axis=-1).reshape(-1, 2).astype(np.float32)
    quads = [(n * y + x, n * y + x + 1, n * y + x + n + 1, n * y + x + n) for y in range(n - 1) for x in range(n - 1)]
    indices = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.uint32)
    return positions.astype(np.float32), uvs, indices


def write_obj(path, positions, uvs, indices):
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in positions.tolist()]
    lines += [f"vt {s!r} {t!r}" for s, t in uvs.tolist()]
    lines += ["f " + " ".join(f"{i + 1}/{i + 1}" for i in tri) for tri in indices.tolist()]
    path.write_text("\n".join(lines) + "\n")


OPTIONS = dict(technique="single-pass", size=96, eye=(0, -2.2, 2.6), light="2,-1,3", height_field="bricks@64")


def test_a_mesh_of_arrays_draws_as_the_same_mesh_from_a_file(tmp_path):
    positions, uvs, indices = grid()
    write_obj(tmp_path / "grid.obj", positions, uvs, indices)
    from_file = bumpmap.render(scene=f"mesh:{tmp_path / 'grid.obj'}", obj_v="keep", **OPTIONS)
    from_arrays = bumpmap.render(scene=bumpmap.Mesh(positions, uvs, indices), **OPTIONS)
    assert from_arrays.shape == (96, 96, 4)
    lit = from_arrays[..., :3].max(axis=-1) > 30
    assert 0.2 < lit.mean() < 0.95, "the grid fills part of the frame"
    assert np.array_equal(from_arrays, from_file)
    # Bumps show: the bricks' mortar darkens some of the lit grid.
    assert from_arrays[lit][:, 0].std() > 8


def test_given_tangents_and_a_kept_renderer_draw_it_too():
    positions, uvs, indices = grid()
    mesh = bumpmap.Mesh(positions, uvs, indices)
    framed = mesh.with_tangents(mode="mikktspace")
    assert framed.tangents.shape[1] == 4 and len(framed.positions) >= len(positions)
    assert repr(framed).startswith("Mesh(") and "with tangents" in repr(framed)
    image = bumpmap.render(scene=framed, **OPTIONS)
    with bumpmap.Renderer("cpu") as renderer:
        scene = renderer.prepare(scene=framed, **{k: v for k, v in OPTIONS.items() if k != "light"})
        kept = scene.render(light=(2, -1, 3))
    assert np.array_equal(image, kept)
    # Flat frames on a bumpy grid: different tangents, a different image.
    flat = np.tile(np.array([[1, 0, 0, 1]], np.float32), (len(framed.positions), 1))
    other = bumpmap.render(scene=bumpmap.Mesh(framed.positions, framed.uvs, framed.indices, framed.normals, flat),
                           **OPTIONS)
    assert not np.array_equal(image, other)


def test_wrong_arrays_are_clear_exceptions():
    positions, uvs, indices = grid()
    with pytest.raises(TypeError, match="positions must be float32, got float64"):
        bumpmap.render(scene=bumpmap.Mesh(positions.astype(np.float64), uvs, indices), size=16)
    with pytest.raises(ValueError, match=r"render\(\): uvs has 35 rows, positions 36: one per vertex"):
        bumpmap.render(scene=bumpmap.Mesh(positions, uvs[:-1], indices), size=16)
    bad = indices.copy()
    bad[0, 0] = 999
    with pytest.raises(ValueError, match=r"render\(\): the scene's Mesh: triangle 0 uses vertex 999, but there are only 36 vertices"):
        bumpmap.render(scene=bumpmap.Mesh(positions, uvs, bad), size=16)
    with pytest.raises(TypeError, match=r"scene must be a built-in scene's name, \"mesh:FILE\" or a bumpmap.Mesh, not int"):
        bumpmap.render(scene=42, size=16)
    with pytest.raises(ValueError, match="tangents has 3 rows"):
        bumpmap.render(scene=bumpmap.Mesh(positions, uvs, indices, tangents=np.ones((3, 4), np.float32)), size=16)
