"""Heights as geometry from Python: height_mips against `normalmap --height-out`'s files (PNG read
by pypng, KTX2 and DDS read here from their specifications), its min–max levels against a
Catmull-Rom interpolant written here in NumPy, and render's heights options against `bumpmap
render`, byte for byte."""

import struct

import numpy as np
import pytest

import bumpmap
from conftest import read_png


def catmull_rom(t):
    """The four Catmull-Rom weights at t in [0, 1), written out independently of bumpmap."""
    t2, t3 = t * t, t * t * t
    return np.array([(-t3 + 2 * t2 - t) / 2, (3 * t3 - 5 * t2 + 2) / 2, (-3 * t3 + 4 * t2 + t) / 2, (t3 - t2) / 2])


def interpolant(heights, i, j, fx, fy):
    """The C1 interpolant in cell (i, j) (between the texel centres i+1/2 and i+3/2, j likewise)
    at the fraction (fx, fy) across it; the heights repeat."""
    h, w = heights.shape
    rows = [(j - 1 + b) % h for b in range(4)]
    cols = [(i - 1 + a) % w for a in range(4)]
    patch = heights[np.ix_(rows, cols)].astype(np.float64)
    return catmull_rom(fy) @ patch @ catmull_rom(fx)


@pytest.fixture(scope="module")
def bricks():
    return bumpmap.read_height_field("bricks@32")


def test_height_mips_are_what_height_out_writes(tmp_path, cli, bricks):
    cli("normalmap", "bricks@32", "-o", tmp_path / "n.png", "--mips", "--bits", "16", "--height-out", tmp_path / "h.png")
    levels, minmax = bumpmap.height_mips(bricks, bits=16)
    assert [l.shape for l in levels] == [(32 >> k, 32 >> k) for k in range(6)]
    assert [m.shape for m in minmax] == [(32 >> k, 32 >> k, 2) for k in range(6)]
    assert all(l.dtype == np.float32 for l in levels + minmax)
    for k, level in enumerate(levels):
        stored = read_png(tmp_path / ("h.png" if k == 0 else f"h.mip{k}.png"))
        assert stored.dtype == np.uint16 and stored.shape == level.shape + (1,)
        # Rounded to the nearest of 65535 steps (in float32, whose own rounding at 0.5 is ±0.005).
        assert np.abs(level.astype(np.float64) * 65535 - stored[..., 0]).max() <= 0.505, f"level {k}"
        # Each smaller level is the mean of the four texels it covers.
        if k > 0:
            below = levels[k - 1]
            means = (below[0::2, 0::2] + below[1::2, 0::2] + below[0::2, 1::2] + below[1::2, 1::2]) / 4
            assert np.allclose(level, means, atol=1e-6), f"level {k}"
    for k, bounds in enumerate(minmax):
        stored = read_png(tmp_path / ("h.minmax.png" if k == 0 else f"h.minmax.mip{k}.png")).astype(np.float64) / 65535
        assert stored.shape == bounds.shape[:2] + (3,)
        # Rounded outward: the file's bounds hold ours.
        assert (stored[..., 0] <= bounds[..., 0] + 1e-7).all() and (stored[..., 1] >= bounds[..., 1] - 1e-7).all()
        assert np.abs(stored[..., :2] - bounds).max() <= 1 / 65535 + 1e-7
        if k > 0:
            below = minmax[k - 1]
            blocks = [below[y::2, x::2] for y in (0, 1) for x in (0, 1)]
            assert np.array_equal(bounds[..., 0], np.minimum.reduce([b[..., 0] for b in blocks]))
            assert np.array_equal(bounds[..., 1], np.maximum.reduce([b[..., 1] for b in blocks]))


def test_the_min_max_bounds_hold_the_interpolant(bricks):
    levels, minmax = bumpmap.height_mips(bricks)
    level0, bounds = levels[0], minmax[0]
    fractions = np.linspace(0, 1, 7, endpoint=False)
    tight = 0
    for j in range(level0.shape[0]):
        for i in range(level0.shape[1]):
            values = np.clip([interpolant(level0, i, j, fx, fy) for fy in fractions for fx in fractions], 0, 1)
            lo, hi = bounds[j, i]
            assert lo - 1e-5 <= values.min() and values.max() <= hi + 1e-5, f"cell ({i}, {j})"
            tight += hi - lo < 1e-6
    # Not vacuous: the bricks' flat tops and mortar give cells whose bounds are one height.
    assert 0 < tight < level0.size
    assert (bounds[..., 1] - bounds[..., 0]).max() > 0.1


def test_render_with_heights_equals_the_cli(tmp_path, cli):
    out = tmp_path / "r.png"
    flags = ["--scene", "wall", "--technique", "pom", "--size", "48", "--eye", "0,-1.1,0.5", "--depth", "0.05",
             "--layers", "16", "--parallax-shadow", "hard", "--light", "dir:1,0,0.3"]
    cli("render", "-o", out, *flags)
    got = bumpmap.render(scene="wall", technique="pom", size=48, eye=(0, -1.1, 0.5), depth=0.05, layers=16,
                         parallax_shadow="hard", light="dir:1,0,0.3")
    assert np.array_equal(got[..., :3], read_png(out))
    assert (got[..., :3].max(axis=2) > 40).mean() > 0.2
    unshadowed = bumpmap.render(scene="wall", technique="pom", size=48, eye=(0, -1.1, 0.5), depth=0.05, layers=16,
                                light="dir:1,0,0.3")
    assert got[..., :3].mean() < unshadowed[..., :3].mean()


def test_a_height_map_file_renders(tmp_path, cli):
    cli("normalmap", "dimples@64", "-o", tmp_path / "n.png", "--mips", "--height-out", tmp_path / "h.ktx2")
    flags = ["--scene", "wall", "--technique", "height-exact", "--size", "40", "--normal-map", tmp_path / "n.png",
             "--height-map", tmp_path / "h.ktx2"]
    cli("render", "-o", tmp_path / "r.png", *flags)
    got = bumpmap.render(scene="wall", technique="height-exact", size=40, normal_map=tmp_path / "n.png",
                         height_map=tmp_path / "h.ktx2")
    assert np.array_equal(got[..., :3], read_png(tmp_path / "r.png"))
    # Not two black images: the lit wall covers most of the frame.
    assert (got[..., :3].max(axis=2) > 40).mean() > 0.2


def test_heights_errors_are_exceptions(tmp_path):
    with pytest.raises(ValueError, match=r"render\(\): depth: '0' is not a depth: give a positive number of the scene's units"):
        bumpmap.render(technique="pom", depth=0)
    with pytest.raises(ValueError, match=r"render\(\): layers: 999 is not in 1\.\.=256"):
        bumpmap.render(technique="pom", layers=999)
    with pytest.raises(ValueError, match=r"parallax_shadow.*possible values: off, hard, soft, horizon"):
        bumpmap.render(technique="pom", parallax_shadow="sharp")
    (normals,) = bumpmap.write_texture(tmp_path / "n.png", bumpmap.normal_map(bumpmap.read_height_field("bricks@16")))
    with pytest.raises(FileNotFoundError, match=r"missing\.png"):
        bumpmap.render(technique="pom", normal_map=normals, height_map=tmp_path / "missing.png")
    with pytest.raises(ValueError, match=r"heights must be a 2-D array"):
        bumpmap.height_mips(np.zeros((4, 4, 3), np.float32))
    with pytest.raises(ValueError, match=r"bits"):
        bumpmap.height_mips(np.zeros((4, 4), np.float32), bits=12)


# Independent readers of the two containers, from their specifications (not bumpmap's reader).
VK_FORMATS = {9: ("R8_UNORM", "u1", 1), 70: ("R16_UNORM", "<u2", 1), 77: ("R16G16_UNORM", "<u2", 2)}
DXGI_FORMATS = {61: ("R8_UNORM", "u1", 1), 56: ("R16_UNORM", "<u2", 1), 35: ("R16G16_UNORM", "<u2", 2)}


def read_ktx2(path):
    """KTX 2.0: the identifier, the header, the level index (level 0 first in the index, the data
    laid out smallest first), each level where the index says, aligned as §3.9.7 requires, and
    the data format descriptor's texel size."""
    data = path.read_bytes()
    assert data[:12] == b"\xabKTX 20\xbb\r\n\x1a\n"
    vk, type_size, width, height, depth, layers, faces, levels, scheme = struct.unpack_from("<9I", data, 12)
    name, dtype, channels = VK_FORMATS[vk]
    assert (depth, layers, faces, scheme) == (0, 0, 1, 0)
    assert type_size == np.dtype(dtype).itemsize
    dfd_offset, dfd_length = struct.unpack_from("<2I", data, 48)
    # The basic descriptor block (after the DFD's total size): texel blocks of 1x1x1x1 (stored
    # minus one) and bytesPlane0, one texel's size.
    block = dfd_offset + 4
    assert dfd_length >= 4 + 24 and data[block + 12 : block + 16] == b"\0\0\0\0", name
    assert data[block + 16] == type_size * channels, name
    texel = type_size * channels
    align = texel * 4 // np.gcd(texel, 4)
    out = []
    for k in range(levels):
        offset, length, raw = struct.unpack_from("<3Q", data, 80 + 24 * k)
        w, h = max(width >> k, 1), max(height >> k, 1)
        assert length == raw == w * h * texel and offset % align == 0 and offset + length <= len(data)
        out.append(np.frombuffer(data, dtype=dtype, count=w * h * channels, offset=offset).reshape(h, w, channels))
    return name, out


def read_dds(path):
    """DDS with the DX10 header: every level of one 2D surface, level 0 first."""
    data = path.read_bytes()
    assert data[:4] == b"DDS " and data[84:88] == b"DX10"
    height, width, _, _, levels = struct.unpack_from("<5I", data, 12)
    name, dtype, channels = DXGI_FORMATS[struct.unpack_from("<I", data, 128)[0]]
    assert struct.unpack_from("<I", data, 132)[0] == 3, "D3D10_RESOURCE_DIMENSION_TEXTURE2D"
    offset, out = 148, []
    for k in range(levels):
        w, h = max(width >> k, 1), max(height >> k, 1)
        out.append(np.frombuffer(data, dtype=dtype, count=w * h * channels, offset=offset).reshape(h, w, channels))
        offset += w * h * channels * np.dtype(dtype).itemsize
    assert offset == len(data)
    return name, out


@pytest.mark.parametrize("ext, bits", [("ktx2", 16), ("ktx2", 8), ("dds", 16), ("dds", 8)])
def test_heights_containers_mean_what_their_formats_say(tmp_path, cli, bricks, ext, bits):
    cli("normalmap", "bricks@32", "-o", tmp_path / "n.png", "--mips", "--bits", bits, "--height-out",
        tmp_path / f"h.{ext}")
    levels, minmax = bumpmap.height_mips(bricks, bits=bits)
    read = read_ktx2 if ext == "ktx2" else read_dds
    name, stored = read(tmp_path / f"h.{ext}")
    assert name == ("R16_UNORM" if bits == 16 else "R8_UNORM")
    top = 65535 if bits == 16 else 255
    assert len(stored) == len(levels) == 6
    for k, (ours, theirs) in enumerate(zip(levels, stored)):
        assert np.abs(ours.astype(np.float64) * top - theirs[..., 0]).max() <= 0.505, f"level {k}"
    name, bounds = read(tmp_path / f"h.minmax.{ext}")
    assert name == "R16G16_UNORM" and len(bounds) == len(minmax)
    for k, (ours, theirs) in enumerate(zip(minmax, bounds)):
        theirs = theirs.astype(np.float64) / 65535
        # Rounded outward, within one step.
        assert (theirs[..., 0] <= ours[..., 0] + 1e-7).all() and (theirs[..., 1] >= ours[..., 1] - 1e-7).all(), k
        assert np.abs(theirs - ours).max() <= 1 / 65535 + 1e-7, k


@pytest.mark.parametrize("ext, bits", [("png", 16), ("png", 8), ("ktx2", 16), ("dds", 8)])
def test_write_heights_writes_the_files_height_out_writes(tmp_path, cli, bricks, ext, bits):
    cli("normalmap", "bricks@32", "-o", tmp_path / "n.png", "--mips", "--bits", bits, "--height-out",
        tmp_path / "cli" / f"h.{ext}")
    written = bumpmap.write_heights(tmp_path / "py" / f"h.{ext}", bricks, bits=bits)
    theirs = sorted(p.name for p in (tmp_path / "cli").iterdir())
    # Six levels of heights and six of bounds as PNGs; one file of each in a container.
    assert len(theirs) == (12 if ext == "png" else 2)
    assert sorted(p.name for p in written) == theirs
    assert all(p.parent == tmp_path / "py" for p in written)
    for name in theirs:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_write_heights_are_read_back_by_render(tmp_path, bricks):
    (normals,) = bumpmap.write_texture(tmp_path / "n.png", bumpmap.normal_map(bricks))
    heights = bumpmap.write_heights(tmp_path / "h.ktx2", bricks, bits=16)
    got = bumpmap.render(scene="wall", technique="height-exact", size=40, normal_map=normals, height_map=heights[0])
    # Drawn by the exact walk over the written bounds, not refused and not black.
    assert (got[..., :3].max(axis=2) > 40).mean() > 0.2


def test_write_heights_refuses_before_writing_anything(tmp_path, bricks):
    with pytest.raises(OSError, match=r"h\.jpg.*unsupported output format.*\.png, \.dds or \.ktx2"):
        bumpmap.write_heights(tmp_path / "h.jpg", bricks)
    with pytest.raises(ValueError, match=r"bits"):
        bumpmap.write_heights(tmp_path / "h.png", bricks, bits=12)
    with pytest.raises(ValueError, match=r"heights must be a 2-D array"):
        bumpmap.write_heights(tmp_path / "h.png", np.zeros((4, 4, 3), np.float32))
    # A folder where the bounds would go: the set fails as a whole, none of its files stays.
    (tmp_path / "h.minmax.png").mkdir()
    with pytest.raises(OSError, match=r"h\.minmax\.png"):
        bumpmap.write_heights(tmp_path / "h.png", bricks)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["h.minmax.png"]
