//! `bumpmap inspect` and `bumpmap height` end to end: verdicts on maps this project writes and
//! on files that are not normal maps, heights back from files, and bad input refused cleanly.

mod common;

use common::*;
use std::path::Path;

fn json(args: &[&str]) -> serde_json::Value {
    let o = bumpmap(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    serde_json::from_slice(&o.stdout).expect("inspect --json prints JSON")
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A colour image with smooth hues everywhere: what a photograph decodes to as vectors.
fn write_colour_photo(path: &Path, w: u32, h: u32) {
    let img = image::RgbImage::from_fn(w, h, |x, y| {
        let (u, v) = (x as f32 / w as f32, y as f32 / h as f32);
        image::Rgb([
            (255.0 * (0.5 + 0.5 * (7.0 * u + 2.0 * v).sin())) as u8,
            (255.0 * (0.5 + 0.5 * (5.0 * v - 3.0 * u).cos())) as u8,
            (255.0 * (0.3 + 0.3 * (9.0 * u * v).sin())) as u8,
        ])
    });
    img.save(path).unwrap();
}

fn write_rgb_exr(path: &Path, w: u32, h: u32, f: impl Fn(u32, u32) -> [f32; 3]) {
    let img = image::Rgb32FImage::from_fn(w, h, |x, y| image::Rgb(f(x, y)));
    image::DynamicImage::ImageRgb32F(img).save(path).unwrap();
}

#[test]
fn inspect_names_the_convention_of_maps_made_either_way_and_exits_0() {
    let dir = scratch("inspect_conventions");
    let (gl, dx) = (dir.join("gl.png"), dir.join("dx.ktx2"));
    ok(&["normalmap", "bricks@128", "-o", s(&gl), "--y-convention", "opengl", "--kernel", "sobel3", "--mips"]);
    ok(&["normalmap", "noise:4@128", "-o", s(&dx), "--y-convention", "directx", "--mips", "--format", "bc7"]);
    let o = bumpmap(&["inspect", s(&gl), s(&dx)]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{out}{}", stderr(&o));
    assert!(out.contains("convention: opengl (green up)"), "{out}");
    assert!(out.contains("its slopes fit the sobel3 kernel best"), "{out}");
    assert!(out.contains("convention: directx (green down)"), "{out}");
    assert!(
        out.contains("7 levels below 0, length-in-alpha"),
        "our mips (gl.mip1.png …) keep the length in alpha: {out}"
    );
    assert!(out.contains("compression: BC7 added about"), "{out}");
    let v = json(&["inspect", "--json", s(&gl), s(&dx)]);
    assert_eq!(v[0]["convention"]["verdict"], "opengl");
    assert_eq!(v[1]["convention"]["verdict"], "directx");
    assert_eq!(v[1]["stored"], "bc7");
    assert_eq!(v[0]["convention"]["made_with"], "sobel3");
    assert!(v[1]["compression_degrees"].as_f64().unwrap() > 0.1, "{}", v[1]);
    assert_eq!(v[0]["mips"]["filter"], "length-in-alpha");
    assert_eq!(v[0]["levels"], 8);
    assert_eq!(v[1]["mips"]["filter"], "smooth", "noise at 128² barely shortens its normals");
    assert_eq!(v[0]["seam"]["tiles"], true);
    assert_eq!(v[0]["normal_map"], true);
    // A folder reads every map directly inside it, gl.png with the levels beside it.
    let v = json(&["inspect", "--json", s(&dir)]);
    assert_eq!(v.as_array().unwrap().len(), 2, "{v}");
    // A level beside a PNG that is a link out of its folder is not read: the file is refused,
    // naming the link (the rule every level found by name follows).
    #[cfg(unix)]
    {
        let elsewhere = scratch("inspect_conventions_elsewhere");
        let level3 = dir.join("gl.mip3.png");
        std::fs::rename(&level3, elsewhere.join("moved.png")).unwrap();
        std::os::unix::fs::symlink(elsewhere.join("moved.png"), &level3).unwrap();
        let o = bumpmap(&["inspect", "--json", s(&gl)]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains("gl.mip3.png: is a link to"), "{}", stderr(&o));
    }
}

#[test]
fn renormalized_mips_are_named_and_strict_exits_1() {
    let dir = scratch("inspect_renormalized");
    let dds = dir.join("renorm.dds");
    ok(&["normalmap", "bricks@128", "-o", s(&dds), "--mips", "--mip-mode", "renormalize"]);
    let o = bumpmap(&["inspect", s(&dds)]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "a finding exits 1 only with --strict: {out}");
    assert!(out.contains("renormalized") && out.contains("brighter"), "{out}");
    assert!(out.contains("FIX: the mips were renormalized"), "{out}");
    let o = bumpmap(&["inspect", "--strict", s(&dds)]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("--strict"), "{}", stderr(&o));
    let v = json(&["inspect", "--json", s(&dds)]);
    assert_eq!(v[0]["mips"]["filter"], "renormalized");
    assert!(v[0]["mips"]["renormalized_brightening"].as_f64().unwrap() > 1.05, "{v}");
}

#[test]
fn photos_roughness_maps_flat_maps_and_ramps_are_told_apart() {
    let dir = scratch("inspect_not_normal");
    let (photo, rough, flat, ramp) =
        (dir.join("photo.png"), dir.join("rough.png"), dir.join("flat.png"), dir.join("ramp.png"));
    write_colour_photo(&photo, 64, 48);
    write_gray_png(&rough, 64, 64, |x, y| ((x * 3 + y * 7) % 200 + 30) as u8);
    let heights = dir.join("h.png");
    write_gray_png(&heights, 64, 64, |_, _| 90);
    ok(&["normalmap", s(&heights), "-o", s(&flat)]);
    write_gray_png(&heights, 64, 64, |x, _| (x * 3) as u8);
    ok(&["normalmap", s(&heights), "-o", s(&ramp), "--wrap", "clamp"]);
    let v = json(&["inspect", "--json", s(&photo), s(&rough), s(&flat), s(&ramp)]);
    assert_eq!(v[0]["normal_map"], false, "{}", v[0]);
    assert_eq!(v[0]["kind"], "not-unit-vectors");
    assert_eq!(v[1]["normal_map"], false, "{}", v[1]);
    assert_eq!(v[1]["kind"], "gray");
    assert_eq!(v[2]["normal_map"], true);
    assert_eq!(v[2]["convention"]["verdict"], "undecidable", "{}", v[2]);
    assert_eq!(v[3]["convention"]["verdict"], "undecidable", "{}", v[3]);
    let o = bumpmap(&["inspect", s(&photo)]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("not a normal map"));
    let o = bumpmap(&["inspect", "--strict", s(&rough)]);
    assert_eq!(o.status.code(), Some(1));
}

#[test]
fn signed_float_maps_are_read_as_such() {
    let dir = scratch("inspect_float");
    let exr = dir.join("n.exr");
    // A signed map: −1..1 as stored, a bump field in it.
    write_rgb_exr(&exr, 32, 32, |x, y| {
        let (a, b) = (0.3 * (x as f32 * 0.4).sin(), 0.3 * (y as f32 * 0.3).cos());
        let z = (1.0 - a * a - b * b).sqrt();
        [a, b, z]
    });
    let v = json(&["inspect", "--json", s(&exr)]);
    assert_eq!(v[0]["stored"], "float-signed", "{v}");
    assert_eq!(v[0]["normal_map"], true, "{v}");
    // A one-channel EXR (the heights `height` writes): a gray map, told as a gray PNG is, not an
    // undecodable file.
    let (png, heights) = (dir.join("n.png"), dir.join("h.exr"));
    ok(&["normalmap", "bricks@64", "-o", s(&png)]);
    ok(&["height", s(&png), "-o", s(&heights)]);
    let v = json(&["inspect", "--json", s(&heights)]);
    assert_eq!((v[0]["normal_map"].clone(), v[0]["kind"].clone()), (false.into(), "gray".into()), "{v}");
    assert_eq!(bumpmap(&["inspect", "--strict", s(&heights)]).status.code(), Some(1));
}

#[test]
fn unreadable_files_exit_1_and_usage_exits_2() {
    let dir = scratch("inspect_bad");
    let missing = dir.join("missing.png");
    let o = bumpmap(&["inspect", s(&missing)]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("missing.png"), "{}", stderr(&o));
    let garbage = dir.join("garbage.png");
    std::fs::write(&garbage, b"not an image at all").unwrap();
    let o = bumpmap(&["inspect", s(&garbage)]);
    assert_eq!(o.status.code(), Some(1));
    assert!(!stderr(&o).contains("panicked"));
    assert_eq!(bumpmap(&["inspect"]).status.code(), Some(2));
    let empty = scratch("inspect_empty_folder");
    let o = bumpmap(&["inspect", s(&empty)]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("holds no"), "{}", stderr(&o));
}

/// Heights of a file as a float plane.
fn read_heights(path: &Path) -> (usize, usize, Vec<f32>) {
    let field = bumpmap_io::load_height_field(path, bumpmap_io::Channel::Luminance).unwrap();
    (field.width(), field.height(), field.to_f32())
}

#[test]
fn height_gives_back_the_heights_a_normal_map_was_made_from() {
    let dir = scratch("height_round_trip");
    // Tiling: dimples, forward differences, scale 4, 16 bits, green down.
    let (map, back) = (dir.join("n.png"), dir.join("back.exr"));
    ok(&["normalmap", "dimples@96", "-o", s(&map), "--bits", "16", "--y-convention", "directx", "--scale", "4"]);
    let err = ok(&["height", s(&map), "-o", s(&back), "--raw", "--scale", "4"]);
    assert!(err.contains("method fft (the map tiles"), "{err}");
    assert!(err.contains("kernel forward (fits the slopes best"), "{err}");
    assert!(err.contains("read as directx (by the curl test"), "{err}");
    let (w, h, got) = read_heights(&back);
    assert_eq!((w, h), (96, 96));
    // The file as OpenEXR itself reads it: headers validated pedantically, one float channel
    // `Y` (luminance, which `image` does not decode: it wants RGB), the same values.
    let meta = exr::meta::MetaData::read_from_file(&back, true).expect("a valid OpenEXR header");
    let channels: Vec<String> = meta.headers[0].channels.list.iter().map(|c| c.name.to_string()).collect();
    assert_eq!(channels, ["Y"]);
    assert_eq!(meta.headers[0].channels.list[0].sample_type, exr::meta::attribute::SampleType::F32);
    let image = exr::prelude::read_first_flat_layer_from_file(&back).expect("OpenEXR reads it");
    let values: Vec<f32> = image.layer_data.channel_data.list[0].sample_data.values_as_f32().collect();
    assert_eq!(values, got, "OpenEXR reads the values our reader does");
    let truth = bumpmap::HeightPreset::Dimples.render(96, 96).to_f32();
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    let (mt, mg) = (mean(&truth), mean(&got));
    let rms =
        (truth.iter().zip(&got).map(|(t, g)| ((t - mt) - (g - mg)).powi(2)).sum::<f32>() / truth.len() as f32).sqrt();
    assert!(rms < 0.001, "heights back within 0.1% of a unit range: rms {rms}");
    // Non-square and not tiling: dct, 16-bit PNG mapped onto 0..1 by default.
    let (wide, png) = (dir.join("wide.png"), dir.join("wide_h.png"));
    let src = dir.join("ramp.png");
    write_gray_png(&src, 80, 48, |x, y| ((x * 2 + y) % 256) as u8);
    ok(&["normalmap", s(&src), "-o", s(&wide), "--wrap", "clamp"]);
    let o = bumpmap(&["height", s(&wide), "-o", s(&png)]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(out.contains("80x48 heights spanning"), "{out}");
    assert!(stderr(&o).contains("method dct (the map tiles but its heights climb"), "{}", stderr(&o));
    // The ramp comes back: heights rise along x twice as fast as along y.
    let back = image::open(&png).unwrap().to_luma16();
    let at = |x: u32, y: u32| back.get_pixel(x, y).0[0] as f32;
    assert!(at(70, 24) > at(10, 24) && at(40, 40) > at(40, 8), "the heights climb as the ramp does");
    let img = image::open(&png).unwrap();
    assert_eq!(img.color(), image::ColorType::L16);
    let px = img.to_luma16();
    assert_eq!(px.pixels().map(|p| p.0[0]).min(), Some(0));
    assert_eq!(px.pixels().map(|p| p.0[0]).max(), Some(65535));
}

#[test]
fn height_refuses_bad_input_and_writes_nothing() {
    let dir = scratch("height_bad");
    // 1x1.
    let tiny = dir.join("tiny.png");
    image::RgbImage::from_pixel(1, 1, image::Rgb([128, 128, 255])).save(&tiny).unwrap();
    fails_cleanly(&dir, &["height", s(&tiny), "-o", s(&dir.join("t.png"))], &tiny, "1x1");
    // NaN texels in an EXR.
    let nan = dir.join("nan.exr");
    write_rgb_exr(&nan, 8, 8, |x, y| if (x, y) == (3, 5) { [f32::NAN, 0.0, 1.0] } else { [0.0, 0.0, 1.0] });
    fails_cleanly(&dir, &["height", s(&nan), "-o", s(&dir.join("n.png"))], &nan, "(3, 5) is not a number");
    // A colour photo: warned and integrated, or refused with --strict.
    let photo = dir.join("photo.png");
    write_colour_photo(&photo, 32, 32);
    fails_cleanly(&dir, &["height", s(&photo), "-o", s(&dir.join("p.png")), "--strict"], &photo, "not a normal map");
    let err = ok(&["height", s(&photo), "-o", s(&dir.join("p.png"))]);
    assert!(err.contains("warning") && err.contains("not a normal map"), "{err}");
    std::fs::remove_file(dir.join("p.png")).unwrap();
    // The output is the input.
    let map = dir.join("map.png");
    ok(&["normalmap", "pinwheel@32", "-o", s(&map)]);
    let before = std::fs::read(&map).unwrap();
    fails_cleanly(&dir, &["height", s(&map), "-o", s(&map)], &map, "overwrite the input");
    assert_eq!(std::fs::read(&map).unwrap(), before);
    // Usage: --raw into a PNG, a scale of 0, --method kernel without a kernel.
    let listing_before = listing(&dir);
    for args in [
        vec!["height", s(&map), "-o", "x.png", "--raw"],
        vec!["height", s(&map), "-o", "x.exr", "--scale", "0"],
        vec!["height", s(&map), "-o", "x.exr", "--method", "kernel"],
        vec!["height", s(&map), "-o", "x.exr", "--kernel", "sobel9"],
    ] {
        let o = bumpmap(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    }
    // --kernel spectral was given: the message must not ask to add a --kernel.
    let o = bumpmap(&["height", s(&map), "-o", "x.exr", "--method", "kernel", "--kernel", "spectral"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--kernel spectral is none") && !stderr(&o).contains("add --kernel"), "{}", stderr(&o));
    let o = bumpmap(&["height", s(&map), "-o", s(&dir.join("x.jpg"))]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(listing(&dir), listing_before);
}

#[test]
fn a_flat_map_is_warned_about_and_written_as_zero() {
    let dir = scratch("height_flat");
    let (heights, map, out) = (dir.join("h.png"), dir.join("n.png"), dir.join("out.png"));
    write_gray_png(&heights, 16, 16, |_, _| 40);
    ok(&["normalmap", s(&heights), "-o", s(&map)]);
    let err = ok(&["height", s(&map), "-o", s(&out)]);
    assert!(err.contains("the map is flat"), "{err}");
    let px = image::open(&out).unwrap().to_luma16();
    assert!(px.pixels().all(|p| p.0[0] == 0));
}

#[test]
#[cfg(target_os = "linux")]
fn a_map_too_big_for_the_memory_is_refused_naming_the_bytes() {
    let dir = scratch("inspect_memory");
    let map = dir.join("big.png");
    ok(&["normalmap", "noise:2@4096", "-o", s(&map)]);
    let exe = env!("CARGO_BIN_EXE_bumpmap");
    for command in [
        format!("'{exe}' inspect '{}'", s(&map)),
        format!("'{exe}' height '{}' -o '{}'", s(&map), s(&dir.join("h.png"))),
    ] {
        // 600 MiB of address space: the map decodes (64 MiB), its work (800 MiB) does not fit.
        let o =
            std::process::Command::new("sh").arg("-c").arg(format!("ulimit -v 614400; {command}")).output().unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{command}: {err}");
        assert!(err.contains("big.png") && err.contains("not enough memory") && err.contains("800.0 MiB"), "{err}");
    }
    assert_eq!(listing(&dir), ["big.png"]);
}

#[test]
fn a_level_beside_a_png_of_the_wrong_size_is_named_and_height_does_not_need_it() {
    let dir = scratch("inspect_bad_level");
    let map = dir.join("n.png");
    ok(&["normalmap", "dimples@64", "-o", s(&map), "--mips"]);
    // Level 2 replaced by a 7x7 image.
    let level2 = dir.join("n.mip2.png");
    image::RgbImage::from_pixel(7, 7, image::Rgb([128, 128, 255])).save(&level2).unwrap();
    let before = listing(&dir);
    let o = bumpmap(&["inspect", s(&map)]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("n.mip2.png") && err.contains("is 7x7") && err.contains("must be 16x16"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    // height reads level 0 alone.
    let out = dir.join("h.png");
    ok(&["height", s(&map), "-o", s(&out)]);
    assert_eq!(listing(&dir).len(), before.len() + 1);
}

#[test]
fn a_map_of_nan_is_not_a_normal_map_and_strict_exits_1() {
    // Every texel NaN, or infinite: no length is 1, so it is not a normal map (it once read as
    // one, its NaN lengths never "far from 1").
    let dir = scratch("inspect_nan");
    for (name, value) in [("nan.exr", f32::NAN), ("inf.exr", f32::INFINITY)] {
        let path = dir.join(name);
        write_rgb_exr(&path, 16, 16, |_, _| [value, value, value]);
        let o = bumpmap(&["inspect", "--strict", s(&path)]);
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(o.status.code(), Some(1), "{out}{}", stderr(&o));
        assert!(out.contains("not a normal map"), "{out}");
    }
}

#[test]
fn a_scale_so_small_the_heights_overflow_is_refused() {
    // `height --scale 1e-35` once wrote a flat image ("spanning -inf texels") and exited 0.
    let dir = scratch("height_tiny_scale");
    let (map, out) = (dir.join("n.png"), dir.join("h.png"));
    ok(&["normalmap", "bricks@64", "-o", s(&map)]);
    for scale in ["1e-35", "-1e-9", "1e7"] {
        let flag = format!("--scale={scale}");
        let o = bumpmap(&["height", s(&map), "-o", s(&out), &flag]);
        assert_eq!(o.status.code(), Some(2), "--scale {scale}: {}", stderr(&o));
        assert!(stderr(&o).contains("from 1e-6 to 1e6"), "{}", stderr(&o));
        assert!(!out.exists());
    }
    ok(&["height", s(&map), "-o", s(&out), "--scale", "1e-6"]);
}
