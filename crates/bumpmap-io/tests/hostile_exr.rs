//! OpenEXR files whose headers declare more than they hold: refused from the header, before the
//! decoder allocates for them (issue #23: 8.4 GB asked for by a 341-byte file).

use std::path::Path;

use bumpmap_io::{Channel, DecodeLimits, read_height_field};

/// A small valid EXR (`w`×`h`, float RGB) written by `image`.
fn small_exr(w: u32, h: u32) -> Vec<u8> {
    let img = image::Rgb32FImage::from_fn(w, h, |x, y| image::Rgb([x as f32 / 8.0, y as f32 / 8.0, 0.5]));
    let mut bytes = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb32F(img).write_to(&mut bytes, image::ImageFormat::OpenExr).unwrap();
    bytes.into_inner()
}

/// `bytes` with the box2i attribute `name` set to (0, 0)–(w − 1, h − 1), and the optional
/// `chunkCount` attribute (which `image` checks against the window) renamed out of the way, as
/// a hand-made file would not have it.
fn with_window(mut bytes: Vec<u8>, name: &str, w: i32, h: i32) -> Vec<u8> {
    let count = b"chunkCount\0int\0";
    if let Some(at) = bytes.windows(count.len()).position(|k| k == count) {
        bytes[at + 9] = b'X';
    }
    let key = [name.as_bytes(), b"\0box2i\0", &16u32.to_le_bytes()].concat();
    let at = bytes.windows(key.len()).position(|k| k == key).expect("the attribute") + key.len();
    for (i, v) in [0, 0, w - 1, h - 1].into_iter().enumerate() {
        bytes[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
    }
    bytes
}

fn refused(bytes: &[u8], expect: &str) {
    let name = Path::new("hostile.exr");
    let e = read_height_field(bytes, name, Channel::Red, &DecodeLimits::default()).unwrap_err().to_string();
    assert!(e.contains("hostile.exr") && e.contains(expect), "must say '{expect}': {e}");
}

#[test]
fn a_header_that_declares_more_than_the_file_holds_is_refused_before_decoding() {
    let ok = small_exr(8, 8);
    let field = read_height_field(&ok, Path::new("ok.exr"), Channel::Red, &DecodeLimits::default()).unwrap();
    assert_eq!((field.width(), field.height()), (8, 8));
    // A 700,000,000×1 data window behind a 1×1 display window (one row: the chunk count holds).
    let wide = with_window(with_window(small_exr(8, 1), "dataWindow", 700_000_000, 1), "displayWindow", 1, 1);
    refused(&wide, "layer 0's data window is 700000000x1 texels; the limit is 16384x16384");
    // A legal 16384² window in a file of a few hundred bytes: thousands of chunks it has not.
    let tall = with_window(with_window(ok, "dataWindow", 16384, 16384), "displayWindow", 16384, 16384);
    assert!(tall.len() < 2000);
    refused(&tall, "chunks of pixels, at least");
}

#[test]
fn heights_too_large_to_differentiate_are_refused_not_flattened() {
    // ±1e20 made every slope's square overflow: each normal came out zero, (128, 128, 128).
    for v in [1e20f32, -1e20, f32::NAN] {
        let img = image::Rgb32FImage::from_fn(4, 4, |x, _| image::Rgb([if x == 2 { v } else { 0.5 }, 0.0, 0.0]));
        let mut bytes = std::io::Cursor::new(Vec::new());
        image::DynamicImage::ImageRgb32F(img).write_to(&mut bytes, image::ImageFormat::OpenExr).unwrap();
        refused(bytes.get_ref(), "the height at texel (2, 0) is");
        refused(bytes.get_ref(), "heights must be finite and within ±1e9");
    }
}

#[test]
fn one_channel_float_tiff_heights_are_read() {
    // What GIS and terrain tools write; `image` refuses it ("color type Unknown(32)").
    let heights: Vec<f32> = (0..6 * 5).map(|i| (i as f32 * 0.37).sin() * 3.0).collect();
    let mut bytes = std::io::Cursor::new(Vec::new());
    tiff::encoder::TiffEncoder::new(&mut bytes)
        .unwrap()
        .write_image::<tiff::encoder::colortype::Gray32Float>(6, 5, &heights)
        .unwrap();
    let name = Path::new("terrain.tif");
    let field = read_height_field(bytes.get_ref(), name, Channel::Luminance, &DecodeLimits::default()).unwrap();
    assert_eq!((field.width(), field.height()), (6, 5));
    assert_eq!(field.to_f32(), heights, "the floats as stored, scene units kept");
    let e = read_height_field(bytes.get_ref(), name, Channel::Green, &DecodeLimits::default()).unwrap_err();
    assert!(e.to_string().contains("has no green channel (it has one float channel)"), "{e}");
    // And a huge value in one is refused like an OpenEXR's.
    let mut bad = heights.clone();
    bad[7] = 1e20;
    let mut bytes = std::io::Cursor::new(Vec::new());
    tiff::encoder::TiffEncoder::new(&mut bytes)
        .unwrap()
        .write_image::<tiff::encoder::colortype::Gray32Float>(6, 5, &bad)
        .unwrap();
    let e = read_height_field(bytes.get_ref(), name, Channel::Red, &DecodeLimits::default()).unwrap_err();
    assert!(e.to_string().contains("the height at texel (1, 1) is 100000000000000000000"), "{e}");
}

#[test]
fn one_channel_openexr_heights_are_read() {
    // A lone `Y` channel, as height data is often stored; `image` refuses it.
    use exr::prelude::*;
    let heights: Vec<f32> = (0..6 * 5).map(|i| (i as f32 * 0.29).cos() * 2.0).collect();
    let channels = AnyChannels::sort(vec![AnyChannel::new("Y", FlatSamples::F32(heights.clone()))].into());
    let image = Image::from_channels((6, 5), channels);
    let mut bytes = std::io::Cursor::new(Vec::new());
    image.write().to_buffered(&mut bytes).unwrap();
    let name = Path::new("terrain.exr");
    let field = read_height_field(bytes.get_ref(), name, Channel::Luminance, &DecodeLimits::default()).unwrap();
    assert_eq!((field.width(), field.height()), (6, 5));
    assert_eq!(field.to_f32(), heights, "the floats as stored");
    let e = read_height_field(bytes.get_ref(), name, Channel::Alpha, &DecodeLimits::default()).unwrap_err();
    assert!(e.to_string().contains("has no alpha channel (it has one channel)"), "{e}");
}

#[test]
fn a_one_channel_openexr_is_a_gray_float_map_to_the_map_readers_and_a_nan_in_it_is_named() {
    use bumpmap_io::{AnyTexture, read_any_texture};
    use exr::prelude::*;
    let one_channel = |values: Vec<f32>| {
        let channels = AnyChannels::sort(vec![AnyChannel::new("Y", FlatSamples::F32(values))].into());
        let mut bytes = std::io::Cursor::new(Vec::new());
        Image::from_channels((3, 2), channels).write().to_buffered(&mut bytes).unwrap();
        bytes.into_inner()
    };
    let name = Path::new("h.exr");
    let values = vec![0.0, 0.25, 0.5, 0.75, 1.0, 0.5];
    let AnyTexture::Float(gray) =
        read_any_texture(&one_channel(values.clone()), name, &DecodeLimits::default()).unwrap()
    else {
        panic!("not read as floats")
    };
    assert_eq!(gray.texels, values.iter().map(|&v| [v, v, v, 1.0]).collect::<Vec<_>>());
    let e = read_any_texture(&one_channel(vec![0.0, f32::NAN, 0.5, 0.5, 0.5, 0.5]), name, &DecodeLimits::default())
        .unwrap_err();
    assert!(e.to_string().contains("h.exr") && e.to_string().contains("(1, 0)"), "{e}");
}

#[test]
fn a_tga_has_no_magic_bytes_and_is_named_by_its_extension() {
    // A TGA starts with no signature, so sniffing the bytes finds nothing; the name decides.
    let img = image::GrayImage::from_fn(5, 4, |x, y| image::Luma([(x * 40 + y * 7) as u8]));
    let mut bytes = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageLuma8(img.clone()).write_to(&mut bytes, image::ImageFormat::Tga).unwrap();
    let field = read_height_field(bytes.get_ref(), Path::new("rock.TGA"), Channel::Luminance, &DecodeLimits::default())
        .unwrap();
    assert_eq!((field.width(), field.height()), (5, 4));
    for (got, p) in field.to_f32().iter().zip(img.pixels()) {
        assert!((got - p.0[0] as f32 / 255.0).abs() < 1e-6, "{got} against {}", p.0[0]);
    }
    // The same bytes under a name with no image extension stay unrecognised.
    let e = read_height_field(bytes.get_ref(), Path::new("rock.dat"), Channel::Luminance, &DecodeLimits::default())
        .unwrap_err();
    assert!(e.to_string().contains("rock.dat"), "{e}");
}

/// `--ignored` to write this file's hostile inputs as fuzz seeds (first byte 0: heights, read
/// as luminance, as the `image` target reads it): `BUMPMAP_SEED_DIR=fuzz/regressions/image
/// cargo test -p bumpmap-io --test hostile_exr -- --ignored`.
#[test]
#[ignore]
fn write_fuzz_seeds() {
    let dir = std::path::PathBuf::from(std::env::var("BUMPMAP_SEED_DIR").unwrap_or("/tmp".into()));
    let ok = small_exr(8, 8);
    let wide = with_window(with_window(small_exr(8, 1), "dataWindow", 700_000_000, 1), "displayWindow", 1, 1);
    let tall = with_window(with_window(ok.clone(), "dataWindow", 16384, 16384), "displayWindow", 16384, 16384);
    let mut huge = std::io::Cursor::new(Vec::new());
    let img = image::Rgb32FImage::from_fn(4, 4, |x, _| image::Rgb([if x == 2 { 1e20 } else { 0.5 }, 0.0, 0.0]));
    image::DynamicImage::ImageRgb32F(img).write_to(&mut huge, image::ImageFormat::OpenExr).unwrap();
    let mut y_only = std::io::Cursor::new(Vec::new());
    {
        use exr::prelude::*;
        let heights: Vec<f32> = (0..6 * 5).map(|i| i as f32).collect();
        let channels = AnyChannels::sort(vec![AnyChannel::new("Y", FlatSamples::F32(heights))].into());
        Image::from_channels((6, 5), channels).write().to_buffered(&mut y_only).unwrap();
    }
    let mut tiff = std::io::Cursor::new(Vec::new());
    let heights: Vec<f32> = (0..6 * 5).map(|i| i as f32 * 0.1).collect();
    tiff::encoder::TiffEncoder::new(&mut tiff)
        .unwrap()
        .write_image::<tiff::encoder::colortype::Gray32Float>(6, 5, &heights)
        .unwrap();
    for (name, bytes) in [
        ("exr_8x8.exr.bin", &ok),
        ("exr_data_window_700m_by_1.exr.bin", &wide),
        ("exr_16384_square_without_chunks.exr.bin", &tall),
        ("exr_height_1e20.exr.bin", huge.get_ref()),
        ("exr_y_channel_only.exr.bin", y_only.get_ref()),
        ("tiff_gray32_float.tif.bin", tiff.get_ref()),
    ] {
        std::fs::write(dir.join(name), [&[0u8][..], bytes].concat()).unwrap();
    }
}

#[test]
fn a_tile_larger_than_any_block_the_limits_allow_is_refused_before_reading_a_chunk() {
    // Found by fuzzing: an 862-byte one-channel EXR whose tiles are declared 64576×16384; the
    // decoder reserved 1.7 GB for its first chunk.
    let path =
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../fuzz/regressions/image/exr_tile_64576x16384_declared.exr.bin");
    let bytes = std::fs::read(path).unwrap();
    refused(&bytes[1..], "blocks of pixels would take");
    let e = read_height_field(&bytes[1..], Path::new("t.exr"), Channel::Luminance, &DecodeLimits::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("the limit is 256.0 MiB"), "{e}");
}
