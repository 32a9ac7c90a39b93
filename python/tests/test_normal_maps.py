"""normal_map, mip_chain and read_height_field against `bumpmap normalmap`, byte for byte, and
the arrays they refuse."""

import numpy as np
import pytest

import bumpmap
from conftest import read_png


@pytest.fixture(scope="module")
def heights8(tmp_path_factory):
    """Random 8-bit heights, 48x40 (not square, not a power of two), saved as a PNG by pypng."""
    import png

    rng = np.random.default_rng(3)
    h = (rng.random((40, 48)) * 255).astype(np.uint8)
    path = tmp_path_factory.mktemp("h") / "heights8.png"
    png.from_array(h, "L").save(str(path))
    return path, h


@pytest.fixture(scope="module")
def heights16(tmp_path_factory):
    import png

    y, x = np.mgrid[0:33, 0:31]
    h = ((np.sin(x / 3.0) * np.cos(y / 4.0) * 0.5 + 0.5) * 65535).astype(np.uint16)
    path = tmp_path_factory.mktemp("h") / "heights16.png"
    png.from_array(h, "L;16").save(str(path))
    return path, h


def test_read_height_field_keeps_the_stored_samples(heights8, heights16):
    path, h = heights8
    got = bumpmap.read_height_field(path)
    assert got.dtype == np.uint8 and got.shape == (40, 48)
    assert np.array_equal(got, h)
    path16, h16 = heights16
    got16 = bumpmap.read_height_field(str(path16))
    assert got16.dtype == np.uint16 and np.array_equal(got16, h16)


def test_read_height_field_reads_presets():
    bricks = bumpmap.read_height_field("bricks@64")
    assert bricks.shape == (64, 64)
    assert bricks.dtype == np.float32
    assert 0.0 <= bricks.min() < bricks.max() <= 1.0


@pytest.mark.parametrize(
    "options, flags",
    [
        ({}, []),
        ({"scale": 8, "kernel": "sobel3"}, ["--scale", "8", "--kernel", "sobel3"]),
        ({"wrap": "clamp", "y_convention": "directx", "encoding": "kilgard"},
         ["--wrap", "clamp", "--y-convention", "directx", "--encoding", "kilgard"]),
        ({"scale": -2.5, "kernel": "gaussian7"}, ["--scale", "-2.5", "--kernel", "gaussian7"]),
    ],
)
def test_normal_map_equals_the_cli(tmp_path, cli, heights8, options, flags):
    path, h = heights8
    out = tmp_path / "n.png"
    cli("normalmap", path, "-o", out, *flags)
    expected = read_png(out)
    got = bumpmap.normal_map(bumpmap.read_height_field(path), **options)
    assert got.dtype == np.uint8 and got.shape == (40, 48, 4)
    assert np.array_equal(got, expected)
    # The same heights given as they were made, not as read back: the same result.
    assert np.array_equal(bumpmap.normal_map(h, **options), expected)


def test_sixteen_bits_equals_the_cli(tmp_path, cli, heights16):
    path, h = heights16
    out = tmp_path / "n16.png"
    cli("normalmap", path, "-o", out, "--bits", "16", "--kernel", "central")
    got = bumpmap.normal_map(h, bits=16, kernel="central")
    assert got.dtype == np.uint16
    assert np.array_equal(got, read_png(out))


def test_mip_chain_equals_the_cli(tmp_path, cli, heights8):
    path, h = heights8
    for mode in ["length-in-alpha", "renormalize"]:
        out = tmp_path / f"{mode}.png"
        cli("normalmap", path, "-o", out, "--mips", "--mip-mode", mode, "--scale", "6")
        chain = bumpmap.mip_chain(h, mip_mode=mode, scale=6)
        assert [l.shape[:2] for l in chain] == [(40, 48), (20, 24), (10, 12), (5, 6), (2, 3), (1, 1)]
        for k, level in enumerate(chain):
            name = out if k == 0 else out.with_name(f"{mode}.mip{k}.png")
            assert np.array_equal(level, read_png(name)), f"{mode} level {k}"
        if mode == "length-in-alpha":
            # The length factor: the smaller levels' alpha falls below 255 on bumpy heights.
            assert chain[2][..., 3].min() < 250
        else:
            assert (chain[2][..., 3] == 255).all()


def test_float_heights_equal_the_cli_on_a_preset(tmp_path, cli):
    out = tmp_path / "b.png"
    cli("normalmap", "bricks@64", "-o", out)
    bricks = bumpmap.read_height_field("bricks@64")
    assert np.array_equal(bumpmap.normal_map(bricks), read_png(out))


def test_views_and_byte_order_are_read_by_value(heights8):
    _, h = heights8
    expected = bumpmap.normal_map(h)
    # A transposed view (Fortran order) and a strided slice: read through their strides.
    wide = np.zeros((48, 80), dtype=np.uint8)
    wide[:, ::2][:, :40] = h.T
    view = wide[:, ::2][:, :40].T
    assert not view.flags["C_CONTIGUOUS"]
    assert np.array_equal(bumpmap.normal_map(view), expected)
    # Big-endian float32 and uint16 give the same as native ones.
    f = h.astype(np.float32) / 255.0
    assert np.array_equal(bumpmap.normal_map(f.astype(">f4")), bumpmap.normal_map(f))
    u16 = h.astype(np.uint16) * 257
    assert np.array_equal(bumpmap.normal_map(u16.astype(">u2")), bumpmap.normal_map(u16))


def test_wrong_arrays_are_refused_with_what_was_expected(heights8):
    _, h = heights8
    with pytest.raises(TypeError, match=r"uint8, uint16 or float32.*got float64.*astype\(numpy.float32\)"):
        bumpmap.normal_map(h.astype(np.float64))
    with pytest.raises(TypeError, match=r"got int32"):
        bumpmap.normal_map(h.astype(np.int32))
    with pytest.raises(ValueError, match=r"2-D array.*got shape \[40, 48, 3\]|2-D array.*\(40, 48, 3\)"):
        bumpmap.normal_map(np.zeros((40, 48, 3), dtype=np.uint8))
    with pytest.raises(TypeError, match=r"numpy array.*got list"):
        bumpmap.normal_map([[0, 1], [2, 3]])
    with pytest.raises(ValueError, match="at least 1"):
        bumpmap.normal_map(np.zeros((0, 4), dtype=np.uint8))


def test_bad_options_name_the_keyword(heights8):
    _, h = heights8
    with pytest.raises(ValueError, match=r"normal_map\(\).*'sobel9'.*kernel.*possible values.*sobel3"):
        bumpmap.normal_map(h, kernel="sobel9")
    with pytest.raises(TypeError, match=r"normal_map\(\): scale takes a number, got str") as e:
        bumpmap.normal_map(h, scale="steep")
    assert "--" not in str(e.value)
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'mips'.*it takes: bits, encoding, kernel, scale, wrap, y_convention"):
        bumpmap.normal_map(h, mips=True)
    with pytest.raises(ValueError, match="not 8 or 16"):
        bumpmap.normal_map(h, bits=12)
    with pytest.raises(ValueError, match="scale"):
        bumpmap.normal_map(h, scale=float("nan"))


def test_missing_files_are_os_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="nothing-here.png"):
        bumpmap.read_height_field(tmp_path / "nothing-here.png")
    bad = tmp_path / "not-an-image.png"
    bad.write_bytes(b"hello")
    with pytest.raises(OSError, match="not-an-image.png"):
        bumpmap.read_height_field(bad)


def test_heights_that_cannot_be_differentiated_are_refused():
    for bad in [1e20, -1e20, float("nan"), float("inf")]:
        h = np.full((4, 5), 0.5, dtype=np.float32)
        h[2, 3] = bad
        with pytest.raises(ValueError, match=r"heights\[2, 3\] is .*finite and within ±1e9"):
            bumpmap.normal_map(h)
