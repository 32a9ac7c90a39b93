"""render's (and compare's and the map functions') keywords as Python values, read into the library's typed options without a command
line in between: every documented keyword is read, its default is the library's, vectors are
tuples, lights are strings, tuples or dicts, and each wrong value is the exception that names it."""

import inspect

import numpy as np
import pytest

import bumpmap
from bumpmap import _bumpmap
from conftest import read_png

# Keywords that mean something only beside another (refused alone, as the command line refuses
# them), and the frame's size, which is checked apart from its width and height.
NEEDS_ANOTHER = {"y_convention", "spot_cutoff", "spot_exponent", "roughness_layout",
                 "detail_repeat", "detail_method", "detail_strength"}


@pytest.mark.parametrize("function", ["render", "compare", "normal_map", "mip_chain", "height_mips", "horizon_maps",
                                      "roughness_map", "lean_moments", "read_height_field", "tangents",
                                      "write_texture", "height_from_normals"])
def test_every_documented_keyword_is_read(function):
    documented = {name for name, *_ in _bumpmap.options(function)}
    assert documented == set(_bumpmap.keywords(function))


def test_the_signature_lists_every_keyword():
    documented = {name for name, *_ in _bumpmap.options("render")}
    signature = inspect.signature(bumpmap.render)
    assert set(signature.parameters) == documented | {"progress"}


def test_each_default_given_draws_what_no_keyword_draws():
    """A keyword given its signature's default changes nothing: the defaults the docs show are
    the ones the library uses (a default wrong by one value, say fov 46, fails here)."""
    plain = bumpmap.render(size=24)
    checked = 0
    for name, param in inspect.signature(bumpmap.render).parameters.items():
        if param.default in (None, False) or name in NEEDS_ANOTHER or name in ("size", "progress"):
            continue
        got = bumpmap.render(size=24, **{name: param.default})
        assert np.array_equal(got, plain), f"{name}={param.default!r} is not the default"
        checked += 1
    assert checked >= 20
    assert inspect.signature(bumpmap.render).parameters["torus_radii"].default == (2.0, 0.7)


def test_vectors_are_any_sequence_of_numbers():
    base = dict(scene="wall", technique="pom", size=32)
    as_tuple = bumpmap.render(eye=(0, -3, 1.2), **base)
    assert np.array_equal(as_tuple, bumpmap.render(eye=[0, -3, 1.2], **base))
    assert np.array_equal(as_tuple, bumpmap.render(eye=np.array([0, -3, 1.2], np.float32), **base))
    assert np.array_equal(as_tuple, bumpmap.render(eye=(np.float64(0), -3, 1.2), **base))
    assert not np.array_equal(as_tuple, bumpmap.render(eye=(0, -3, 2.5), **base))


def test_lights_as_strings_tuples_and_dicts_are_the_same_lights(tmp_path, cli):
    base = dict(scene="sphere", technique="single-pass", size=40)
    cli("render", "--scene", "sphere", "--technique", "single-pass", "--size", "40", "--light", "4,0,3@1,0.6,0.4",
        "--light", "dir:-1,0,1", "-o", tmp_path / "r.png")
    expected = read_png(tmp_path / "r.png")
    for lights in (
        ["4,0,3@1,0.6,0.4", "dir:-1,0,1"],
        [{"position": (4, 0, 3), "color": (1, 0.6, 0.4)}, {"direction": (-1, 0, 1)}],
        ({"position": [4, 0, 3], "color": [1, 0.6, 0.4]}, "dir:-1,0,1"),
        iter(["4,0,3@1,0.6,0.4", {"direction": (-2, 0, 2)}]),
    ):
        got = bumpmap.render(light=lights, **base)
        assert np.array_equal(got[..., :3], expected), lights
    one = bumpmap.render(light=(4, 0, 3), **base)
    assert np.array_equal(one, bumpmap.render(light="4,0,3", **base))
    assert np.array_equal(one, bumpmap.render(light=[(4, 0, 3)], **base))
    assert np.array_equal(one, bumpmap.render(light={"position": (4, 0, 3)}, **base))


def test_attenuation_as_a_tuple_or_its_notation():
    base = dict(scene="wall", technique="single-pass", size=32, light=(0, -1, 2))
    as_text = bumpmap.render(attenuation="1,0.2,0.05", **base)
    assert np.array_equal(as_text, bumpmap.render(attenuation=(1, 0.2, 0.05), **base))
    assert not np.array_equal(as_text, bumpmap.render(**base))


def test_wrong_values_name_the_keyword():
    cases = [
        (TypeError, r"render\(\): eye takes 3 numbers \(a tuple\), got str", dict(eye="0,-3,1")),
        (ValueError, r"render\(\): eye: takes 3 numbers, got 2", dict(eye=(0, 1))),
        (ValueError, r"eye must be three finite numbers, got NaN,0\.0,1\.0", dict(eye=(float("nan"), 0, 1))),
        (TypeError, r"render\(\): spp takes a whole number, got float", dict(spp=2.5)),
        (TypeError, r"render\(\): ambient takes a number, got str", dict(ambient="0.3")),
        (TypeError, r"render\(\): ambient takes a number, got bool", dict(ambient=True)),
        (ValueError, r"ambient must be in \[0, 1\], got 1\.5", dict(ambient=1.5)),
        (ValueError, r"invalid value 'kilgrad' for technique; possible values: kilgard, single-pass", dict(technique="kilgrad")),
        (TypeError, r"render\(\): filter takes a string, got int", dict(filter=3)),
        (ValueError, r"render\(\): tessellation: '0' is not a count in 1\.\.=2048", dict(tessellation=(0, 5))),
        (ValueError, r"render\(\): tessellation: '2\.5' is not a count in 1\.\.=2048", dict(tessellation=(2.5, 5))),
        (ValueError, r"render\(\): repeat: repeats must be non-zero and within ±1024, got '0,2'", dict(repeat=(0, 2))),
        (ValueError, r"render\(\): spp: 0 is not in 1\.\.=4096", dict(spp=0)),
        (ValueError, r"render\(\): cube_size: 5000 is not in 1\.\.=1024", dict(cube_size=5000)),
        (ValueError, r"render\(\): spp: -3 is not a count", dict(spp=-3)),
        (ValueError, r"a \"position\" or a \"direction\"", dict(light={"colour": (1, 1, 1)})),
        (ValueError, r"render\(\): light: a light's colour must be finite and not negative", dict(light="1,1,1@-1,0,0")),
        (ValueError, r"non-zero direction", dict(light={"direction": (0, 0, 0)})),
        (TypeError, r"render\(\): light takes a light", dict(light=5)),
        (ValueError, r"render\(\): attenuation: 'fast' is not a number", dict(attenuation="fast")),
        (ValueError, r"y_convention is given only with normal_map", dict(y_convention="directx")),
        (ValueError, r"height_field and normal_map cannot both be given", dict(height_field="bricks", normal_map="n.png")),
        (ValueError, r"render\(\): no_self_shadow and self_shadow cannot both be given", dict(no_self_shadow=True, self_shadow="step")),
        (ValueError, r"render\(\): size and width cannot both be given", dict(size=8, width=8, height=8)),
        (ValueError, r"render\(\): width is given only with height", dict(width=8)),
        (ValueError, r"render\(\): size: '0' is not a size in 1\.\.=16384 pixels", dict(size=0)),
        (TypeError, r"unexpected keyword argument 'colour' \(it takes: allow_outside_paths, ambient", dict(colour=1)),
        (TypeError, r"no_self_shadow is True or False, got int", dict(no_self_shadow=1)),
        (ValueError, r"unknown scene 'donut': use torus, wall", dict(scene="donut")),
    ]
    for error, message, options in cases:
        with pytest.raises(error, match=message):
            bumpmap.render(size=8, **options) if "size" not in options and "width" not in options else bumpmap.render(**options)


def test_flags_set_false_are_flags_not_given():
    plain = bumpmap.render(size=16)
    assert np.array_equal(plain, bumpmap.render(size=16, rebuild_mips=False, silhouettes=False))
    assert np.array_equal(plain, bumpmap.render(size=16, eye=None, light=None))


def test_prepare_reads_the_same_keywords():
    with bumpmap.Renderer("cpu") as renderer:
        scene = renderer.prepare(scene="wall", technique="pom", size=32, eye=(0, -3, 1.2), light={"direction": (1, -1, 1)})
        assert np.array_equal(scene.render(), bumpmap.render(scene="wall", technique="pom", size=32, eye=(0, -3, 1.2),
                                                             light="dir:1,-1,1"))
        with pytest.raises(TypeError, match=r"prepare\(\): the backend is the Renderer's"):
            renderer.prepare(backend="cpu")
        with pytest.raises(ValueError, match=r"prepare\(\): invalid value 'pom2' for technique"):
            renderer.prepare(technique="pom2")
    with pytest.raises(ValueError, match=r"Renderer\(\): invalid value 'cuda' for backend; possible values: cpu, gpu, auto"):
        bumpmap.Renderer("cuda")


def test_compare_reads_typed_keywords():
    with pytest.raises(ValueError, match=r"compare\(\): invalid value 'golf' for studies; possible values: all, none, golf-ball"):
        bumpmap.compare(studies=["golf"])
    with pytest.raises(ValueError, match=r"compare\(\): spp: 0 is not in 1\.\.=4096"):
        bumpmap.compare(size=8, spp=0, studies="none")
    with pytest.raises(TypeError, match=r"compare\(\) got an unexpected keyword argument 'light' \(it takes: backend, bump_scale"):
        bumpmap.compare(light=(1, 2, 3))
    with pytest.raises(TypeError, match=r"compare\(\): techniques takes strings, got int"):
        bumpmap.compare(techniques=["kilgard", 3])
    listed = bumpmap.compare(size=16, spp=1, studies=[], techniques=["kilgard", "single-pass"])
    joined = bumpmap.compare(size=16, spp=1, studies="none", techniques="kilgard,single-pass")
    assert list(listed["techniques"]) == list(joined["techniques"]) == ["kilgard", "single-pass"]


def test_map_keywords_are_typed_values():
    heights = bumpmap.read_height_field("bricks@32")
    plain = bumpmap.normal_map(heights, scale=6, bits=16)
    assert np.array_equal(plain, bumpmap.normal_map(heights, scale=np.float32(6), bits=np.int64(16)))
    assert np.array_equal(bumpmap.normal_map(heights), bumpmap.normal_map(heights, scale=4, kernel="forward", y_convention="opengl"))
    with pytest.raises(TypeError, match=r"normal_map\(\): bits takes a whole number, got float"):
        bumpmap.normal_map(heights, bits=16.0)
    with pytest.raises(TypeError, match=r"mip_chain\(\): kernel takes a string, got int"):
        bumpmap.mip_chain(heights, kernel=3)
    with pytest.raises(ValueError, match=r"invalid value 'up' for y_convention; possible values: opengl, directx"):
        bumpmap.horizon_maps(heights, y_convention="up")
    with pytest.raises(ValueError, match=r"roughness_map\(\): roughness: '1\.5' is not in \[0, 1\]"):
        bumpmap.roughness_map(heights, roughness=1.5)
    with pytest.raises(ValueError, match=r"invalid value 'cyan' for channel; possible values: luminance, red"):
        bumpmap.read_height_field("bricks@32", channel="cyan")


def test_a_format_is_a_word_of_the_set_as_the_stub_says(tmp_path):
    level = bumpmap.normal_map(bumpmap.read_height_field("bricks@16"))
    (bc5,) = bumpmap.write_texture(tmp_path / "a.dds", level, format="bc5")
    (alias,) = bumpmap.write_texture(tmp_path / "b.dds", level, format="bc5_unorm")
    assert bc5.read_bytes() == alias.read_bytes()
    assert bumpmap.read_texture(bc5)["format"] == "bc5"
    # The stub's Literal is lower case; the run time now refuses what the stub refuses.
    with pytest.raises(ValueError, match=r"write_texture\(\): invalid value 'BC5' for format; possible values: rgba8, rgba16, bc5, bc7"):
        bumpmap.write_texture(tmp_path / "c.dds", level, format="BC5")


def test_tangents_read_typed_keywords():
    positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
    uvs = np.array([[0, 0], [1, 0], [0, 1]], np.float32)
    indices = np.array([0, 1, 2], np.uint32)
    ours = bumpmap.tangents(positions, None, uvs, indices, mode="ours", split_angle=np.float32(30))
    mikk = bumpmap.tangents(positions, None, uvs, indices, mode="mikktspace")
    assert ours["tangents"].shape == mikk["tangents"].shape == (3, 4)
    with pytest.raises(ValueError, match=r"invalid value 'mikk' for mode; possible values: ours, mikktspace"):
        bumpmap.tangents(positions, None, uvs, indices, mode="mikk")
    with pytest.raises(ValueError, match=r"split_angle must be in \[0, 180\], got 200"):
        bumpmap.tangents(positions, None, uvs, indices, split_angle=200)
