"""read_texture: what write_texture wrote comes back level for level, with its format and Y
convention; PNG levels agree with Pillow, an independent reader; bad files are exceptions."""

import numpy as np
import pytest
from PIL import Image

import bumpmap


@pytest.fixture(scope="module")
def chains():
    heights = bumpmap.read_height_field("dimples@32")
    return {
        8: bumpmap.mip_chain(heights),
        16: bumpmap.mip_chain(heights, bits=16),
        "directx": bumpmap.mip_chain(heights, y_convention="directx"),
    }


@pytest.mark.parametrize("ext, bits", [("png", 8), ("png", 16), ("dds", 8), ("dds", 16), ("ktx2", 8), ("ktx2", 16)])
def test_what_write_texture_wrote_comes_back_unchanged(tmp_path, chains, ext, bits):
    chain = chains[bits]
    bumpmap.write_texture(tmp_path / f"n.{ext}", chain)
    got = bumpmap.read_texture(tmp_path / f"n.{ext}")
    assert got["format"] == ("rgba16" if bits == 16 else "rgba8")
    assert len(got["levels"]) == len(chain) == 6
    for k, (a, b) in enumerate(zip(got["levels"], chain)):
        assert a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b), f"level {k}"
    assert got["y_convention"] == "opengl"


def test_png_levels_are_what_pillow_reads(tmp_path, chains):
    bumpmap.write_texture(tmp_path / "n.png", chains[8])
    got = bumpmap.read_texture(tmp_path / "n.png")["levels"]
    for k, level in enumerate(got):
        path = tmp_path / ("n.png" if k == 0 else f"n.mip{k}.png")
        assert np.array_equal(level, np.asarray(Image.open(path).convert("RGBA"))), f"level {k}"


@pytest.mark.parametrize("fmt", ["bc5", "bc7"])
def test_compressed_levels_are_what_pillow_decodes_and_the_y_convention_is_told(tmp_path, chains, fmt):
    bumpmap.write_texture(tmp_path / "n.dds", chains["directx"], format=fmt)
    got = bumpmap.read_texture(tmp_path / "n.dds")
    assert got["format"] == fmt and got["y_convention"] == "directx"
    ours = got["levels"][0].astype(np.int32)
    pillow = np.asarray(Image.open(tmp_path / "n.dds").convert("RGBA")).astype(np.int32)
    if fmt == "bc7":
        assert np.array_equal(ours, pillow)
    else:
        # BC5's interpolated steps, (6a + b)/7, round one way or the other: within 1.
        assert np.abs(ours[..., :2] - pillow[..., :2]).max() <= 1
        # BC5 stores X and Y; Z is rebuilt as sqrt(1 - x² - y²) (Pillow leaves blue 0).
        x, y = (ours[..., 0] / 255 * 2 - 1), (ours[..., 1] / 255 * 2 - 1)
        z = np.sqrt(np.clip(1 - x * x - y * y, 0, 1))
        assert np.abs(ours[..., 2] - (z * 0.5 + 0.5) * 255).max() <= 1


def test_a_flat_map_has_no_y_convention_to_tell(tmp_path):
    flat = np.full((16, 16, 4), (128, 128, 255, 255), np.uint8)
    bumpmap.write_texture(tmp_path / "flat.png", flat)
    assert bumpmap.read_texture(tmp_path / "flat.png")["y_convention"] is None


def test_bad_files_are_exceptions_naming_them(tmp_path, chains):
    with pytest.raises(FileNotFoundError, match="missing.png"):
        bumpmap.read_texture(tmp_path / "missing.png")
    (tmp_path / "junk.ktx2").write_bytes(b"\xabKTX 20\xbb\r\n\x1a\n" + b"\0" * 20)
    with pytest.raises(OSError, match="junk.ktx2"):
        bumpmap.read_texture(tmp_path / "junk.ktx2")
    # A level beside a PNG that is not the next size.
    bumpmap.write_texture(tmp_path / "n.png", chains[8])
    Image.new("RGBA", (3, 3)).save(tmp_path / "n.mip2.png")
    with pytest.raises(OSError, match=r"n.mip2.png.*must be 8x8"):
        bumpmap.read_texture(tmp_path / "n.png")
