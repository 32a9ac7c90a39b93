"""`bumpmap normalmap --roughness-out`: the roughness map engines read, checked against
Filament's roughness prefilter computed here with NumPy from the 16-bit normal map's own
lengths (its alpha), level by level: the formula the code names, computed independently."""

import numpy as np

from conftest import read_png


def filament(perceptual, length):
    """Filament's tools/roughness-prefilter: κ = (3r − r³)/(1 − r²), α′ = √(α² + 2/κ)."""
    alpha = perceptual**2
    r = np.clip(length, 0.0, 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = (3 * r - r**3) / (1 - r**2)
        variance = np.where(r >= 1.0, 0.0, 2.0 / kappa)
    # Perceptual roughness is √α: (α′)^½ = (α² + 2/κ)^¼.
    return np.minimum(np.sqrt(np.sqrt(alpha**2 + variance)), 1.0)


def test_the_roughness_map_is_filaments_prefilter_of_the_normal_maps_lengths(cli, tmp_path):
    normals, rough, orm = tmp_path / "n.png", tmp_path / "r.png", tmp_path / "orm.png"
    cli("normalmap", "dimples", "-o", normals, "--mips", "--bits", "16", "--roughness-out", rough, "--roughness", "0.35")
    cli("normalmap", "dimples", "-o", tmp_path / "n8.png", "--mips", "--roughness-out", orm,
        "--roughness", "0.35", "--roughness-layout", "gltf")
    levels = 0
    rougher = []
    for k in range(9):
        suffix = "" if k == 0 else f".mip{k}"
        n = read_png(tmp_path / f"n{suffix}.png")
        r = read_png(tmp_path / f"r{suffix}.png")
        assert n.dtype == np.uint16 and r.dtype == np.uint8
        want = np.round(filament(0.35, n[..., 3] / 65535.0) * 255.0)
        got = r[..., 0].astype(np.float64)
        assert np.abs(got - want).max() <= 1, f"level {k}"
        assert (r[..., 0] == r[..., 1]).all() and (r[..., 0] == r[..., 2]).all() and (r[..., 3] == 255).all()
        # glTF's metallicRoughness: G roughness, B metallic 0, R 1 (no occlusion).
        o = read_png(tmp_path / f"orm{suffix}.png")
        assert (o[..., 1] == r[..., 1]).all() and (o[..., 2] == 0).all() and (o[..., 0] == 255).all()
        rougher.append(got.mean())
        levels += 1
    assert levels == 9
    assert rougher[0] == round(0.35 * 255), "level 0: every normal alone, the surface's own roughness"
    assert rougher[4] > rougher[0] + 20, f"the smaller levels are rougher where the dimples spread: {rougher}"


def test_render_reads_an_exported_roughness_map(cli, tmp_path):
    """The file `--roughness-out` writes (glTF's ORM layout, KTX2) drawn by `render`'s
    roughness-map technique: nearly the picture of the map the renderer makes itself from the
    normal map, and far from the unfiltered single pass. Shininess 30 is roughness 0.5."""
    import bumpmap

    normals, orm = tmp_path / "n.png", tmp_path / "orm.ktx2"
    cli("normalmap", "dimples@256", "-o", normals, "--mips", "--roughness-out", orm, "--roughness", "0.5",
        "--roughness-layout", "gltf")
    common = dict(backend="cpu", size=96, scene="sphere", eye=(0, -9, 2.5), shininess=30, ambient=0, diffuse=0,
                  normal_map=str(normals))
    read = bumpmap.render(technique="roughness-map", roughness_map=str(orm), roughness_layout="gltf", **common)
    made = bumpmap.render(technique="roughness-map", **common)
    plain = bumpmap.render(technique="single-pass", **common)
    read, made, plain = (a[..., :3].astype(np.float64) for a in (read, made, plain))
    assert (read > 40).sum() > 100, "the highlight is drawn"
    near, far = np.abs(read - made).mean(), np.abs(read - plain).mean()
    assert near < 0.05 and far > 4 * near, (near, far)
