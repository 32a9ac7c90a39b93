//! Hostile input, round four (issue #57): what the fourth sweep found short, one test per class.

mod common;

use std::path::Path;
use std::process::Output;

use common::{limited, listing, ok, png_header_only, scratch, stderr};

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Exit 1, `expect` in the message, no abort or panic, and `dir` as it was.
fn refused(o: &Output, dir: &Path, before: &[String], expect: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains(expect), "message must say '{expect}': {err}");
    assert!(!err.contains("panicked") && !err.contains("memory allocation of"), "{err}");
    assert_eq!(listing(dir), before, "nothing may be written");
}

/// Every heights or horizon file — named by an option, or found by name beside one — is sized
/// from its header and refused before its texels are decoded. The 16384² files here are headers
/// alone: decoding one would fail on its missing body, or ask for gigabytes, and the 1 GiB
/// limit turns either into another message than the size's.
#[test]
fn heights_and_horizon_files_are_sized_from_their_headers_before_they_are_decoded() {
    let dir = scratch("hostile4_sized");
    let at = |name: &str| dir.join(name);
    ok(&[
        "normalmap",
        "bricks@64",
        "-o",
        s(&at("n.png")),
        "--mips",
        "--height-out",
        s(&at("h.png")),
        "--horizon-out",
        s(&at("hz.png")),
    ]);
    let huge = png_header_only(16384, 16384);
    std::fs::write(at("big.png"), &huge).unwrap();
    let render = |args: &[&str]| {
        let (out, normal) = (at("out.png"), at("n.png"));
        let mut all = vec!["render", "--scene", "wall", "--size", "32", "--normal-map", s(&normal), "-o", s(&out)];
        all.extend(args);
        limited(1024, &all)
    };
    let before = listing(&dir);
    let big = at("big.png");
    let o = render(&["--technique", "pom", "--height-map", s(&big)]);
    refused(&o, &dir, &before, "big.png: is 16384x16384, but the normal map is 64x64");
    let o = render(&["--technique", "horizon", "--horizon-map", s(&big)]);
    refused(&o, &dir, &before, "big.png: is 16384x16384, but the normal map is 64x64");
    // Found by name: the bounds beside the heights, the second half beside the horizons.
    for (beside, named, technique, flag) in [
        ("h.minmax.png", "h.png", "height-exact", "--height-map"),
        ("hz.dirs4-7.png", "hz.png", "horizon", "--horizon-map"),
    ] {
        let kept = std::fs::read(at(beside)).unwrap();
        std::fs::write(at(beside), &huge).unwrap();
        let before = listing(&dir);
        let o = render(&["--technique", technique, flag, s(&at(named))]);
        refused(&o, &dir, &before, &format!("{beside}: is 16384x16384, but "));
        assert!(stderr(&o).contains("64x64"), "{}", stderr(&o));
        std::fs::write(at(beside), kept).unwrap();
    }
    // Restored, the set draws.
    let o = render(&["--technique", "height-exact", "--height-map", s(&at("h.png"))]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// Bounds of the wrong format beside heights are refused, naming the file and what it holds,
/// never read as bounds: a normal map (8-bit RGBA), or gray heights (blue not 0).
#[test]
fn bounds_of_another_format_are_refused_not_read_as_bounds() {
    let dir = scratch("hostile4_bounds");
    let at = |name: &str| dir.join(name);
    ok(&["normalmap", "bricks@64", "-o", s(&at("n.png")), "--bits", "16", "--height-out", s(&at("h.png"))]);
    ok(&["normalmap", "bricks@64", "-o", s(&at("n8.png"))]);
    let kept = std::fs::read(at("h.minmax.png")).unwrap();
    for (stand_in, says) in [
        ("n8.png", "h.minmax.png: holds R8G8B8A8_UNORM, not min–max bounds"),
        ("h.png", "h.minmax.png: is not min–max bounds: its texel (0, 0) has blue"),
    ] {
        std::fs::copy(at(stand_in), at("h.minmax.png")).unwrap();
        let before = listing(&dir);
        let (out, normal, heights) = (at("out.png"), at("n.png"), at("h.png"));
        let o = limited(
            2048,
            &["render", "--scene", "wall", "--size", "32", "--technique", "height-exact", "--normal-map", s(&normal)]
                .into_iter()
                .chain(["--height-map", s(&heights), "-o", s(&out)])
                .collect::<Vec<_>>(),
        );
        refused(&o, &dir, &before, says);
    }
    std::fs::write(at("h.minmax.png"), kept).unwrap();
}

/// A quad with `normal` as its glTF material's normal texture (`tangents --normal-map`), its
/// textures sampled as `sampler` says (`None`: no sampler, the technique's filters).
fn quad_gltf(dir: &Path, normal: &Path, name: &str, sampler: Option<serde_json::Value>) -> std::path::PathBuf {
    let obj = dir.join(format!("{name}.obj"));
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 4 0\nvt 4 4\nvt 0 4\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
    )
    .unwrap();
    let gltf = dir.join(format!("{name}.gltf"));
    ok(&["tangents", s(&obj), "--normal-map", s(normal), "-o", s(&gltf)]);
    std::fs::remove_file(&obj).unwrap();
    if let Some(sampler) = sampler {
        let mut json: serde_json::Value = serde_json::from_slice(&std::fs::read(&gltf).unwrap()).unwrap();
        json["samplers"] = serde_json::json!([sampler]);
        for texture in json["textures"].as_array_mut().unwrap() {
            texture["sampler"] = serde_json::json!(0);
        }
        std::fs::write(&gltf, serde_json::to_vec(&json).unwrap()).unwrap();
    }
    gltf
}

/// `--filter` given wins over a glTF material's sampler (its filters; the wrap modes stay), and
/// says so; not given, the material's filters are used.
#[test]
fn a_filter_the_user_typed_wins_over_the_materials_sampler() {
    let dir = scratch("hostile4_filter");
    let normal = dir.join("n.png");
    ok(&["normalmap", "bricks@64", "-o", s(&normal)]);
    let nearest = serde_json::json!({"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497});
    let (with, without) = (quad_gltf(&dir, &normal, "nearest", Some(nearest)), quad_gltf(&dir, &normal, "plain", None));
    let render = |gltf: &Path, out: &str, extra: &[&str]| {
        let (scene, out) = (format!("mesh:{}", s(gltf)), dir.join(out));
        let mut args = vec![
            "render",
            "--scene",
            &scene,
            "--technique",
            "single-pass",
            "--size",
            "96",
            "--decal",
            "none",
            "-o",
            s(&out),
        ];
        args.extend(extra);
        let o = common::bumpmap(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        (std::fs::read(&out).unwrap(), stderr(&o))
    };
    let (material, _) = render(&with, "material.png", &[]);
    let (typed, said) = render(&with, "typed.png", &["--filter", "trilinear"]);
    let (plain, _) = render(&without, "plain.png", &[]);
    assert!(said.contains("filter replaces the material's samplers' filters"), "{said}");
    assert!(typed == plain, "the typed filter draws as a material without a sampler");
    assert!(material != typed, "without --filter the material's NEAREST is used");
    // Two black frames would agree: the quad is lit.
    bumpmap_testkit::assert_has_content("hostile4_filter", &common::read_png(&dir.join("typed.png")));
}

/// `image` as a PNG data URI, for a glTF's `images`.
fn png_uri(image: &image::RgbaImage) -> String {
    let mut bytes = Vec::new();
    image.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png).unwrap();
    format!("data:image/png;base64,{}", base64::encode(bytes))
}

/// `--decal none` replaces the base colour only: the material's emissive texture still glows
/// where it glows (it was dropped with the base colour, and the emissive factor alone lit the
/// whole quad white). Drawn as the same material without a base colour texture is.
#[test]
fn decal_none_keeps_the_materials_emission() {
    let dir = scratch("hostile4_emission");
    let normal = dir.join("n.png");
    ok(&["normalmap", "bricks@64", "-o", s(&normal)]);
    let quad = quad_gltf(&dir, &normal, "quad", None);
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(&quad).unwrap()).unwrap();
    // A glow in one corner, a red base colour.
    let glow =
        image::RgbaImage::from_fn(16, 16, |x, y| image::Rgba(if x < 4 && y < 4 { [255; 4] } else { [0, 0, 0, 255] }));
    let red = image::RgbaImage::from_pixel(16, 16, image::Rgba([200, 40, 40, 255]));
    let write = |name: &str, base_colour: bool| {
        let mut g = json.clone();
        let images = g["images"].as_array_mut().unwrap();
        images.extend([serde_json::json!({"uri": png_uri(&glow)}), serde_json::json!({"uri": png_uri(&red)})]);
        let n = images.len();
        let textures = g["textures"].as_array_mut().unwrap();
        textures.extend([serde_json::json!({"source": n - 2}), serde_json::json!({"source": n - 1})]);
        let t = textures.len();
        let m = &mut g["materials"][0];
        m["emissiveTexture"] = serde_json::json!({"index": t - 2});
        m["emissiveFactor"] = serde_json::json!([1, 1, 1]);
        if base_colour {
            m["pbrMetallicRoughness"]["baseColorTexture"] = serde_json::json!({"index": t - 1});
        }
        let path = dir.join(name);
        std::fs::write(&path, serde_json::to_vec(&g).unwrap()).unwrap();
        format!("mesh:{}", s(&path))
    };
    let (coloured, plain) = (write("coloured.gltf", true), write("plain.gltf", false));
    let render = |scene: &str, out: &str, extra: &[&str]| {
        let out = dir.join(out);
        let mut args = vec!["render", "--scene", scene, "--technique", "single-pass", "--size", "96", "-o", s(&out)];
        args.extend(extra);
        let o = common::bumpmap(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        common::read_png(&out)
    };
    let replaced = render(&coloured, "replaced.png", &["--decal", "none"]);
    let without = render(&plain, "without.png", &[]);
    assert!(replaced.texels == without.texels, "--decal none draws as the material without a base colour");
    // Not white all over: the bricks' joints stay darker than the glowing corner.
    let lum = |t: &[u8; 4]| t[0] as u32 + t[1] as u32 + t[2] as u32;
    let darkest = replaced.texels.iter().filter(|t| lum(t) > 0).map(lum).min().unwrap();
    assert!(darkest < 600, "the quad is not white all over: its darkest lit pixel sums to {darkest}");
}
