"""`bumpmap normalmap --lean-out`: LEAN mapping's moments, checked against the same moments
computed here with NumPy from the 8-bit normal map the command writes beside them: level 0 texel
by texel, and each smaller level as the mean of the level-0 texels it covers. The DDS is read by
hand from its header (DX10, R32G32B32A32_FLOAT), not by bumpmap."""

import struct

import numpy as np

from conftest import read_png

MIN_NZ = 0.1  # bumpmap_math::lean::MIN_NZ: steeper normals are read at slope 10


def read_float_dds(path):
    data = path.read_bytes()
    assert data[:4] == b"DDS " and data[84:88] == b"DX10"
    height, width, _, _, levels = struct.unpack_from("<5I", data, 12)
    assert struct.unpack_from("<I", data, 128)[0] == 2, "DXGI_FORMAT_R32G32B32A32_FLOAT"
    offset, out = 148, []
    for k in range(levels):
        w, h = max(width >> k, 1), max(height >> k, 1)
        out.append(np.frombuffer(data, dtype="<f4", count=w * h * 4, offset=offset).reshape(h, w, 4))
        offset += w * h * 16
    assert offset == len(data)
    return out


def test_the_lean_moments_are_the_normal_maps_slopes_and_their_means(cli, tmp_path):
    cli("normalmap", "dimples@64", "--mips", "-o", tmp_path / "n.png", "--lean-out", tmp_path / "l.dds")
    first, second = read_float_dds(tmp_path / "l.dds"), read_float_dds(tmp_path / "l.mxy-j.dds")
    assert len(first) == len(second) == 7
    texels = read_png(tmp_path / "n.png")[..., :3].astype(np.float64)
    n = texels * (2.0 / 255.0) - 1.0  # Encoding::Unorm's inverse (expand_normal)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    z = np.maximum(n[..., 2], MIN_NZ)
    bx, by = n[..., 0] / z, n[..., 1] / z
    moments = np.stack([bx, by, bx * bx, by * by, bx * by, 1.0 / z**3], axis=-1)
    for k in range(7):
        s = 1 << k
        want = moments.reshape(64 // s, s, 64 // s, s, 6).mean(axis=(1, 3))
        got = np.concatenate([first[k], second[k][..., :2]], axis=-1)
        assert np.allclose(got, want, rtol=1e-4, atol=1e-5), f"level {k}: {np.abs(got - want).max()}"
        assert (second[k][..., 2:] == 0).all()
        # M − BBᵀ is a covariance: never negative on the diagonal.
        assert (got[..., 2] - got[..., 0] ** 2 >= -1e-5).all() and (got[..., 3] - got[..., 1] ** 2 >= -1e-5).all()
    top = first[6][0, 0]
    assert top[2] - top[0] ** 2 > 0.05, "the dimples' slopes spread at the 1x1 level"
