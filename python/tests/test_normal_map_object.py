"""`bumpmap.NormalMap`: a map's levels and Y convention kept together. It holds what the
functions make and read (level for level), writes and reads itself back, and draws exactly as its
levels given with its convention, or as the file it was written to."""

import numpy as np
import pytest

import bumpmap


@pytest.fixture(scope="module")
def heights():
    return bumpmap.read_height_field("bricks@64")


def test_made_from_heights_it_holds_the_chain(heights):
    nm = bumpmap.NormalMap.from_heights(heights, scale=6, kernel="sobel3")
    chain = bumpmap.mip_chain(heights, scale=6, kernel="sobel3")
    assert len(nm) == len(chain) == 7 and all(np.array_equal(a, b) for a, b in zip(nm.levels, chain))
    assert nm.size == (64, 64) and nm.y_convention == "opengl"
    one = bumpmap.NormalMap.from_heights(heights, mips=False, bits=16, y_convention="directx")
    assert len(one) == 1 and one.levels[0].dtype == np.uint16 and one.y_convention == "directx"
    assert repr(one) == "NormalMap(64x64, 1 levels, uint16, directx)"


def test_written_and_read_back_it_is_the_same_map_with_its_convention(heights, tmp_path):
    nm = bumpmap.NormalMap.from_heights(heights, scale=6, y_convention="directx")
    written = nm.write(tmp_path / "n.ktx2")
    back = bumpmap.NormalMap.read(written[0])
    assert back.y_convention == "directx", "told from the texels by the curl test"
    assert all(np.array_equal(a, b) for a, b in zip(nm.levels, back.levels))
    assert nm.inspect()["convention"]["verdict"] == "directx"
    # Integrated with its own convention: the heights come back (up to the offset and scale
    # heights lose), correlated with the ones it was made from.
    h = nm.heights()
    assert h.shape == (64, 64) and np.corrcoef(h.ravel(), heights.ravel())[0, 1] > 0.9


def test_it_draws_as_its_levels_and_as_its_file(heights, tmp_path):
    nm = bumpmap.NormalMap.from_heights(heights, scale=6, y_convention="directx")
    nm.write(tmp_path / "n.ktx2")  # every level in one file, as render reads them
    options = dict(scene="sphere", technique="single-pass", size=96)
    drawn = bumpmap.render(normal_map=nm, **options)
    assert np.array_equal(drawn, bumpmap.render(normal_map=nm.levels, y_convention="directx", **options))
    assert np.array_equal(drawn, bumpmap.render(normal_map=tmp_path / "n.ktx2", y_convention="directx", **options))
    # Read with the wrong convention, the bumps light from the other side: a different image.
    assert not np.array_equal(drawn, bumpmap.render(normal_map=nm.levels, **options))
    with bumpmap.Renderer("cpu") as r:
        assert np.array_equal(drawn, r.render(normal_map=nm, **options))


def test_wrong_input_is_a_clear_exception(tmp_path):
    with pytest.raises(ValueError, match="levels is empty"):
        bumpmap.NormalMap([])
    with pytest.raises(ValueError, match="y_convention must be 'opengl' or 'directx', not 'up'"):
        bumpmap.NormalMap(np.zeros((4, 4, 4), np.uint8), "up")
    flat = np.full((16, 16, 4), (128, 128, 255, 255), np.uint8)
    bumpmap.write_texture(tmp_path / "flat.png", flat)
    with pytest.raises(ValueError, match="do not tell OpenGL from DirectX"):
        bumpmap.NormalMap.read(tmp_path / "flat.png")
    assert bumpmap.NormalMap.read(tmp_path / "flat.png", y_convention="opengl").y_convention == "opengl"
