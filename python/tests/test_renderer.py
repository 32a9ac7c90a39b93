"""Arrays where the command line takes files, and a Renderer kept between frames: an array
renders exactly as the file holding it, a kept scene's frames are `render`'s frames with the
same light and eye, and a closed renderer or a bad array is a clear exception."""

import threading

import numpy as np
import pytest

import bumpmap

SMALL = {"size": 48, "scene": "patch", "technique": "single-pass", "backend": "cpu"}


@pytest.fixture(scope="module")
def normals():
    return bumpmap.normal_map(bumpmap.read_height_field("pinwheel@64"), scale=6)


def test_a_normal_map_array_renders_as_its_png_byte_for_byte(tmp_path, normals):
    (path,) = bumpmap.write_texture(tmp_path / "n.png", normals)
    from_file = bumpmap.render(normal_map=path, **SMALL)
    from_array = bumpmap.render(normal_map=normals, **SMALL)
    assert np.array_equal(from_array, from_file)
    # Not a flat image: the bumps show.
    assert from_file[..., :3].std() > 5
    # Sixteen bits and a whole chain too.
    chain = bumpmap.mip_chain(bumpmap.read_height_field("pinwheel@64"), scale=6, bits=16)
    bumpmap.write_texture(tmp_path / "c.ktx2", chain)
    assert np.array_equal(bumpmap.render(normal_map=chain, **SMALL),
                          bumpmap.render(normal_map=tmp_path / "c.ktx2", **SMALL))


def test_height_field_and_decal_arrays_render_as_their_files(tmp_path):
    heights = (bumpmap.read_height_field("dimples@64") * 65535).astype(np.uint16)
    decal = np.zeros((32, 32, 4), np.uint8)
    decal[..., 0] = np.arange(32, dtype=np.uint8)[None, :] * 8
    decal[..., 1] = 200
    decal[..., 3] = 255
    from PIL import Image

    Image.fromarray(heights).save(tmp_path / "h.png")
    Image.fromarray(decal).save(tmp_path / "d.png")
    options = dict(SMALL, technique="kilgard")
    from_files = bumpmap.render(height_field=str(tmp_path / "h.png"), decal=str(tmp_path / "d.png"), **options)
    from_arrays = bumpmap.render(height_field=heights, decal=decal, **options)
    assert np.array_equal(from_arrays, from_files)
    assert from_files[..., 1].max() > 100, "the decal's green shows"


def test_a_kept_scene_draws_what_render_draws_with_the_same_light_and_eye():
    with bumpmap.Renderer("cpu") as renderer:
        scene = renderer.prepare(scene="sphere", technique="single-pass", size=40, height_field="dimples")
        assert scene.size == (40, 40) and scene.technique == "single-pass"
        for light, eye in [((3.0, -2.0, 4.0), None), ((-4.0, 1.0, 2.0), (0.5, -5.0, 2.0))]:
            got = scene.render(light=light, eye=eye)
            options = dict(scene="sphere", technique="single-pass", size=40, height_field="dimples",
                           light=",".join(map(str, light)), backend="cpu")
            if eye:
                options["eye"] = eye
            assert np.array_equal(got, bumpmap.render(**options)), (light, eye)
        # The light stays where it was put.
        assert np.array_equal(scene.render(), got)
        # An eye at the point looked at (or a rounding error from it) is refused, not a black
        # frame, and the camera stays where it was.
        for eye in [(0.0, 0.0, 0.0), (0.0, 0.0, 1e-30)]:
            with pytest.raises(ValueError, match="is at the point looked at"):
                scene.render(eye=eye)
        assert np.array_equal(scene.render(), got)
    assert renderer.closed


def test_frames_of_a_moving_light_differ_and_threads_may_share_a_renderer():
    renderer = bumpmap.Renderer("cpu")
    scenes = [renderer.prepare(scene=s, size=32) for s in ("torus", "sphere")]
    lights = [(4 * np.cos(a), 4 * np.sin(a), 3) for a in np.linspace(0, 2 * np.pi, 6, endpoint=False)]
    serial = [[s.render(light=l) for l in lights] for s in scenes]
    assert not np.array_equal(serial[0][0], serial[0][3]), "the light moved"
    got = [None, None]

    def draw(k):
        got[k] = [scenes[k].render(light=l) for l in lights]

    threads = [threading.Thread(target=draw, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)
    for k in range(2):
        assert all(np.array_equal(a, b) for a, b in zip(got[k], serial[k])), k


def test_a_closed_renderer_and_bad_arrays_are_clear_exceptions(normals):
    renderer = bumpmap.Renderer("cpu")
    scene = renderer.prepare(size=16)
    renderer.close()
    with pytest.raises(RuntimeError, match="closed"):
        scene.render()
    with pytest.raises(RuntimeError, match="closed"):
        renderer.prepare(size=16)
    with pytest.raises(TypeError, match="normal_map: level 0 is float64"):
        bumpmap.render(normal_map=normals.astype(np.float64), **SMALL)
    with pytest.raises(ValueError, match="normal_map.*shape"):
        bumpmap.render(normal_map=normals[..., :3], **SMALL)
    with pytest.raises(TypeError, match="decal"):
        bumpmap.render(decal=np.zeros((8, 8, 4), np.uint16), **SMALL)
    with pytest.raises(TypeError, match="height_field"):
        bumpmap.render(height_field=np.zeros((8, 8), np.complex64), **SMALL)
    live = bumpmap.Renderer("cpu").prepare(size=16)
    with pytest.raises(ValueError, match="light must be finite"):
        live.render(light=(0, float("nan"), 1))
    with pytest.raises(TypeError, match="light must be three numbers"):
        live.render(light="up")
    with pytest.raises(TypeError, match="backend is the Renderer's"):
        bumpmap.Renderer("cpu").prepare(backend="gpu")
