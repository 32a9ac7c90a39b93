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
