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
