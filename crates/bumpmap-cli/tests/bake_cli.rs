//! `bumpmap bake` end to end: a displaced plane baked onto a flat one, its files read back by
//! independent readers (`image`, `gltf`), and bad input refused with nothing written.

mod common;

use std::path::Path;

use common::*;

/// Writes an OBJ of the unit square (`z = height(x, y)`), `n` quads a side, with `vt` (v up, as
/// OBJ has it) and no normals.
fn square_obj(path: &Path, n: usize, height: impl Fn(f32, f32) -> f32, uvs: bool) {
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f32 / n as f32, j as f32 / n as f32);
            text += &format!("v {x} {y} {}\n", height(x, y));
            if uvs {
                text += &format!("vt {x} {}\n", 1.0 - y);
            }
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i + 1;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            if uvs {
                text += &format!("f {a}/{a} {b}/{b} {c}/{c}\nf {a}/{a} {c}/{c} {d}/{d}\n");
            } else {
                text += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
            }
        }
    }
    std::fs::write(path, text).unwrap();
}

fn waves(x: f32, y: f32) -> f32 {
    use std::f32::consts::TAU;
    0.03 * (TAU * 2.0 * x).sin() * (TAU * 3.0 * y).cos()
}

#[test]
fn a_bake_writes_its_map_mask_and_low_poly_glb() {
    let dir = scratch("bake_files");
    let (high, low) = (dir.join("high.obj"), dir.join("low.obj"));
    square_obj(&high, 96, waves, false);
    square_obj(&low, 1, |_, _| 0.0, true);
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let o = bumpmap(&[
        "bake",
        high.to_str().unwrap(),
        low.to_str().unwrap(),
        "-o",
        &path("n.png"),
        "--size",
        "64",
        "--mask-out",
        &path("mask.png"),
        "--low-out",
        &path("low.glb"),
        "--object-out",
        &path("object.png"),
        "--ao-out",
        &path("ao.png"),
        "--ao-rays",
        "32",
        "--height-out",
        &path("height.png"),
        "--curvature-out",
        &path("curvature.png"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("4096 of 4096 texels"), "{}", stderr(&o));
    // The map, read by the image crate: a tangent-space normal map tilted by the waves, green up.
    let map = image::open(dir.join("n.png")).unwrap().to_rgba8();
    assert_eq!(map.dimensions(), (64, 64));
    let blue_min = map.pixels().map(|p| p[2]).min().unwrap();
    let red: Vec<u8> = map.pixels().map(|p| p[0]).collect();
    assert!(blue_min > 200, "mostly facing out: blue {blue_min}");
    assert!(red.iter().max().unwrap() - red.iter().min().unwrap() > 20, "the waves tilt it");
    let mask = image::open(dir.join("mask.png")).unwrap().to_luma8();
    assert!(mask.pixels().all(|p| p[0] == 255), "every ray hit");
    // The occlusion: open sky mostly, the valleys between the waves a little darker.
    let ao = image::open(dir.join("ao.png")).unwrap().to_luma8();
    let (lo, hi) = ao.pixels().fold((255, 0), |(l, h), p| (p[0].min(l), p[0].max(h)));
    assert!(hi >= 250 && lo < hi, "occlusion from {lo} to {hi}");
    // The displacement, 16 bits over its range, the range beside it: the waves' ±0.03.
    let height = image::open(dir.join("height.png")).unwrap();
    assert!(matches!(height, image::DynamicImage::ImageLuma16(_)), "{:?}", height.color());
    let range_of = |file: &str| -> (f32, f32) {
        let range = std::fs::read_to_string(dir.join(file)).unwrap();
        let number = |key: &str| -> f32 {
            let rest = &range[range.find(key).unwrap() + key.len()..];
            rest.trim_start_matches([':', ' ']).split([',', '}']).next().unwrap().trim().parse().unwrap()
        };
        (number("\"min\""), number("\"max\""))
    };
    let (lo, hi) = range_of("height.range.json");
    assert!((lo + 0.03).abs() < 0.003 && (hi - 0.03).abs() < 0.003, "{lo} {hi}");
    // The curvature, 16 bits over a range symmetric about 0: the waves' mean curvature,
    // −½∇²z, peaks at ½·0.03·((4π)² + (6π)²) ≈ 7.7 on the crests (convex: light) and the
    // troughs (dark); flat on average.
    let (lo, hi) = range_of("curvature.range.json");
    assert!(lo == -hi && (4.0..9.0).contains(&hi), "{lo} {hi}");
    let image::DynamicImage::ImageLuma16(curvature) = image::open(dir.join("curvature.png")).unwrap() else {
        panic!("not 16-bit gray")
    };
    let mean = curvature.pixels().map(|p| p[0] as f64).sum::<f64>() / 4096.0;
    let (darkest, lightest) = curvature.pixels().fold((u16::MAX, 0), |(l, h), p| (p[0].min(l), p[0].max(h)));
    assert!((mean - 32767.5).abs() < 1500.0 && darkest < 8000 && lightest > 57000, "{mean} {darkest} {lightest}");
    // LOW as baked for, read by the gltf crate: its tangents and the map as its normalTexture.
    let (doc, buffers, images) = gltf::import(dir.join("low.glb")).unwrap();
    let prim = doc.meshes().next().unwrap().primitives().next().unwrap();
    let reader = prim.reader(|b| Some(&buffers[b.index()].0[..]));
    assert_eq!(reader.read_tangents().expect("TANGENT").count(), 4);
    assert!(prim.material().normal_texture().is_some());
    assert_eq!((images[0].width, images[0].height), (64, 64));
    assert_eq!(
        listing(&dir),
        [
            "ao.png",
            "curvature.png",
            "curvature.range.json",
            "height.png",
            "height.range.json",
            "high.obj",
            "low.glb",
            "low.obj",
            "mask.png",
            "n.png",
            "object.png"
        ]
    );
}

#[test]
fn a_cage_file_is_where_the_rays_start() {
    let dir = scratch("bake_cage");
    let (high, low, cage, other) =
        (dir.join("high.obj"), dir.join("low.obj"), dir.join("cage.obj"), dir.join("other.obj"));
    square_obj(&high, 32, waves, false);
    square_obj(&low, 1, |_, _| 0.0, true);
    square_obj(&cage, 1, |_, _| 0.1, true);
    square_obj(&other, 2, |_, _| 0.1, true);
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let run = |cage: &Path, out: &str| {
        bumpmap(&[
            "bake",
            &path("high.obj"),
            &path("low.obj"),
            "-o",
            &path(out),
            "--size",
            "32",
            "--cage",
            cage.to_str().unwrap(),
        ])
    };
    let o = run(&cage, "caged.png");
    assert!(o.status.success(), "{}", stderr(&o));
    let o = bumpmap(&[
        "bake",
        &path("high.obj"),
        &path("low.obj"),
        "-o",
        &path("extruded.png"),
        "--size",
        "32",
        "--extrude",
        "0.1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (a, b) = (
        image::open(dir.join("caged.png")).unwrap().to_rgba8(),
        image::open(dir.join("extruded.png")).unwrap().to_rgba8(),
    );
    let worst =
        a.pixels().zip(b.pixels()).map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap()).max().unwrap();
    assert!(worst <= 1, "a cage 0.1 out is --extrude 0.1: {worst}");
    let o = run(&other, "refused.png");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("other.obj: --cage: 9 vertices and 8 triangles"), "{}", stderr(&o));
    assert!(!dir.join("refused.png").exists());
}

#[test]
fn maps_named_by_list_go_beside_the_normal_map_and_an_out_flag_names_its_own() {
    let dir = scratch("bake_maps");
    let (high, low) = (dir.join("high.obj"), dir.join("low.obj"));
    square_obj(&high, 48, waves, false);
    square_obj(&low, 1, |_, _| 0.0, true);
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (h, l) = (path("high.obj"), path("low.obj"));
    let args = ["bake", &h, &l, "-o", &path("n.png"), "--size", "32", "--ao-rays", "8"];
    let o = bumpmap(&[&args[..], &["--maps", "object,ao,height,mask,low", "--mask-out", &path("missed.png")]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        listing(&dir),
        [
            "high.obj",
            "low.obj",
            "missed.png",
            "n.png",
            "n_ao.png",
            "n_height.png",
            "n_height.range.json",
            "n_low.glb",
            "n_object.png",
        ]
    );
    // Each is the map its --*-out flag writes: the object-space normals as RGB, the occlusion
    // gray, the displacement 16-bit gray, LOW a glTF with the map as its normal texture.
    assert!(matches!(image::open(dir.join("n_object.png")).unwrap(), image::DynamicImage::ImageRgb8(_)));
    assert!(matches!(image::open(dir.join("n_ao.png")).unwrap(), image::DynamicImage::ImageLuma8(_)));
    assert!(matches!(image::open(dir.join("n_height.png")).unwrap(), image::DynamicImage::ImageLuma16(_)));
    assert!(gltf::import(dir.join("n_low.glb")).unwrap().0.materials().any(|m| m.normal_texture().is_some()));
    // The same bake with the flag for the occlusion writes the same bytes.
    let o = bumpmap(&[&args[..], &["--ao-out", &path("ao.png")]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(dir.join("ao.png")).unwrap(), std::fs::read(dir.join("n_ao.png")).unwrap());
}

#[test]
fn what_cannot_be_baked_is_refused_with_nothing_written() {
    let dir = scratch("bake_refused");
    let (high, low, bare, far) = (dir.join("high.obj"), dir.join("low.obj"), dir.join("bare.obj"), dir.join("far.obj"));
    square_obj(&high, 16, waves, false);
    square_obj(&low, 1, |_, _| 0.0, true);
    square_obj(&bare, 1, |_, _| 0.0, false);
    square_obj(&far, 16, |_, _| 5.0, false);
    let out = dir.join("n.png");
    let high_before = std::fs::read(&high).unwrap();
    let run = |h: &Path, l: &Path, extra: &[&str]| {
        let mut args =
            vec!["bake", h.to_str().unwrap(), l.to_str().unwrap(), "-o", out.to_str().unwrap(), "--size", "16"];
        args.extend_from_slice(extra);
        bumpmap(&args)
    };
    for (o, status, says) in [
        (run(&high, &bare, &[]), 1, "bare.obj: has no texture coordinates"),
        (run(&far, &low, &[]), 1, "met the high-poly mesh nowhere"),
        (run(&high, &low, &["--spp", "0"]), 2, "--spp"),
        (run(&high, &low, &["--extrude", "-1"]), 2, "--extrude"),
        (run(&high, &low, &["--ao-rays", "5000"]), 2, "--ao-rays"),
        (run(&high, &low, &["--mask-out", out.to_str().unwrap()]), 2, "two outputs of the bake"),
        (run(&high, &low, &["--mask-out", high.to_str().unwrap()]), 1, "high.obj"),
        (run(&high, &low, &["--maps", "ao,bogus"]), 2, "'bogus' for '--maps"),
        (
            run(&high, &low, &["--maps", "mask", "--object-out", dir.join("n_mask.png").to_str().unwrap()]),
            2,
            "two outputs of the bake",
        ),
        (
            run(&high, &low, &["--low-out", dir.join("l.glb").to_str().unwrap(), "--y-convention", "directx"]),
            2,
            "--low-out",
        ),
        (run(&dir.join("missing.obj"), &low, &[]), 1, "missing.obj"),
    ] {
        assert_eq!(o.status.code(), Some(status), "{says}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "wanted '{says}' in: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"));
    }
    assert_eq!(listing(&dir), ["bare.obj", "far.obj", "high.obj", "low.obj"], "nothing written");
    assert_eq!(std::fs::read(&high).unwrap(), high_before, "an input is never replaced");
}

/// A named square of [`parts_obj`]: its name, quads a side, and height.
type Part<'a> = (&'a str, usize, &'a dyn Fn(f32, f32) -> f32);

/// Writes an OBJ of named unit squares, each `o NAME`, `n` quads a side at `z = height(x, y)`;
/// with UVs, each square's in its own column of the layout (`x / parts + column`).
fn parts_obj(path: &Path, parts: &[Part], uvs: bool) {
    let (mut text, mut first) = (String::new(), 1);
    for (column, (name, n, height)) in parts.iter().enumerate() {
        let n = *n;
        text += &format!("o {name}\n");
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (i as f32 / n as f32, j as f32 / n as f32);
                text += &format!("v {x} {y} {}\n", height(x, y));
                if uvs {
                    text += &format!("vt {} {}\n", (x + column as f32) / parts.len() as f32, 1.0 - y);
                }
            }
        }
        for j in 0..n {
            for i in 0..n {
                let a = first + j * (n + 1) + i;
                let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
                text += &if uvs {
                    format!("f {a}/{a} {b}/{b} {c}/{c}\nf {a}/{a} {c}/{c} {d}/{d}\n")
                } else {
                    format!("f {a} {b} {c}\nf {a} {c} {d}\n")
                };
            }
        }
        first += (n + 1) * (n + 1);
    }
    std::fs::write(path, text).unwrap();
}

#[test]
fn parts_matched_by_name_meet_only_their_own() {
    // A wavy part under a flat lid 0.05 above it, both baked from 0.1 in front: unpaired, the
    // part's rays meet the lid first and its half of the map is flat; paired by name, they
    // pass the lid and meet the waves.
    let dir = scratch("bake_match_names");
    let (high, low) = (dir.join("high.obj"), dir.join("low.obj"));
    let lid = |_: f32, _: f32| 0.05;
    let flat = |_: f32, _: f32| 0.0;
    parts_obj(&high, &[("Part_high", 48, &waves), ("lid_HIGH", 1, &lid)], false);
    parts_obj(&low, &[("part_low", 1, &flat), ("Lid_low", 1, &lid)], true);
    let red_spread = |map: &str, extra: &[&str]| {
        let out = dir.join(map);
        let mut args = vec!["bake", high.to_str().unwrap(), low.to_str().unwrap(), "-o", out.to_str().unwrap()];
        args.extend(["--size", "32", "--spp", "1", "--extrude", "0.1", "--max-distance", "0.1"]);
        args.extend(extra);
        let o = bumpmap(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let image = image::open(&out).unwrap().to_rgba8();
        // The part's half of the layout, away from the padding at its edge.
        let red: Vec<u8> =
            image.enumerate_pixels().filter(|(x, _, _)| (2..14).contains(x)).map(|(_, _, p)| p[0]).collect();
        red.iter().max().unwrap() - red.iter().min().unwrap()
    };
    let unpaired = red_spread("unpaired.png", &[]);
    let paired = red_spread("paired.png", &["--match-names"]);
    assert!(unpaired < 4 && paired > 20, "unpaired {unpaired}, paired {paired}");
    // A LOW part without a HIGH part of its name: an error naming it and HIGH's parts.
    parts_obj(&low, &[("part_low", 1, &flat), ("cap_low", 1, &lid)], true);
    let o = bumpmap(&[
        "bake",
        high.to_str().unwrap(),
        low.to_str().unwrap(),
        "-o",
        dir.join("n.png").to_str().unwrap(),
        "--size",
        "16",
        "--match-names",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("'cap_low'") && stderr(&o).contains("'Part_high', 'lid_HIGH'"), "{}", stderr(&o));
    assert!(!dir.join("n.png").exists());
}

#[test]
fn the_displacement_and_curvature_as_exr_are_the_values_themselves() {
    let dir = scratch("bake_exr");
    let (high, low) = (dir.join("high.obj"), dir.join("low.obj"));
    square_obj(&high, 64, waves, false);
    square_obj(&low, 1, |_, _| 0.0, true);
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let o = bumpmap(&[
        "bake",
        high.to_str().unwrap(),
        low.to_str().unwrap(),
        "-o",
        &path("n.png"),
        "--size",
        "32",
        "--spp",
        "1",
        "--height-out",
        &path("height.exr"),
        "--curvature-out",
        &path("curvature.exr"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Read by the OpenEXR crate (headers validated pedantically): one float channel, the
    // values in the meshes' units, not 0..1.
    let values = |name: &str| -> Vec<f32> {
        let file = dir.join(name);
        let meta = exr::meta::MetaData::read_from_file(&file, true).expect("a valid OpenEXR header");
        assert_eq!(meta.headers[0].channels.list[0].sample_type, exr::meta::attribute::SampleType::F32);
        let image = exr::prelude::read_first_flat_layer_from_file(&file).expect("OpenEXR reads it");
        image.layer_data.channel_data.list[0].sample_data.values_as_f32().collect()
    };
    let height = values("height.exr");
    let (lo, hi) = height.iter().fold((f32::MAX, f32::MIN), |(l, h), v| (l.min(*v), h.max(*v)));
    assert!(height.len() == 32 * 32 && (lo + 0.03).abs() < 0.004 && (hi - 0.03).abs() < 0.004, "{lo} {hi}");
    let peak = values("curvature.exr").iter().map(|v| v.abs()).fold(0.0, f32::max);
    assert!((5.0..10.0).contains(&peak), "{peak}");
    assert!(dir.join("height.range.json").exists() && dir.join("curvature.range.json").exists());
}
