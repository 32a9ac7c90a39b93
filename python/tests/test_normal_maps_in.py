"""Normal maps made elsewhere, from Python: inspect() says what `bumpmap inspect --json` says,
on files and on arrays; height_from_normals() gives what `bumpmap height` writes, and gets the
heights back from maps made here (the slopes re-derived in NumPy, not by bumpmap)."""

import json

import numpy as np
import pytest

import bumpmap
from conftest import read_png


def normals_numpy(heights, scale, y_up):
    """A forward-difference normal map of periodic heights, in float32 −1..1, written here in
    NumPy: n ∝ (−s·∂h/∂x, −s·∂h/∂y, 1), ∂ toward the next column and row, green negated for Y up."""
    dx = np.roll(heights, -1, axis=1) - heights
    dy = np.roll(heights, -1, axis=0) - heights
    n = np.stack([-scale * dx, -scale * dy, np.ones_like(heights)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    if y_up:
        n[..., 1] *= -1
    return n.astype(np.float32)


def smooth_heights(h, w):
    y, x = np.mgrid[0:h, 0:w].astype(np.float64)
    t = 2 * np.pi
    return (0.5 + 0.25 * np.sin(t * x / w) * np.cos(2 * t * y / h) + 0.2 * np.cos(t * (3 * x / w + y / h))).astype(
        np.float32
    )


def test_inspect_on_a_file_is_what_the_command_line_says(tmp_path, cli):
    path = tmp_path / "n.png"
    cli("normalmap", "dimples@64", "-o", path, "--y-convention", "directx", "--kernel", "sobel3")
    report = bumpmap.inspect(path)
    printed = json.loads(cli("inspect", "--json", path).stdout)[0]
    assert report == printed
    assert report["convention"]["verdict"] == "directx"
    assert report["convention"]["made_with"] == "sobel3"
    assert report["normal_map"] is True
    assert report["findings"] == []


def test_inspect_on_arrays_in_every_dtype_and_layout(tmp_path, cli):
    path = tmp_path / "n.png"
    cli("normalmap", "bricks@64", "-o", path, "--y-convention", "opengl")
    rgba = read_png(path)  # by pypng
    from_file = bumpmap.inspect(path)
    as_u8 = bumpmap.inspect(rgba)
    assert as_u8["convention"] == from_file["convention"]
    assert as_u8["file"] == "array"
    # Three channels, a Fortran-ordered copy, float32 in −1..1 and uint16: the same verdict.
    rgb = np.asfortranarray(rgba[..., :3])
    assert bumpmap.inspect(rgb)["convention"]["verdict"] == "opengl"
    signed = (rgba[..., :3].astype(np.float32) / 127.5 - 1.0).astype(np.float32)
    report = bumpmap.inspect(signed)
    assert report["stored"] == "float-signed" and report["convention"]["verdict"] == "opengl"
    wide = rgba.astype(np.uint16) * 257
    assert bumpmap.inspect(wide)["stored"] == "unorm16"


def test_inspect_tells_a_colour_photo_and_a_gray_map_from_normal_maps():
    rng = np.random.default_rng(3)
    photo = rng.integers(0, 256, size=(48, 48, 3), dtype=np.uint8)
    assert bumpmap.inspect(photo)["normal_map"] is False
    gray = np.repeat(rng.integers(0, 256, size=(48, 48, 1), dtype=np.uint8), 3, axis=2)
    report = bumpmap.inspect(gray)
    assert report["kind"] == "gray" and report["findings"]


def test_inspect_refuses_what_it_cannot_read(tmp_path):
    with pytest.raises(FileNotFoundError, match="missing.png"):
        bumpmap.inspect(tmp_path / "missing.png")
    with pytest.raises(ValueError, match="shape"):
        bumpmap.inspect(np.zeros((8, 8), np.uint8))
    with pytest.raises(TypeError, match="float64"):
        bumpmap.inspect(np.zeros((8, 8, 3)))
    with pytest.raises(TypeError, match="path or a numpy array"):
        bumpmap.inspect(42)


@pytest.mark.parametrize("y_up", [True, False])
def test_height_from_normals_gives_the_heights_back(y_up):
    heights = smooth_heights(48, 64)
    normals = normals_numpy(heights.astype(np.float64), 4.0, y_up)
    got = bumpmap.height_from_normals(normals, scale=4.0, raw=True)
    assert got.dtype == np.float32 and got.shape == (48, 64)
    err = (got - got.mean()) - (heights - heights.mean())
    rms = float(np.sqrt((err**2).mean()))
    span = float(heights.max() - heights.min())
    assert rms < 1e-3 * span, f"rms {rms} of a span {span}"
    # Mapped onto 0..1 by default.
    unit = bumpmap.height_from_normals(normals)
    assert unit.min() == 0.0 and unit.max() == 1.0


def test_height_from_normals_is_what_the_command_line_writes(tmp_path, cli):
    path, out = tmp_path / "n.png", tmp_path / "h.png"
    cli("normalmap", "pinwheel@48", "-o", path, "--bits", "16")
    cli("height", path, "-o", out)
    written = read_png(out)[..., 0].astype(np.float64) / 65535.0
    got = bumpmap.height_from_normals(read_png(path))
    assert np.abs(got - written).max() <= 0.5 / 65535 + 1e-6


def test_height_from_normals_refuses_bad_values():
    normals = normals_numpy(smooth_heights(16, 16).astype(np.float64), 4.0, True)
    with pytest.raises(ValueError, match="scale"):
        bumpmap.height_from_normals(normals, scale=0.0)
    with pytest.raises(ValueError, match="kernel"):
        bumpmap.height_from_normals(normals, method="kernel")
    with pytest.raises(ValueError, match="kernel='spectral' is none: use method='fft'"):
        bumpmap.height_from_normals(normals, method="kernel", kernel="spectral")
    with pytest.raises(ValueError, match=r"from 1e-6 to 1e6 in size"):
        bumpmap.height_from_normals(normals, scale=1e-35)
    with pytest.raises(ValueError, match="1x1"):
        bumpmap.height_from_normals(np.full((1, 1, 3), 128, np.uint8))
    bad = normals.copy()
    bad[3, 5, 0] = np.nan
    with pytest.raises(ValueError, match=r"\(5, 3\) is not a number"):
        bumpmap.height_from_normals(bad)
    with pytest.raises(TypeError, match="unexpected keyword"):
        bumpmap.height_from_normals(normals, bits=8)
    with pytest.raises(ValueError, match="kernel; possible values: auto, spectral, forward"):
        bumpmap.height_from_normals(normals, kernel="sobel")
    with pytest.raises(TypeError, match="method takes a string"):
        bumpmap.height_from_normals(normals, method=2)
    with pytest.raises(TypeError, match="raw is True or False"):
        bumpmap.height_from_normals(normals, raw="yes")


def test_height_from_normals_reads_typed_keywords(tmp_path, cli):
    """Each keyword means what the flag of the same name means: the heights are those `bumpmap
    height` writes with it (a kernel undone exactly, a convention given, a boundary)."""
    path = tmp_path / "n.png"
    cli("normalmap", "pinwheel@48", "-o", path, "--bits", "16", "--kernel", "sobel3", "--y-convention", "directx",
        "--scale", "4")
    normals = read_png(path)
    for keywords, flags in [
        (dict(method="kernel", kernel="sobel3", scale=4, y_convention="directx"),
         ["--method", "kernel", "--kernel", "sobel3", "--scale", "4", "--y-convention", "directx"]),
        (dict(method="dct", kernel="spectral", y_convention="y-down"),
         ["--method", "dct", "--kernel", "spectral", "--y-convention", "directx"]),
    ]:
        out = tmp_path / "h.png"
        cli("height", path, "-o", out, *flags)
        written = read_png(out)[..., 0].astype(np.float64) / 65535.0
        got = bumpmap.height_from_normals(normals, **keywords)
        assert np.abs(got - written).max() <= 0.5 / 65535 + 1e-6, keywords


def test_fortran_ordered_and_strided_arrays_read_as_their_c_copies():
    # Every array input goes through one reader; a Fortran-ordered array was once read in its
    # memory order.
    heights = smooth_heights(24, 40)
    for view in (np.asfortranarray(heights), heights[:, ::-1].copy()[:, ::-1], heights.T.copy().T):
        assert np.array_equal(bumpmap.normal_map(view), bumpmap.normal_map(np.ascontiguousarray(view)))
    rgba = bumpmap.normal_map(heights)
    fortran = np.asfortranarray(rgba)
    assert bumpmap.inspect(fortran) == bumpmap.inspect(rgba)
