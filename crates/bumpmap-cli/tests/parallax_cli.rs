//! Heights as geometry from the command line: the exact walk against the displaced reference,
//! heights files that render as the built-in heights, the heights options doing what they say,
//! and bad heights input failing cleanly.

mod common;

use std::path::Path;

use common::*;

type Rgb = Vec<[i32; 3]>;

fn pixels(path: &Path) -> Rgb {
    image::open(path).unwrap().to_rgb8().pixels().map(|p| p.0.map(i32::from)).collect()
}

/// The largest channel difference of each pixel.
fn differences(a: &Rgb, b: &Rgb) -> Vec<i32> {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(p, q)| (0..3).map(|c| (p[c] - q[c]).abs()).max().unwrap()).collect()
}

fn mean(a: &Rgb) -> f64 {
    a.iter().flatten().map(|&v| v as f64).sum::<f64>() / (3 * a.len()) as f64
}

/// `render ARGS… --size 64 -o DIR/NAME`, which must succeed; its pixels.
fn render(dir: &Path, name: &str, args: &[&str]) -> Rgb {
    render_at(dir, name, "64", args)
}

/// `render ARGS… --size SIZE -o DIR/NAME`, which must succeed; its pixels.
fn render_at(dir: &Path, name: &str, size: &str, args: &[&str]) -> Rgb {
    let out = dir.join(name);
    let mut all = vec!["render", "--size", size, "-o", out.to_str().unwrap()];
    all.extend_from_slice(args);
    let o = bumpmap(&all);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    pixels(&out)
}

/// The wall seen from `degrees` off its normal, 1.2 from its centre (compare's study's camera).
fn eye(degrees: f32) -> String {
    let a = degrees.to_radians();
    format!("0,{},{}", -a.sin() * 1.2, a.cos() * 1.2)
}

#[test]
fn the_exact_walk_sees_what_the_displaced_reference_sees() {
    let dir = scratch("parallax_exact_vs_displaced");
    for degrees in [30.0, 60.0, 75.0, 85.0] {
        let eye = eye(degrees);
        // One sample at each pixel's centre and bilinear decals on both sides: the same rays
        // through the same surface, so the images differ only where a pixel's centre lies on an
        // edge of the heights (a brick's top edge seen edge-on), which the rounding of the ray's
        // entry point in the rasterizer sends either way. At 96² no row of pixels lines up with
        // a brick's edge (at 64² and 75° one does, and costs 26 dB); measured 49–72 dB.
        let common = ["--scene", "wall", "--height-field", "bricks@64", "--eye", &eye, "--filter", "linear"];
        let at = |name, technique: &[&str]| render_at(&dir, name, "96", &[&common[..], technique].concat());
        let exact = at("exact.png", &["--technique", "height-exact"]);
        let truth = at("truth.png", &["--technique", "reference-displaced", "--spp", "1"]);
        let normal = at("normal.png", &["--technique", "single-pass"]);
        assert!(mean(&truth) > 20.0, "{degrees}°: the reference is not blank (mean {})", mean(&truth));
        let db = psnr(&exact, &truth);
        assert!(db >= 40.0, "{degrees}°: height-exact is {db:.1} dB from the displaced reference");
        let agree = |a: &Rgb| differences(a, &truth).iter().filter(|&&d| d <= 2).count() as f64 / truth.len() as f64;
        let (exact, normal) = (agree(&exact), agree(&normal));
        assert!(exact >= 0.98, "{degrees}°: height-exact agrees with the displaced reference at {exact:.4} of pixels");
        assert!(normal < 0.6, "{degrees}°: normal mapping is not the displaced surface ({normal:.4} of pixels agree)");
    }
}

/// PSNR over RGB, in dB.
fn psnr(a: &Rgb, b: &Rgb) -> f64 {
    let se: f64 = a.iter().flatten().zip(b.iter().flatten()).map(|(&x, &y)| ((x - y) as f64).powi(2)).sum();
    let mse = se / (3 * a.len()) as f64;
    if mse == 0.0 { f64::INFINITY } else { 10.0 * (255.0f64 * 255.0 / mse).log10() }
}

#[test]
fn heights_files_render_as_the_built_in_heights() {
    let dir = scratch("parallax_heights_files");
    let at = |name: &str| dir.join(name).to_str().unwrap().to_string();
    // The heights in every format and both bit depths, each with its normal map.
    let files = [
        ("n16.png", "h.png", "16", 1),
        ("n16.png", "h.ktx2", "16", 1),
        ("n16.png", "h.dds", "16", 1),
        ("n8.png", "h8.png", "8", 9),
    ];
    for (normals, heights, bits, _) in files {
        let o = bumpmap(&[
            "normalmap",
            "bricks@64",
            "-o",
            &at(normals),
            "--mips",
            "--bits",
            bits,
            "--height-out",
            &at(heights),
        ]);
        assert!(o.status.success(), "{heights}: {}", stderr(&o));
    }
    let view = ["--scene", "wall", "--eye", "0,-1,0.6"];
    for technique in ["pom", "height-exact"] {
        let built_in = render(
            &dir,
            "built_in.png",
            &[&view[..], &["--height-field", "bricks@64", "--decal", "none", "--technique", technique]].concat(),
        );
        // Two black images would agree: the wall is drawn and lit.
        assert!(mean(&built_in) > 20.0, "{technique}: the built-in heights' wall is blank ({})", mean(&built_in));
        for (normals, heights, _, tolerance) in files {
            let from_file = render(
                &dir,
                "from_file.png",
                &[&view[..], &["--normal-map", &at(normals), "--height-map", &at(heights), "--technique", technique]]
                    .concat(),
            );
            // 16 bits: the built-in levels are the same means, rounded to 16 bits only in the
            // file (a level of 1/65535 moves a march's hit by a sliver): one level of 8 bits.
            // 8 bits: heights in steps of 1/255, hits a little elsewhere.
            let worst = *differences(&built_in, &from_file).iter().max().unwrap();
            assert!(worst <= tolerance, "{technique} from {heights}: differs by {worst} > {tolerance}");
        }
    }
}

#[test]
fn the_heights_options_change_what_they_say() {
    let dir = scratch("parallax_options");
    // Silhouettes: the torus's outline is cut by its bricks' mortar, so more background shows.
    let background = |img: &Rgb| img.iter().filter(|p| p.iter().all(|&c| c == 0)).count();
    let whole = render(&dir, "whole.png", &["--technique", "pom", "--depth", "0.15"]);
    let cut = render(&dir, "cut.png", &["--technique", "pom", "--depth", "0.15", "--silhouettes"]);
    assert!(mean(&whole) > 20.0, "the torus is drawn");
    assert!(
        background(&cut) > background(&whole) + 20,
        "silhouettes cut the outline: {} background pixels, {} without",
        background(&cut),
        background(&whole)
    );
    // Shadows: a grazing light darkens the mortar beside the bricks; soft at most as dark as hard.
    let lit = ["--scene", "wall", "--depth", "0.2", "--light", "dir:1,0,0.1"];
    for technique in ["pom", "relief", "height-exact"] {
        let off = mean(&render(&dir, "off.png", &[&lit[..], &["--technique", technique]].concat()));
        let hard = mean(&render(
            &dir,
            "hard.png",
            &[&lit[..], &["--technique", technique, "--parallax-shadow", "hard"]].concat(),
        ));
        let soft = mean(&render(
            &dir,
            "soft.png",
            &[&lit[..], &["--technique", technique, "--parallax-shadow", "soft"]].concat(),
        ));
        assert!(off > 10.0 && hard < 0.95 * off, "{technique}: hard shadows darken ({hard} against {off})");
        assert!(soft <= off && soft >= hard - 0.5, "{technique}: soft between hard and none ({hard} ≤ {soft} ≤ {off})");
    }
    // Writing the hit's depth: a wall standing through a floor meets it along a straight line
    // unless each fragment's depth is where its ray met the heights; then the line follows the
    // bricks of both.
    let cross = dir.join("cross.obj");
    std::fs::write(
        &cross,
        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n\
         vt 0 0\nvt 4 0\nvt 4 4\nvt 0 4\nvn 0 1 0\nvn 0 0 1\n\
         f 4/1/1 3/2/1 2/3/1 1/4/1\nf 5/1/2 6/2/2 7/3/2 8/4/2\n",
    )
    .unwrap();
    let scene = format!("mesh:{}", cross.display());
    let seam =
        ["--scene", &scene, "--technique", "pom", "--depth", "0.08", "--eye", "0.3,1.2,2.4", "--target", "0,0,0"];
    let polygon = render(&dir, "polygon.png", &seam);
    let carved = render(&dir, "carved.png", &[&seam[..], &["--write-depth"]].concat());
    assert!(mean(&polygon) > 20.0, "the crossing quads are drawn");
    let changed = differences(&polygon, &carved).iter().filter(|&&d| d > 8).count();
    assert!(changed > 10, "--write-depth moves the seam ({changed} pixels)");
}

#[test]
fn bad_heights_input_fails_cleanly() {
    let dir = scratch("parallax_bad_input");
    let at = |name: &str| dir.join(name);
    let s = |p: &Path| p.to_str().unwrap().to_string();
    let o = bumpmap(&["normalmap", "bricks@64", "-o", &s(&at("n.png")), "--mips", "--height-out", &s(&at("h.png"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = bumpmap(&["normalmap", "bricks@32", "-o", &s(&at("n32.png")), "--height-out", &s(&at("h32.png"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::copy(at("h.png"), at("alone.png")).unwrap();
    let out = s(&at("out.png"));
    let n = s(&at("n.png"));

    // Values out of range: usage errors, exit 2, nothing written.
    for (flag, value, expect) in [
        ("--depth", "NaN", "'NaN' is not a depth"),
        ("--depth", "0", "'0' is not a depth"),
        ("--depth", "-1", "'-1' is not a depth"),
        ("--depth", "inf", "'inf' is not a depth"),
        ("--layers", "0", "0 is not in 1..=256"),
        ("--layers", "-1", "-1 is not in 1..=256"),
        ("--layers", "999", "999 is not in 1..=256"),
        ("--parallax-shadow", "sharp", "possible values: off, hard, soft"),
    ] {
        let o = bumpmap(&["render", "--technique", "pom", "--size", "32", "-o", &out, flag, value]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{flag} {value}: {err}");
        assert!(err.contains(expect), "{flag} {value}: message must say '{expect}': {err}");
        assert!(!at("out.png").exists());
    }

    // Files that do not fit: exit 1, the file named, nothing written.
    let render = ["render", "--size", "32", "-o", &out, "--normal-map", &n];
    let other_size = at("h32.png");
    fails_cleanly(
        &dir,
        &[&render[..], &["--technique", "pom", "--height-map", &s(&other_size)]].concat(),
        &other_size,
        "is 32x32, but the normal map is 64x64",
    );
    let alone = at("alone.png");
    fails_cleanly(
        &dir,
        &[&render[..], &["--technique", "height-exact", "--height-map", &s(&alone)]].concat(),
        &alone,
        "has no min–max levels beside it",
    );
    // Level counts that do not fit the size: a level missing from the chain, min–max levels
    // that stop early.
    for (name, drop) in
        [("gap", vec!["gap.mip3.png"]), ("short", vec!["short.minmax.mip5.png", "short.minmax.mip6.png"])]
    {
        let heights = at(&format!("{name}.png"));
        let o = bumpmap(&["normalmap", "bricks@64", "-o", &s(&at("n_tmp.png")), "--height-out", &s(&heights)]);
        assert!(o.status.success(), "{}", stderr(&o));
        for f in listing(&dir).iter().filter(|f| f.starts_with("n_tmp")) {
            std::fs::remove_file(at(f)).unwrap();
        }
        for f in drop {
            std::fs::remove_file(at(f)).unwrap();
        }
        let named = if name == "gap" { heights.clone() } else { at("short.minmax.png") };
        let expect = if name == "gap" {
            "heights has 3 levels; a 64x64 level 0 takes 1 or all 7"
        } else {
            "min–max has 5 levels; a 64x64 level 0 takes all 7"
        };
        fails_cleanly(
            &dir,
            &[&render[..], &["--technique", "height-exact", "--height-map", &s(&heights)]].concat(),
            &named,
            expect,
        );
    }
    let missing = at("missing.png");
    fails_cleanly(
        &dir,
        &[&render[..], &["--technique", "pom", "--height-map", &s(&missing)]].concat(),
        &missing,
        "cannot read",
    );
    let not_image = at("notes.png");
    std::fs::write(&not_image, b"these are not heights").unwrap();
    fails_cleanly(
        &dir,
        &[&render[..], &["--technique", "pom", "--height-map", &s(&not_image)]].concat(),
        &not_image,
        "",
    );
    // A normal map alone has no heights to take as geometry.
    let before = listing(&dir);
    let o = bumpmap(&[&render[..], &["--technique", "pom"]].concat());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("--technique pom needs heights to take as geometry"), "{}", stderr(&o));
    assert_eq!(listing(&dir), before);
    // Heights read wherever asked, but nothing else is: the input files are untouched.
    assert!(at("h.png").exists() && at("h.minmax.png").exists());
}

#[test]
fn a_depth_past_the_surface_is_clamped_with_a_note_and_still_renders() {
    let dir = scratch("parallax_clamped");
    let out = dir.join("deep.png");
    let o = bumpmap(&[
        "render",
        "--scene",
        "wall",
        "--technique",
        "pom",
        "--depth",
        "1000",
        "--size",
        "48",
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("--depth 1000 would carve past the surface's bounds; drawn at 1 "),
        "a note says how deep it was drawn: {err}"
    );
    assert!(mean(&pixels(&out)) > 10.0, "the clamped wall is drawn");
}

#[test]
fn bad_height_out_fails_cleanly_and_out_of_range_heights_are_named() {
    let dir = scratch("parallax_height_out");
    let at = |name: &str| dir.join(name);
    let s = |p: &Path| p.to_str().unwrap().to_string();
    let normal_map = s(&at("n.png"));
    // An extension that holds no heights: exit 1, the file named, nothing written.
    let tga = at("h.tga");
    fails_cleanly(
        &dir,
        &["normalmap", "bricks@16", "-o", &normal_map, "--mips", "--height-out", &s(&tga)],
        &tga,
        "unsupported output format (use .png, .dds or .ktx2)",
    );
    // Clashes with the command's other outputs are usage errors; nothing is written.
    for (args, expect) in [
        (vec!["--height-out", normal_map.as_str()], "--height-out"),
        (vec!["--lean-out", "LEAN", "--height-out", "LEAN"], "--lean-out"),
    ] {
        let lean = s(&at("h.ktx2"));
        let args: Vec<&str> = args.into_iter().map(|a| if a == "LEAN" { lean.as_str() } else { a }).collect();
        let o = bumpmap(&[&["normalmap", "bricks@16", "-o", &normal_map, "--mips"][..], &args].concat());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(expect) && !stderr(&o).contains("panicked"), "{}", stderr(&o));
        assert!(listing(&dir).is_empty(), "{args:?}: nothing written");
    }
    // The input is never overwritten.
    let input = at("in.png");
    write_gray_png(&input, 16, 16, |x, y| ((x * 16 + y) % 256) as u8);
    let before = std::fs::read(&input).unwrap();
    fails_cleanly(
        &dir,
        &["normalmap", &s(&input), "-o", &normal_map, "--height-out", &s(&input)],
        &input,
        "output would overwrite the input file",
    );
    assert_eq!(std::fs::read(&input).unwrap(), before);
    // A folder of height fields has no one set of heights to write.
    let o = bumpmap(&["normalmap", &s(&dir), "-o", &s(&at("out")), "--height-out", &s(&at("h.png"))]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("give one height field, not a folder"), "{}", stderr(&o));
    // Float heights outside [0, 1] are written clamped, with a warning that names the file and
    // the range.
    let exr = at("tall.exr");
    let field: Vec<f32> = (0..64).map(|i| i as f32 / 32.0).collect();
    image::Rgb32FImage::from_fn(8, 8, |x, y| image::Rgb([field[(y * 8 + x) as usize]; 3])).save(&exr).unwrap();
    let heights = at("tall_h.png");
    let o = bumpmap(&["normalmap", &s(&exr), "-o", &s(&at("tall_n.png")), "--height-out", &s(&heights)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(&format!("warning: {}: heights from 0 to 1.96875 are clamped to [0, 1]", exr.display())),
        "{}",
        stderr(&o)
    );
    let stored = image::open(&heights).unwrap().to_luma16();
    assert_eq!(stored.get_pixel(0, 0).0[0], 0);
    assert_eq!(stored.get_pixel(7, 7).0[0], 65535, "clamped to 1");
}

#[test]
fn bounds_of_other_heights_beside_a_heights_file_are_refused_naming_them() {
    // The bricks' heights with the noise's min–max files copied in beside them: the march
    // would skip where the bounds say no surface is. They were read as the bounds, exit 0.
    let dir = scratch("parallax_foreign_bounds");
    let at = |name: &str| dir.join(name).to_str().unwrap().to_string();
    for (preset, normals, heights) in [("bricks@64", "n.png", "h.png"), ("noise:3@64", "m.png", "g.png")] {
        let o = bumpmap(&["normalmap", preset, "-o", &at(normals), "--height-out", &at(heights)]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if let Some(rest) = name.strip_prefix("g.minmax") {
            std::fs::copy(dir.join(&name), dir.join(format!("h.minmax{rest}"))).unwrap();
        }
    }
    let draw = |heights: &str, normals: &str| {
        bumpmap(&[
            "render",
            "--scene",
            "wall",
            "--technique",
            "pom",
            "--normal-map",
            &at(normals),
            "--height-map",
            &at(heights),
            "-o",
            &at("out.png"),
        ])
    };
    let o = draw("h.png", "n.png");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("h.minmax.png: min–max level 0 does not hold the heights"), "{}", stderr(&o));
    assert!(!dir.join("out.png").exists());
    // The noise's own bounds still hold its heights.
    let o = draw("g.png", "m.png");
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_normal_map_or_a_horizon_map_given_as_heights_is_refused() {
    // They were read as heights from their red channel, exit 0.
    let dir = scratch("parallax_not_heights");
    let at = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let ok = |args: &[&str]| {
        let o = bumpmap(args);
        assert!(o.status.success(), "{}", stderr(&o));
    };
    ok(&["normalmap", "bricks@64", "-o", &at("n.png"), "--height-out", &at("h.png"), "--horizon-out", &at("hz.png")]);
    ok(&["normalmap", "bricks@64", "-o", &at("n.ktx2")]);
    let before = listing(&dir);
    for (heights, says) in [
        ("n.png", "n.png: is a colour image, not heights"),
        ("hz.png", "hz.png: is a colour image, not heights"),
        ("n.ktx2", "n.ktx2: holds R8G8B8A8_UNORM, not heights"),
    ] {
        let o = bumpmap(&[
            "render",
            "--scene",
            "wall",
            "--technique",
            "pom",
            "--normal-map",
            &at("n.png"),
            "--height-map",
            &at(heights),
            "-o",
            &at("out.png"),
        ]);
        assert_eq!(o.status.code(), Some(1), "{heights}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{}", stderr(&o));
    }
    assert_eq!(listing(&dir), before, "nothing written");
    // The heights themselves draw.
    ok(&[
        "render",
        "--scene",
        "wall",
        "--technique",
        "pom",
        "--normal-map",
        &at("n.png"),
        "--height-map",
        &at("h.png"),
        "-o",
        &at("out.png"),
    ]);
}
