"""`bumpmap view --record`'s animated PNG, read by Pillow: a decoder that shares no code with
the Rust `png` crate that wrote it. It must see every frame, the delay asked for, and the light
moving from frame to frame."""

import numpy as np
from PIL import Image, ImageSequence


def test_pillow_plays_every_frame_of_a_recorded_orbit(cli, tmp_path):
    out = tmp_path / "orbit.png"
    cli("view", "--record", out, "--backend", "cpu", "--size", "48", "--frames", "6", "--frame-ms", "80")
    with Image.open(out) as im:
        assert im.format == "PNG" and im.is_animated
        assert im.n_frames == 6
        assert im.info.get("loop") == 0, "loops forever"
        frames = []
        for frame in ImageSequence.Iterator(im):
            assert frame.info["duration"] == 80
            frames.append(np.asarray(frame.convert("RGB"), dtype=np.int16))
    for k, f in enumerate(frames):
        assert f.shape == (48, 48, 3)
        assert (f[..., 0] > 40).sum() > 100, f"frame {k} shows the torus"
    moved = [np.abs(frames[k] - frames[(k + 1) % 6]).max() for k in range(6)]
    assert min(moved) > 10, f"the light moves between every pair of frames: {moved}"
