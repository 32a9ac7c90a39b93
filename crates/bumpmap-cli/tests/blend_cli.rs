//! `bumpmap blend` end to end: a noise detail over bricks, read back by the `image` crate;
//! maps of other sizes, bits and Y conventions; bad values refused with nothing written.

mod common;

use common::*;

fn normalmap(dir: &std::path::Path, preset: &str, name: &str, extra: &[&str]) {
    let out = dir.join(name);
    let mut args = vec!["normalmap", preset, "-o", out.to_str().unwrap()];
    args.extend(extra);
    let o = bumpmap(&args);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_detail_over_a_base_keeps_the_base_and_adds_the_detail() {
    let dir = scratch("blend_cli");
    normalmap(&dir, "bricks@128", "base.png", &[]);
    normalmap(&dir, "noise:4@32", "detail.png", &["--scale", "2", "--bits", "16"]);
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let run = |args: &[&str]| {
        let mut all = vec!["blend".to_string(), path("base.png"), path("detail.png")];
        all.extend(args.iter().map(|s| s.to_string()));
        bumpmap(&all.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let o = run(&["-o", &path("out.png"), "--detail-repeat", "4"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Mixed bits are said, and the finer kept.
    assert!(stderr(&o).contains("the base is 8-bit and the detail 16-bit: the result is 16-bit"), "{}", stderr(&o));
    let out = image::open(dir.join("out.png")).unwrap();
    assert!(matches!(out, image::DynamicImage::ImageRgba16(_)), "{:?}", out.color());
    let (out, base) = (out.to_rgba8(), image::open(dir.join("base.png")).unwrap().to_rgba8());
    assert_eq!(out.dimensions(), (128, 128), "the base's size");
    // The bricks' edges are still there, and the noise added texel-to-texel variation on the faces.
    let differs = out.pixels().zip(base.pixels()).filter(|(a, b)| a[0].abs_diff(b[0]) > 4).count();
    assert!(differs > 128 * 128 / 4, "{differs}");
    let corr = {
        let (a, b): (Vec<f64>, Vec<f64>) =
            out.pixels().zip(base.pixels()).map(|(a, b)| (a[0] as f64, b[0] as f64)).unzip();
        let (ma, mb) = (a.iter().sum::<f64>() / a.len() as f64, b.iter().sum::<f64>() / b.len() as f64);
        let cov: f64 = a.iter().zip(&b).map(|(x, y)| (x - ma) * (y - mb)).sum();
        let (va, vb): (f64, f64) = (a.iter().map(|x| (x - ma).powi(2)).sum(), b.iter().map(|y| (y - mb).powi(2)).sum());
        cov / (va * vb).sqrt()
    };
    assert!(corr > 0.5, "the base shows through: {corr}");
    // 8 bits asked: 8 bits written, nothing said about bits; a DirectX detail said as flipped.
    let o = run(&["-o", &path("dx.ktx2"), "--bits", "8", "--detail-y-convention", "directx", "--mips"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("flipped to the base's opengl") && !stderr(&o).contains("-bit:"), "{}", stderr(&o));
    // Refusals: a value out of range (2), an output on an input (1), a missing file (1).
    let before = listing(&dir);
    for (args, code) in [
        (vec!["-o", &path("x.png"), "--detail-strength", "-1"], 2),
        (vec!["-o", &path("x.png"), "--detail-repeat", "0"], 2),
        (vec!["-o", &path("x.png"), "--method", "sum"], 2),
        (vec!["-o", &path("base.png")], 1),
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {}", stderr(&o));
    }
    let o = bumpmap(&["blend", &path("base.png"), &path("missing.png"), "-o", &path("x.png")]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("missing.png"), "{}", stderr(&o));
    assert_eq!(listing(&dir), before, "nothing written, nothing replaced");
}

/// `render --detail-map`: a DirectX detail with its convention said draws as the OpenGL one
/// does, and not without it; a 16-bit detail is said to be read at 8 bits; techniques that
/// cannot read a second map refuse it, with nothing written.
#[test]
fn a_detail_map_at_render_time_is_converted_said_or_refused() {
    let dir = scratch("blend_cli_render");
    normalmap(&dir, "noise:4@32", "gl.png", &["--scale", "2"]);
    normalmap(&dir, "noise:4@32", "dx.png", &["--scale", "2", "--y-convention", "directx"]);
    normalmap(&dir, "noise:4@32", "sixteen.png", &["--scale", "2", "--bits", "16"]);
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let render = |out: &str, extra: &[&str]| {
        let out = path(out);
        let mut args = vec!["render", "--scene", "wall", "--size", "64", "-o", &out];
        if !extra.contains(&"--technique") {
            args.extend(["--technique", "single-pass"]);
        }
        args.extend(extra);
        bumpmap(&args)
    };
    let o = render("plain.png", &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = render("gl_out.png", &["--detail-map", &path("gl.png"), "--detail-repeat", "3"]);
    assert!(o.status.success() && stderr(&o).contains("as the detail map (green up: opengl)"), "{}", stderr(&o));
    let dx = path("dx.png");
    let o = render("dx_out.png", &["--detail-map", &dx, "--detail-repeat", "3", "--detail-y-convention", "directx"]);
    assert!(o.status.success() && stderr(&o).contains("(green down: directx)"), "{}", stderr(&o));
    let o = render("dx_unsaid.png", &["--detail-map", &dx, "--detail-repeat", "3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = render("sixteen_out.png", &["--detail-map", &path("sixteen.png"), "--detail-repeat", "3"]);
    assert!(o.status.success() && stderr(&o).contains("read at 8 bits a channel"), "{}", stderr(&o));
    let read = |name: &str| image::open(dir.join(name)).unwrap().to_rgba8().into_raw();
    let (plain, gl, dx_said, dx_unsaid) =
        (read("plain.png"), read("gl_out.png"), read("dx_out.png"), read("dx_unsaid.png"));
    assert_eq!(gl, dx_said, "a DirectX detail, said so, draws as its OpenGL twin");
    let changed = |a: &[u8], b: &[u8]| a.iter().zip(b).filter(|(x, y)| x.abs_diff(**y) > 8).count();
    assert!(changed(&gl, &plain) > 64 * 64 / 10, "the detail shows: {}", changed(&gl, &plain));
    assert!(changed(&gl, &dx_unsaid) > 64 * 64 / 20, "green's way matters: {}", changed(&gl, &dx_unsaid));
    // Refused: the default kilgard (2, naming the way out), object-space's
    // map (1), an option without the map (2), a strength out of range (2), a missing file (1).
    let before = listing(&dir);
    let gl = path("gl.png");
    for (extra, code, says) in [
        (vec!["--technique", "kilgard", "--detail-map", &gl], 2, "add --technique single-pass"),
        (vec!["--technique", "object-space", "--detail-map", &gl], 1, "tangent-space map of unit normals"),
        (vec!["--detail-repeat", "3"], 2, "--detail-map"),
        (vec!["--detail-map", &gl, "--detail-strength", "-1"], 2, "strength"),
        (vec!["--detail-map", &path("missing.png")], 1, "missing.png"),
    ] {
        let o = render("refused.png", &extra);
        assert_eq!(o.status.code(), Some(code), "{extra:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{extra:?}: {}", stderr(&o));
    }
    assert_eq!(listing(&dir), before, "nothing written");
}
