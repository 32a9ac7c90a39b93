//! `bumpmap normalmap` and `bumpmap cubemap` end to end: outputs, and bad input failing cleanly.

mod common;

use common::*;

#[test]
fn png_with_mips_writes_every_level() {
    let dir = scratch("png_with_mips");
    let input = dir.join("h.png");
    write_gray_png(&input, 12, 5, |x, y| ((x * 20 + y * 7) % 256) as u8);
    let out = dir.join("n.png");
    let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--mips"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // 12×5 → 6×2 → 3×1 → 1×1.
    assert_eq!(listing(&dir), ["h.png", "n.mip1.png", "n.mip2.png", "n.mip3.png", "n.png"]);
    let sizes: Vec<_> = ["n.png", "n.mip1.png", "n.mip2.png", "n.mip3.png"]
        .iter()
        .map(|f| image::image_dimensions(dir.join(f)).unwrap())
        .collect();
    assert_eq!(sizes, [(12, 5), (6, 2), (3, 1), (1, 1)]);
    let level0 = image::open(&out).unwrap().to_rgba8();
    assert!(level0.pixels().all(|p| p.0[3] == 255), "level 0 alpha is 255");
    assert!(level0.pixels().any(|p| p.0[0] != 128), "a sloped field must tilt normals");
}

#[test]
fn one_by_one_image_is_a_flat_normal() {
    let dir = scratch("one_by_one");
    let input = dir.join("one.png");
    write_gray_png(&input, 1, 1, |_, _| 77);
    let out = dir.join("n.png");
    let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--mips"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(&out).unwrap().to_rgba8();
    assert_eq!(img.dimensions(), (1, 1));
    assert_eq!(img.get_pixel(0, 0).0, [128, 128, 255, 255], "a wrapped 1×1 field has no slope");
    assert_eq!(listing(&dir), ["n.png", "one.png"], "a 1×1 chain has only level 0");
}

/// `normalmap IN -o out.png` must fail cleanly, naming IN.
fn fails(dir: &std::path::Path, input: &std::path::Path, expect: &str) {
    let out = dir.join("out.png");
    fails_cleanly(dir, &["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap()], input, expect);
}

#[test]
fn bad_inputs_fail_with_a_clear_message_and_no_output() {
    let dir = scratch("bad_inputs");
    let good = dir.join("good.png");
    write_gray_png(&good, 64, 64, |x, y| (x ^ y) as u8);
    let bytes = std::fs::read(&good).unwrap();

    let truncated = dir.join("truncated.png");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    fails(&dir, &truncated, "not a readable image");

    let corrupt = dir.join("corrupt.png");
    std::fs::write(&corrupt, b"this is not an image at all, just text").unwrap();
    fails(&dir, &corrupt, "not a readable image");

    let empty = dir.join("empty.png");
    std::fs::write(&empty, png_header_only(0, 0)).unwrap();
    fails(&dir, &empty, "");

    let huge = dir.join("huge.png");
    std::fs::write(&huge, png_header_only(65535, 65535)).unwrap();
    fails(&dir, &huge, "65535x65535");
    // Declared sizes the decoder's own memory limit would refuse first get the size message.
    let giant = dir.join("giant.png");
    std::fs::write(&giant, png_header_only(1 << 30, 1 << 30)).unwrap();
    fails(&dir, &giant, "1073741824x1073741824; the limit is 16384x16384");

    fails(&dir, &dir.join("missing.png"), "cannot read");
}

#[test]
fn output_equal_to_input_is_refused_and_the_input_survives() {
    let dir = scratch("same_path");
    let input = dir.join("h.png");
    write_gray_png(&input, 8, 8, |x, _| x as u8 * 30);
    let before = std::fs::read(&input).unwrap();
    let sneaky = dir.join(".").join("h.png");
    let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", sneaky.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("overwrite the input"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&input).unwrap(), before);
    assert_eq!(listing(&dir), ["h.png"]);
}

#[test]
fn folder_in_folder_out_processes_every_image() {
    let dir = scratch("folder");
    let input = dir.join("in");
    std::fs::create_dir_all(&input).unwrap();
    for i in 0..4 {
        write_gray_png(&input.join(format!("h{i}.png")), 16, 16, |x, y| (x * y * (i + 1)) as u8);
    }
    std::fs::write(input.join("notes.txt"), "not an image").unwrap();
    let out = dir.join("out");
    let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(listing(&out), ["h0.png", "h1.png", "h2.png", "h3.png"]);
}

#[test]
fn presets_and_containers() {
    let dir = scratch("containers");
    for ext in ["dds", "ktx2"] {
        let out = dir.join(format!("b.{ext}"));
        let o = bumpmap(&["normalmap", "bricks@64", "-o", out.to_str().unwrap(), "--mips", "--encoding", "kilgard"]);
        assert!(o.status.success(), "{}", stderr(&o));
        // 64² RGBA8 with 7 levels: 4·(4096+1024+256+64+16+4+1) = 21,844 bytes of texels.
        let len = std::fs::metadata(&out).unwrap().len();
        assert!(len > 21_844 && len < 21_844 + 400, "{ext}: {len} bytes");
    }
    let o = bumpmap(&["normalmap", "bricks", "-o", dir.join("x.jpg").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("unsupported output format"));
}

#[test]
fn cubemap_faces_match_the_library() {
    let dir = scratch("cubemap");
    let o = bumpmap(&["cubemap", "--size", "32", "--encoding", "kilgard", "-o", dir.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(listing(&dir), ["nx.png", "ny.png", "nz.png", "px.png", "py.png", "pz.png"]);
    // The files hold the same bytes as the Cg Toolkit's cube map, face by face.
    let golden = include_bytes!("../../bumpmap-math/tests/golden/cg_toolkit_normcm_32_rgb8.raw");
    for (i, face) in ["px", "nx", "py", "ny", "pz", "nz"].iter().enumerate() {
        let img = image::open(dir.join(format!("{face}.png"))).unwrap().to_rgb8();
        assert_eq!(img.as_raw().as_slice(), &golden[i * 3072..(i + 1) * 3072], "face {face}");
    }
}

/// A 4×4 paletted PNG whose PLTE chunk holds 4 bytes (not a whole RGB entry), CRCs valid.
fn png_with_bad_palette() -> Vec<u8> {
    let chunk = |kind: &[u8], data: &[u8]| {
        let mut c = (data.len() as u32).to_be_bytes().to_vec();
        let body: Vec<u8> = kind.iter().chain(data).copied().collect();
        c.extend_from_slice(&body);
        c.extend_from_slice(&crc32(&body).to_be_bytes());
        c
    };
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&4u32.to_be_bytes());
    ihdr.extend_from_slice(&4u32.to_be_bytes());
    ihdr.extend_from_slice(&[8, 3, 0, 0, 0]);
    // Stored (uncompressed) deflate block of 4 rows of filter byte 0 + 4 indices: 20 bytes.
    let raw = [0u8; 20];
    let mut z = vec![0x78, 0x01, 0x01, 20, 0, !20u8, 0xFF];
    z.extend_from_slice(&raw);
    let adler = {
        let (mut a, mut b) = (1u32, 0u32);
        for &x in &raw {
            a = (a + x as u32) % 65521;
            b = (b + a) % 65521;
        }
        (b << 16) | a
    };
    z.extend_from_slice(&adler.to_be_bytes());
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend(chunk(b"IHDR", &ihdr));
    png.extend(chunk(b"PLTE", &[1, 2, 3, 4]));
    png.extend(chunk(b"IDAT", &z));
    png.extend(chunk(b"IEND", &[]));
    png
}

#[test]
fn a_palette_that_is_not_whole_rgb_entries_is_an_error_not_a_panic() {
    let dir = scratch("bad_palette");
    let input = dir.join("bad.png");
    std::fs::write(&input, png_with_bad_palette()).unwrap();
    let out = dir.join("out.png");
    fails_cleanly(
        &dir,
        &["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap()],
        &input,
        "PLTE chunk of 4 bytes",
    );
    let render_out = dir.join("r.png");
    fails_cleanly(
        &dir,
        &["render", "--size", "16", "--height-field", input.to_str().unwrap(), "-o", render_out.to_str().unwrap()],
        &input,
        "PLTE chunk of 4 bytes",
    );
}

#[test]
fn misspelt_presets_say_what_is_wrong_with_them() {
    let dir = scratch("bad_presets");
    let out = dir.join("out.png");
    // A preset's value out of range is a malformed argument (exit 2); a name that is no preset
    // may be a missing file (exit 1).
    for (spec, expect, code) in [
        ("bricks@0", "size 0 is outside 1..=16384", 2),
        ("bricks@100000", "size 100000 is outside 1..=16384", 2),
        ("noise:abc", "noise:SEED takes a whole number, got 'abc'", 2),
        ("foo@64", "unknown preset 'foo'", 1),
        ("teapot", "unknown preset 'teapot'", 1),
    ] {
        let o = bumpmap(&["normalmap", spec, "-o", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(code), "{spec}: {}", stderr(&o));
        assert!(stderr(&o).contains(expect), "{spec}: message must say '{expect}': {}", stderr(&o));
        assert!(listing(&dir).is_empty(), "{spec}: no output");
    }
}

/// The channel value near `at` (within 2 texels along the edge's normal) furthest from 128.
fn strongest(img: &image::RgbaImage, c: usize, texels: impl Iterator<Item = (u32, u32)>) -> u8 {
    texels.map(|(x, y)| img.get_pixel(x, y)[c]).max_by_key(|v| (*v as i32 - 128).abs()).unwrap()
}

#[test]
fn green_and_red_point_as_the_formats_say_on_a_raised_square_as_displayed() {
    let dir = scratch("y_convention");
    let input = dir.join("square.png");
    // Black with a white square in the middle (rows and columns 8..24 of 32).
    write_gray_png(&input, 32, 32, |x, y| if (8..24).contains(&x) && (8..24).contains(&y) { 255 } else { 0 });
    for (convention, top_edge_green_up) in [("opengl", true), ("y-up", true), ("directx", false), ("y-down", false)] {
        let out = dir.join(format!("{convention}.png"));
        let o = bumpmap(&[
            "normalmap",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--y-convention",
            convention,
            "--wrap",
            "clamp",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let img = image::open(&out).unwrap().to_rgba8();
        // The top edge as displayed (first rows of the file): its slope faces up the image.
        let top = strongest(&img, 1, (5..=10).map(|y| (16, y)));
        let bottom = strongest(&img, 1, (21..=26).map(|y| (16, y)));
        // The left edge faces left: red below 128 in every convention; the right edge above.
        let left = strongest(&img, 0, (5..=10).map(|x| (x, 16)));
        let right = strongest(&img, 0, (21..=26).map(|x| (x, 16)));
        assert!(left < 100 && right > 156, "{convention}: red left {left}, right {right}");
        if top_edge_green_up {
            assert!(top > 156 && bottom < 100, "{convention}: green must point up: top {top}, bottom {bottom}");
        } else {
            assert!(top < 100 && bottom > 156, "{convention}: green must point down: top {top}, bottom {bottom}");
        }
        // The flat middle is (128, 128, 255).
        let mid = img.get_pixel(16, 16);
        assert!((mid[0] as i32 - 128).abs() <= 1 && (mid[1] as i32 - 128).abs() <= 1 && mid[2] == 255, "{mid:?}");
    }
}

#[test]
fn compressed_formats_need_a_container_that_holds_them() {
    let dir = scratch("bc_formats");
    let png = dir.join("n.png");
    let o = bumpmap(&["normalmap", "bricks@32", "--format", "bc5", "-o", png.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("needs a .dds or .ktx2 output"), "{}", stderr(&o));
    assert!(listing(&dir).is_empty(), "nothing written");
    // texconv's names are accepted; the file says BC7 in its DX10 header.
    let dds = dir.join("n.dds");
    let o = bumpmap(&["normalmap", "bricks@32", "--mips", "--format", "BC7_UNORM", "-o", dds.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = std::fs::read(&dds).unwrap();
    assert_eq!(&bytes[84..88], b"DX10");
    assert_eq!(u32::from_le_bytes(bytes[128..132].try_into().unwrap()), 98, "DXGI_FORMAT_BC7_UNORM");
    // 32² with 6 levels: 64 + 16 + 4 + 1 + 1 + 1 blocks of 16 bytes after the 148-byte header.
    assert_eq!(bytes.len(), 148 + 16 * (64 + 16 + 4 + 1 + 1 + 1));
}

#[test]
fn sixteen_bit_outputs_are_the_eight_bit_map_with_more_bits() {
    let dir = scratch("bits16");
    let input = dir.join("square.png");
    write_gray_png(&input, 32, 32, |x, y| if (8..24).contains(&x) && (8..24).contains(&y) { 255 } else { 0 });
    let (p8, p16) = (dir.join("n8.png"), dir.join("n16.png"));
    for (out, bits) in [(&p8, "8"), (&p16, "16")] {
        let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--mips", "--bits", bits]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    // Every level is a 16-bit RGBA PNG whose channels round to the 8-bit file's within a step.
    for k in 0..6 {
        let name = |p: &std::path::Path| {
            if k == 0 {
                p.to_path_buf()
            } else {
                dir.join(format!("{}.mip{k}.png", p.file_stem().unwrap().to_str().unwrap()))
            }
        };
        let wide = image::open(name(&p16)).unwrap();
        assert_eq!(wide.color(), image::ColorType::Rgba16, "level {k}");
        let narrow = image::open(name(&p8)).unwrap().to_rgba8();
        let wide = wide.to_rgba16();
        let mut finer = 0;
        for (a, b) in narrow.pixels().zip(wide.pixels()) {
            for c in 0..4 {
                let rounded = (b[c] as u32 + 128) / 257;
                assert!(rounded.abs_diff(a[c] as u32) <= 1, "level {k}: {a:?} vs {b:?}");
                finer += (b[c] % 257 != 0) as usize;
            }
        }
        if k == 0 {
            assert!(finer > 0, "the 16-bit file holds values no byte can");
            // Green up at the square's top edge as displayed, as in the 8-bit file.
            let top = (5..=10).map(|y| wide.get_pixel(16, y)[1]).max().unwrap();
            assert!(top > 40000, "top edge green {top}");
        }
    }
    // Containers: R16G16B16A16_UNORM with every level.
    let ktx = dir.join("n.ktx2");
    let o = bumpmap(&["normalmap", "bricks@32", "--mips", "--bits", "16", "-o", ktx.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = std::fs::read(&ktx).unwrap();
    assert_eq!(u32::from_le_bytes(bytes[12..16].try_into().unwrap()), 91, "VK_FORMAT_R16G16B16A16_UNORM");
    assert_eq!(u32::from_le_bytes(bytes[40..44].try_into().unwrap()), 6, "levels");
    let dds = dir.join("n.dds");
    let o = bumpmap(&["normalmap", "bricks@32", "--format", "R16G16B16A16_UNORM", "-o", dds.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = std::fs::read(&dds).unwrap();
    assert_eq!(u32::from_le_bytes(bytes[128..132].try_into().unwrap()), 11, "DXGI_FORMAT_R16G16B16A16_UNORM");
    assert_eq!(bytes.len(), 148 + 8 * 32 * 32);
    // BC formats are 8-bit: asking for both is a usage error, and nothing is written.
    let before = listing(&dir);
    let o = bumpmap(&[
        "normalmap",
        "bricks@32",
        "--bits",
        "16",
        "--format",
        "bc5",
        "-o",
        dir.join("x.dds").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--bits 16"), "{}", stderr(&o));
    let o = bumpmap(&["normalmap", "bricks@32", "--bits", "12", "-o", dir.join("x.png").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(listing(&dir), before);
}

/// Writes a one-channel float height field as an RGB OpenEXR file (R = G = B = h).
fn write_exr(path: &std::path::Path, w: u32, h: u32, f: impl Fn(u32, u32) -> f32) {
    let img = image::Rgb32FImage::from_fn(w, h, |x, y| image::Rgb([f(x, y); 3]));
    image::DynamicImage::ImageRgb32F(img).save(path).unwrap();
}

#[test]
fn exr_heights_are_read_as_stored_in_float() {
    let dir = scratch("exr");
    // The same ramp-and-square field twice: in [0, 2] scene units in float, and in [0, 1] as a
    // 16-bit PNG. Half the scale on twice the heights must give the same normals.
    let height = |x: u32, y: u32| if (8..24).contains(&x) && (8..24).contains(&y) { 1.0 } else { x as f32 / 64.0 };
    let exr = dir.join("h.exr");
    write_exr(&exr, 32, 32, |x, y| 2.0 * height(x, y));
    let png = dir.join("h16.png");
    let wide = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(32, 32, |x, y| {
        image::Luma([(height(x, y) * 65535.0).round() as u16])
    });
    wide.save(&png).unwrap();
    let (a, b) = (dir.join("a.png"), dir.join("b.png"));
    let o = bumpmap(&["normalmap", exr.to_str().unwrap(), "-o", a.to_str().unwrap(), "--scale", "2", "--bits", "16"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = bumpmap(&["normalmap", png.to_str().unwrap(), "-o", b.to_str().unwrap(), "--scale", "4", "--bits", "16"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (a, b) = (image::open(&a).unwrap().to_rgba16(), image::open(&b).unwrap().to_rgba16());
    let worst = a.pixels().zip(b.pixels()).flat_map(|(p, q)| (0..3).map(move |c| p[c].abs_diff(q[c]))).max().unwrap();
    // The PNG's heights are quantized to 1/65535; its normals differ from the float ones by
    // far less than one 8-bit step (257).
    assert!(worst < 64, "largest difference {worst} of 65535");
    let top = (5..=10).map(|y| a.get_pixel(16, y)[1]).max().unwrap();
    assert!(top > 40000, "the square's top edge faces up the image: green {top}");

    // A NaN height is an error naming the file and the texel, and nothing is written.
    let bad = dir.join("nan.exr");
    write_exr(&bad, 8, 8, |x, y| if (x, y) == (3, 5) { f32::NAN } else { 0.0 });
    let out = dir.join("nan.png");
    fails_cleanly(
        &dir,
        &["normalmap", bad.to_str().unwrap(), "-o", out.to_str().unwrap()],
        &bad,
        "texel (3, 5) is NaN",
    );
}

#[test]
fn roughness_out_is_written_with_the_normal_map_or_not_at_all() {
    let dir = scratch("normalmap_roughness_out");
    let (n, r) = (dir.join("n.png"), dir.join("r.ktx2"));
    let o = bumpmap(&[
        "normalmap",
        "bricks@64",
        "-o",
        n.to_str().unwrap(),
        "--mips",
        "--roughness-out",
        r.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let texture = bumpmap_io::load_texture(&r).unwrap();
    let bumpmap_io::StoredLevels::Rgba8(levels) = &texture.levels else { panic!("RGBA8 levels") };
    assert_eq!(levels.len(), 7, "a roughness level for each normal-map level, 64² to 1²");
    assert!(levels[0].texels.iter().all(|t| t[0] == 128), "level 0: the default roughness 0.5 everywhere");
    assert!(levels[2].texels.iter().any(|t| t[0] > 140), "the mortar's edges spread the normals: rougher");

    // Refused before any work, nothing written: no --mips, the normal map's own file, a folder,
    // a value out of range; an output format it cannot write leaves neither file.
    let fresh = scratch("normalmap_roughness_refused");
    let (n, r) = (fresh.join("n.png"), fresh.join("r.png"));
    for (args, code) in [
        (vec!["--roughness-out", r.to_str().unwrap()], 2),
        (vec!["--mips", "--roughness-out", n.to_str().unwrap()], 2),
        (vec!["--mips", "--roughness-out", r.to_str().unwrap(), "--roughness", "1.5"], 2),
        (vec!["--mips", "--roughness-out", fresh.join("r.jpg").to_str().unwrap()], 1),
    ] {
        let mut all = vec!["normalmap", "bricks@64", "-o", n.to_str().unwrap()];
        all.extend(args.iter().copied());
        let o = bumpmap(&all);
        assert_eq!(o.status.code(), Some(code), "{all:?}: {}", stderr(&o));
        assert!(listing(&fresh).is_empty(), "{all:?} left {:?}", listing(&fresh));
    }
    let o = bumpmap(&[
        "normalmap",
        dir.to_str().unwrap(),
        "-o",
        fresh.join("out/").to_str().unwrap(),
        "--mips",
        "--roughness-out",
        r.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("not a folder"), "{}", stderr(&o));
}

#[test]
fn lean_out_writes_two_float_textures_with_the_normal_map_or_nothing() {
    let dir = scratch("normalmap_lean_out");
    let (n, l) = (dir.join("n.png"), dir.join("l.ktx2"));
    let o =
        bumpmap(&["normalmap", "dimples@32", "-o", n.to_str().unwrap(), "--mips", "--lean-out", l.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The ktx2 crate reads them: float levels, one for each of the normal map's (32² to 1²).
    for path in [l.clone(), dir.join("l.mxy-j.ktx2")] {
        let bytes = std::fs::read(&path).unwrap();
        let reader = ktx2::Reader::new(&bytes[..]).expect("valid KTX2");
        assert_eq!(reader.header().format, Some(ktx2::Format::R32G32B32A32_SFLOAT), "{}", path.display());
        assert_eq!(reader.header().level_count, 6);
    }
    // From the 8-bit map `render` draws from, whatever depth the normal map is written at.
    let l16 = dir.join("l16.ktx2");
    let o = bumpmap(&[
        "normalmap",
        "dimples@32",
        "-o",
        dir.join("n16.png").to_str().unwrap(),
        "--bits",
        "16",
        "--mips",
        "--lean-out",
        l16.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(&l16).unwrap(), std::fs::read(&l).unwrap(), "the same moments at --bits 16");
    // Refused before any work, nothing written: PNG cannot hold floats, no --mips, the normal
    // map's own file, a folder of height fields.
    let fresh = scratch("normalmap_lean_refused");
    let (n, l_png, l_dds) = (fresh.join("n.png"), fresh.join("l.png"), fresh.join("l.dds"));
    let (n, l_png, l_dds) = (n.to_str().unwrap(), l_png.to_str().unwrap(), l_dds.to_str().unwrap());
    for (args, says) in [
        (vec!["-o", n, "--mips", "--lean-out", l_png], "which .ktx2 or .dds hold"),
        (vec!["-o", n, "--lean-out", l_dds], "--mips"),
        (vec!["-o", l_dds, "--mips", "--format", "bc7", "--lean-out", l_dds], "is another output's file"),
    ] {
        let mut all = vec!["normalmap", "dimples@32"];
        all.extend(args.iter().copied());
        let o = bumpmap(&all);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{all:?}: {}", stderr(&o));
        assert!(listing(&fresh).is_empty(), "{all:?} left {:?}", listing(&fresh));
    }
}
