//! Horizon maps, ambient occlusion and bent normals from the command line: written with the
//! normal map as one set and read back by an independent decoder (the `image` crate, `ktx2`),
//! the `horizon` technique's shadows, and bad input failing cleanly.

mod common;

use std::path::Path;

use bumpmap_math::{HeightPreset, HorizonMap, Wrap};
use common::*;

fn s(p: &Path) -> String {
    p.to_str().unwrap().to_string()
}

#[test]
fn horizons_occlusion_and_bent_normals_are_written_with_the_normal_map() {
    let dir = scratch("horizon_outputs");
    let at = |name: &str| dir.join(name);
    let args = [
        "normalmap",
        "bricks@64",
        "-o",
        &s(&at("n.png")),
        "--mips",
        "--horizon-out",
        &s(&at("hz.png")),
        "--ao-out",
        &s(&at("ao.png")),
        "--bent-normals-out",
        &s(&at("bent.png")),
    ];
    let o = bumpmap(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    // Seven levels of the normal map and of each horizon texture, one AO and one bent normal map.
    let files = listing(&dir);
    assert_eq!(files.len(), 7 * 3 + 2, "{files:?}");
    assert!(files.contains(&"hz.dirs4-7.mip6.png".to_string()), "{files:?}");

    // The library's maps, which the files must hold rounded to 8 bits.
    let field = HeightPreset::Bricks.render(64, 64);
    let map = HorizonMap::from_heights(&field, Wrap::Repeat).unwrap();
    let ao_want = map.ambient_occlusion(4.0);
    let ao = image::open(at("ao.png")).unwrap();
    assert!(matches!(ao, image::DynamicImage::ImageLuma8(_)), "8-bit gray: {:?}", ao.color());
    let ao = ao.to_luma8();
    for (i, p) in ao.pixels().enumerate() {
        assert!((p[0] as f32 - ao_want[i] * 255.0).abs() <= 0.5 + 1e-3, "texel {i}: {} vs {}", p[0], ao_want[i]);
    }
    // The mortar (heights 0.2, between the bricks) is darker than a brick's middle.
    let (mortar, brick) = (ao.get_pixel(5, 0)[0], ao.get_pixel(5, 4)[0]);
    assert!(mortar < brick && brick == 255, "mortar {mortar}, brick {brick}");
    let hz = image::open(at("hz.png")).unwrap().to_rgba8();
    let hz2 = image::open(at("hz.dirs4-7.png")).unwrap().to_rgba8();
    for (i, (a, b)) in hz.pixels().zip(hz2.pixels()).enumerate() {
        let want = map.levels()[0].texels[i];
        for k in 0..4 {
            assert!((a[k] as f32 - want[k] * 255.0).abs() <= 0.5 + 1e-3, "texel {i} direction {k}");
            assert!((b[k] as f32 - want[k + 4] * 255.0).abs() <= 0.5 + 1e-3, "texel {i} direction {}", k + 4);
        }
    }
    // A mortar texel sees a brick rise on both sides across the joint (toward −t and +t).
    let m = hz.get_pixel(5, 0);
    assert!(m[2] > 0 && hz2.get_pixel(5, 0)[2] > 0, "{m:?}");
    // Bent normals: unit, up, leaning out of the joint; green up the image (glTF) by default.
    let bent = image::open(at("bent.png")).unwrap().to_rgba8();
    for p in bent.pixels() {
        let n = [0, 1, 2].map(|c| p[c] as f32 / 127.5 - 1.0);
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 0.02 && n[2] > 0.5, "{p:?}");
    }
    let o = bumpmap(&[
        "normalmap",
        "bricks@64",
        "-o",
        &s(&at("dx.png")),
        "--bent-normals-out",
        &s(&at("bent_dx.png")),
        "--y-convention",
        "directx",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let dx = image::open(at("bent_dx.png")).unwrap().to_rgba8();
    let flipped = bent.pixels().zip(dx.pixels()).filter(|(a, b)| a[1] != b[1]).all(|(a, b)| 255 - a[1] == b[1]);
    assert!(flipped && bent != dx, "DirectX's green is OpenGL's mirrored");

    // KTX2 at 16 bits: two RGBA16 textures with every level, an R16 AO.
    let o = bumpmap(&[
        "normalmap",
        "bricks@64",
        "-o",
        &s(&at("k.ktx2")),
        "--mips",
        "--bits",
        "16",
        "--horizon-out",
        &s(&at("hz.ktx2")),
        "--ao-out",
        &s(&at("ao.ktx2")),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    for (file, format, levels) in [
        ("hz.ktx2", ktx2::Format::R16G16B16A16_UNORM, 7),
        ("hz.dirs4-7.ktx2", ktx2::Format::R16G16B16A16_UNORM, 7),
        ("ao.ktx2", ktx2::Format::R16_UNORM, 1),
    ] {
        let bytes = std::fs::read(at(file)).unwrap();
        let reader = ktx2::Reader::new(&bytes[..]).unwrap();
        let header = reader.header();
        assert_eq!((header.format, header.level_count, header.pixel_width), (Some(format), levels, 64), "{file}");
    }
}

#[test]
fn bad_horizon_outputs_fail_cleanly_and_write_nothing() {
    let dir = scratch("horizon_bad");
    let at = |name: &str| dir.join(name);
    let n = s(&at("n.png"));
    // Clashes with another output of the set are usage errors naming both.
    for (args, expect) in [
        (vec!["--horizon-out", n.as_str()], "--horizon-out: "),
        (vec!["--ao-out", "X.png", "--bent-normals-out", "X.png"], "--bent-normals-out: "),
        (vec!["--height-out", "X.png", "--horizon-out", "X.png"], "is also --height-out's file"),
        (vec!["--roughness-out", "X.png", "--ao-out", "X.png"], "is also --roughness-out's file"),
    ] {
        let x = s(&at("x.png"));
        let args: Vec<&str> = args.into_iter().map(|a| if a == "X.png" { x.as_str() } else { a }).collect();
        let o = bumpmap(&[&["normalmap", "bricks@16", "-o", &n, "--mips"][..], &args].concat());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(expect) && !stderr(&o).contains("panicked"), "{}", stderr(&o));
        assert!(listing(&dir).is_empty(), "{args:?}: nothing written");
    }
    // A container that holds no horizons: exit 1, the file named.
    let tga = at("hz.tga");
    fails_cleanly(&dir, &["normalmap", "bricks@16", "-o", &n, "--horizon-out", &s(&tga)], &tga, "unsupported output");
    // NaN heights: refused naming the file and the texel, nothing written.
    let bad = at("nan.exr");
    let img = image::Rgb32FImage::from_fn(8, 8, |x, y| image::Rgb([if (x, y) == (2, 6) { f32::NAN } else { 0.5 }; 3]));
    image::DynamicImage::ImageRgb32F(img).save(&bad).unwrap();
    fails_cleanly(&dir, &["normalmap", &s(&bad), "-o", &n, "--ao-out", &s(&at("ao.png"))], &bad, "texel (2, 6) is NaN");
    // The input is never overwritten.
    let input = at("in.png");
    write_gray_png(&input, 16, 16, |x, y| ((x * 16 + y) % 256) as u8);
    let before = std::fs::read(&input).unwrap();
    fails_cleanly(
        &dir,
        &["normalmap", &s(&input), "-o", &n, "--bent-normals-out", &s(&input)],
        &input,
        "output would overwrite the input file",
    );
    assert_eq!(std::fs::read(&input).unwrap(), before);
}

#[test]
fn the_horizon_technique_darkens_what_the_bricks_hide_from_a_low_light() {
    let dir = scratch("horizon_render");
    let draw = |technique: &str, backend: &str| {
        let out = dir.join(format!("{technique}_{backend}.png"));
        let o = bumpmap(&[
            "render",
            "--scene",
            "wall",
            "--technique",
            technique,
            "--backend",
            backend,
            "--light",
            "dir:0.9,0.3,0.34",
            "--size",
            "96",
            "-o",
            &s(&out),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        image::open(&out).unwrap().to_rgb8()
    };
    let (plain, shadowed) = (draw("single-pass", "cpu"), draw("horizon", "cpu"));
    let lum = |img: &image::RgbImage| img.pixels().map(|p| p.0.iter().map(|&c| c as f64).sum::<f64>()).sum::<f64>();
    assert!(lum(&plain) > 0.0 && lum(&shadowed) > 0.5 * lum(&plain), "the wall is drawn, not black");
    // Shadows only take light away: no pixel brighter, and some clearly darker.
    let (mut darker, mut brighter) = (0, 0);
    for (a, b) in plain.pixels().zip(shadowed.pixels()) {
        let (a, b) = (a.0.iter().map(|&c| c as i32).sum::<i32>(), b.0.iter().map(|&c| c as i32).sum::<i32>());
        darker += (b + 30 < a) as usize;
        brighter += (b > a + 6) as usize;
    }
    assert!(darker > 200, "{darker} pixels shadowed");
    assert_eq!(brighter, 0, "no pixel lit more than by normal mapping");
}

#[test]
fn ambient_occlusion_darkens_the_ambient_light_in_the_joints_only() {
    let dir = scratch("horizon_ambient_occlusion");
    // The light behind the wall: what is left is the ambient term.
    let draw = |extra: &[&str], name: &str| {
        let out = s(&dir.join(name));
        let fixed = [
            "render",
            "--scene",
            "wall",
            "--technique",
            "horizon",
            "--light",
            "dir:0,0,-1",
            "--size",
            "256",
            "-o",
            &out,
        ];
        let args = [&fixed[..], extra].concat();
        let o = bumpmap(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        image::open(&out).unwrap().to_rgb8()
    };
    let (plain, occluded) = (draw(&[], "plain.png"), draw(&["--ambient-occlusion"], "ao.png"));
    let sum = |p: &image::Rgb<u8>| p.0.iter().map(|&c| c as i32).sum::<i32>();
    let (mut darker, mut brighter) = (0, 0);
    for (a, b) in plain.pixels().zip(occluded.pixels()) {
        darker += (sum(b) + 3 < sum(a)) as usize;
        brighter += (sum(b) > sum(a) + 1) as usize;
    }
    assert!(occluded.pixels().map(sum).max().unwrap() > 30, "the ambient-lit wall is drawn, not black");
    assert!(darker > 300 && brighter == 0, "{darker} pixels darker, {brighter} brighter");
    // Occlusion is in the joints: a few pixels lose much of their light, most little or none.
    let wall: Vec<(i32, i32)> =
        plain.pixels().zip(occluded.pixels()).filter(|(a, _)| sum(a) > 30).map(|(a, b)| (sum(a), sum(b))).collect();
    let deep = wall.iter().filter(|(a, b)| (*b as f32) < 0.85 * *a as f32).count();
    let slight = wall.iter().filter(|(a, b)| (*b as f32) >= 0.97 * *a as f32).count();
    eprintln!("{} wall pixels: {deep} lose over 15 %, {slight} under 3 %", wall.len());
    assert!(deep > wall.len() / 50 && slight > wall.len() / 2, "{deep} deep, {slight} slight of {}", wall.len());
}

#[test]
fn a_horizon_map_file_renders_as_the_one_made_and_bad_ones_are_refused() {
    let dir = scratch("horizon_map_file");
    let at = |name: &str| dir.join(name);
    let o = bumpmap(&[
        "normalmap",
        "bricks@64",
        "-o",
        &s(&at("n.png")),
        "--mips",
        "--bits",
        "16",
        "--horizon-out",
        &s(&at("hz.png")),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let render = |extra: &[&str], name: &str| {
        let out = s(&at(name));
        let fixed = [
            "render",
            "--scene",
            "wall",
            "--technique",
            "horizon",
            "--height-field",
            "bricks@64",
            "--light",
            "dir:0.9,0.3,0.34",
            "--size",
            "64",
            "-o",
            &out,
        ];
        bumpmap(&[&fixed[..], extra].concat())
    };
    let o = render(&[], "made.png");
    assert!(o.status.success(), "{}", stderr(&o));
    let hz = s(&at("hz.png"));
    let o = render(&["--horizon-map", &hz], "read.png");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("horizon map, 64x64, 8 directions, 7 levels"), "{}", stderr(&o));
    let (made, read) = (image::open(at("made.png")).unwrap().to_rgb8(), image::open(at("read.png")).unwrap().to_rgb8());
    // 16 bits a direction: the same shadows but for a pixel on an edge's rounding.
    let worst = made.pixels().zip(read.pixels()).flat_map(|(a, b)| (0..3).map(move |c| a[c].abs_diff(b[c]))).max();
    assert!(worst.unwrap() <= 8, "largest difference {worst:?}");
    assert!(made.pixels().filter(|p| p[0] > 40).count() > 1000, "not black");

    // Bad maps: exit 1, the file named, nothing written.
    // The wrong size.
    let o = bumpmap(&["normalmap", "bricks@32", "-o", &s(&at("n32.png")), "--horizon-out", &s(&at("hz32.png"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    let before = listing(&dir);
    let refuse = |map: &Path, expect: &str| {
        let o = render(&["--horizon-map", &s(map)], "bad.png");
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(err.contains(&map.display().to_string()) && err.contains(expect), "{expect}: {err}");
        assert_eq!(listing(&dir), before, "nothing written");
    };
    refuse(&at("hz32.png"), "is 32x32, but the normal map is 64x64");
    // Three directions a texel instead of four (an RGB image), and one file of the two.
    image::RgbImage::from_pixel(64, 64, image::Rgb([0, 0, 0])).save(at("rgb.png")).unwrap();
    std::fs::copy(at("hz.dirs4-7.png"), at("rgb.dirs4-7.png")).unwrap();
    std::fs::copy(at("hz.png"), at("alone.png")).unwrap();
    let before = listing(&dir);
    let o = render(&["--horizon-map", &s(&at("rgb.png"))], "bad.png");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("has 3 channels"), "{}", stderr(&o));
    let o = render(&["--horizon-map", &s(&at("alone.png"))], "bad.png");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("alone.dirs4-7.png: not found"), "{}", stderr(&o));
    assert_eq!(listing(&dir), before, "nothing written");
}

#[test]
fn a_heights_or_horizon_file_that_cannot_be_read_is_named_as_an_input() {
    // An input of another extension was called an "unsupported output format", and a horizon
    // map whose first half is missing was blamed on its second half.
    let dir = scratch("horizon_inputs_named");
    let at = |name: &str| dir.join(name).to_str().unwrap().to_string();
    std::fs::write(dir.join("x.xyz"), "not an image").unwrap();
    let o = bumpmap(&["normalmap", "bricks@64", "-o", &at("n.png"), "--horizon-out", &at("hz.png")]);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::remove_file(dir.join("hz.png")).unwrap();
    for (args, says) in [
        (vec!["--technique", "pom", "--height-map", "x.xyz"], "x.xyz: heights are read from .png, .dds or .ktx2"),
        (
            vec!["--technique", "horizon", "--horizon-map", "x.xyz"],
            "x.xyz: horizon maps are read from .png, .dds or .ktx2",
        ),
        (vec!["--technique", "horizon", "--horizon-map", "hz.png"], "hz.png: not found"),
    ] {
        let mut all = vec!["render".to_string(), "--normal-map".into(), at("n.png"), "-o".into(), at("out.png")];
        all.extend(args.iter().map(|a| if a.contains('.') { at(a) } else { a.to_string() }));
        let o = bumpmap(&all.iter().map(String::as_str).collect::<Vec<_>>());
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says) && !stderr(&o).contains("output format"), "{}", stderr(&o));
    }
}
