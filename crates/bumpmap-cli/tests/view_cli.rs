//! `bumpmap view` without a window: `--record`'s animated PNG, read back frame by frame by the
//! `image` crate's APNG decoder (Pillow reads it in the Python tests), and the errors a viewer
//! gives before it opens anything.

mod common;

use common::{bumpmap, scratch, stderr};

/// The frames of an APNG, decoded.
fn frames(path: &std::path::Path) -> Vec<image::RgbaImage> {
    use image::AnimationDecoder;
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let decoder = image::codecs::png::PngDecoder::new(file).unwrap();
    assert!(decoder.is_apng().unwrap(), "an animated PNG");
    decoder.apng().unwrap().into_frames().map(|f| f.unwrap().into_buffer()).collect()
}

#[test]
fn record_writes_one_orbit_of_the_light_as_an_animated_png() {
    let dir = scratch("view_record");
    let out = dir.join("orbit.png");
    let o = bumpmap(&[
        "view",
        "--record",
        out.to_str().unwrap(),
        "--backend",
        "cpu",
        "--size",
        "64",
        "--frames",
        "8",
        "--frame-ms",
        "50",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("8 frames of 64x64"), "{}", stderr(&o));
    let frames = frames(&out);
    assert_eq!(frames.len(), 8);
    for (k, f) in frames.iter().enumerate() {
        assert_eq!(f.dimensions(), (64, 64));
        assert!(f.pixels().filter(|p| p.0[0] > 40).count() > 200, "frame {k} shows the torus");
    }
    // The light moves: neighbouring frames differ, and half a turn differs most.
    for k in 0..8 {
        assert_ne!(frames[k], frames[(k + 1) % 8], "frames {k} and {} are the same", (k + 1) % 8);
    }
}

#[test]
fn record_refuses_what_it_cannot_do_before_any_work() {
    let dir = scratch("view_record_refusals");
    let out = dir.join("o.png");
    let o = bumpmap(&["view", "--record", out.to_str().unwrap(), "--keys", "t,zz"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("'zz' is not a viewer key"), "{}", stderr(&o));
    // The recording may not replace the height field it shows.
    let heights = dir.join("h.png");
    common::write_gray_png(&heights, 16, 16, |x, y| ((x * y) % 256) as u8);
    let before = std::fs::read(&heights).unwrap();
    let o = bumpmap(&["view", heights.to_str().unwrap(), "--record", heights.to_str().unwrap(), "--size", "32"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(std::fs::read(&heights).unwrap(), before, "the input is untouched");
    // A file and the option it stands for, both.
    let o =
        bumpmap(&["view", heights.to_str().unwrap(), "--height-field", "dimples", "--record", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("not both"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn fewer_frames_than_the_keys_need_is_a_usage_error() {
    // Three keys take three frames and show in a fourth: --frames 3 would drop the last one's
    // effect, --frames 2 a key. Refused before a display is looked for (none here).
    let dir = scratch("view_frames_keys");
    let shot = dir.join("s.png");
    for frames in ["2", "3"] {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_bumpmap"))
            .args(["view", "--keys", "t,t,g", "--frames", frames, "--screenshot", shot.to_str().unwrap()])
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains(&format!("--frames {frames}")) && err.contains("--frames 4 or more"), "{err}");
    }
    assert!(!shot.exists());
    // Enough frames gets as far as the display (none here: exit 1, not 2).
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_bumpmap"))
        .args(["view", "--keys", "t,t,g", "--frames", "4"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

#[test]
fn without_a_display_the_window_says_what_to_do() {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_bumpmap"))
        .args(["view", "--backend", "cpu"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("no display") && err.contains("xvfb-run") && err.contains("--record"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    // A display named but not there: the same advice, with the reason.
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_bumpmap"))
        .args(["view", "--backend", "cpu"])
        .env("DISPLAY", ":77")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("X server") && err.contains("xvfb-run") && !err.contains("panicked"), "{err}");
}

#[test]
fn the_readme_lists_every_key_the_viewer_has() {
    let help = String::from_utf8(bumpmap(&["view", "--help"]).stdout).unwrap();
    let block = &help[help.find("Keys (").unwrap()..help.find("Mouse:").unwrap()];
    let keys: Vec<(String, String)> = block
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| (l[2..9].trim().to_string(), l[9..].trim().to_string()))
        .collect();
    assert!(keys.len() > 20, "{block}");
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md")).unwrap();
    for (key, does) in &keys {
        let row = format!("| `{key}` | {does} |");
        assert!(readme.contains(&row), "README.md lacks the row {row}");
    }
    let rows = readme.lines().filter(|l| l.starts_with("| `") && l.ends_with(" |") && l.matches('|').count() == 3);
    let listed: Vec<&str> = rows.filter(|l| keys.iter().any(|(k, _)| l.starts_with(&format!("| `{k}` |")))).collect();
    assert_eq!(listed.len(), keys.len(), "one README row per key");
}
