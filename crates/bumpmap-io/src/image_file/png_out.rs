//! PNG out: 8-bit grey, RGB and RGBA through `image`, 16-bit and animated (APNG) through `png`,
//! each staged into a [`FileSet`] so a command writes all its files or none; and the names of a
//! mip chain's level files.
//!
//! What this module does not do: read (the rest of `image_file`), or write any other format
//! (`texture_file` writes DDS and KTX2).

use std::path::Path;

use crate::atomic::FileSet;
use crate::error::IoError;

/// Pixel layouts [`save_png`] writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PngLayout {
    /// 8-bit grey.
    Gray8,
    /// 8-bit RGB.
    Rgb8,
    /// 8-bit RGBA.
    Rgba8,
}

/// Writes an 8- or 16-bit PNG atomically. `bytes` holds `width·height` pixels, row 0 first.
pub fn save_png(path: &Path, width: usize, height: usize, layout: PngLayout, bytes: &[u8]) -> Result<(), IoError> {
    let mut set = FileSet::new(&[]);
    save_png_into(&mut set, path, width, height, layout, bytes)?;
    set.commit().map(|_| ())
}

/// [`save_png`] as one file of a [`FileSet`].
pub fn save_png_into(
    set: &mut FileSet,
    path: &Path,
    width: usize,
    height: usize,
    layout: PngLayout,
    bytes: &[u8],
) -> Result<(), IoError> {
    set.write(path, |w| write_png(w, width, height, layout, bytes))
}

/// The bytes [`save_png`] writes, in memory (what a web page offers to save).
pub fn png_file_bytes(width: usize, height: usize, layout: PngLayout, bytes: &[u8]) -> Result<Vec<u8>, IoError> {
    let mut out = Vec::new();
    write_png(&mut out, width, height, layout, bytes)
        .map_err(|e| IoError::Texture { path: "a PNG in memory".into(), reason: e.to_string() })?;
    Ok(out)
}

/// The 8-bit PNG encoding of the files this crate writes: fast compression, adaptive filters.
fn write_png(
    w: impl std::io::Write,
    width: usize,
    height: usize,
    layout: PngLayout,
    bytes: &[u8],
) -> std::io::Result<()> {
    use image::ImageEncoder;
    let color = match layout {
        PngLayout::Gray8 => image::ExtendedColorType::L8,
        PngLayout::Rgb8 => image::ExtendedColorType::Rgb8,
        PngLayout::Rgba8 => image::ExtendedColorType::Rgba8,
    };
    debug_assert_eq!(bytes.len(), width * height * color.bits_per_pixel() as usize / 8);
    image::codecs::png::PngEncoder::new_with_quality(
        w,
        image::codecs::png::CompressionType::Fast,
        image::codecs::png::FilterType::Adaptive,
    )
    .write_image(bytes, width as u32, height as u32, color)
    .map_err(std::io::Error::other)
}

/// An 8-bit PNG's bytes in memory (a texture carried inside a glTF's buffer, say): `bytes`
/// holds `width·height` pixels, row 0 first.
pub fn png_bytes(width: usize, height: usize, layout: PngLayout, bytes: &[u8]) -> Result<Vec<u8>, IoError> {
    use image::ImageEncoder;
    let color = match layout {
        PngLayout::Gray8 => image::ExtendedColorType::L8,
        PngLayout::Rgb8 => image::ExtendedColorType::Rgb8,
        PngLayout::Rgba8 => image::ExtendedColorType::Rgba8,
    };
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(bytes, width as u32, height as u32, color)
        .map_err(|e| IoError::Texture { path: "a PNG in memory".into(), reason: e.to_string() })?;
    Ok(out)
}

/// Stages an animated PNG (APNG) into `set`: `frames`, each `width`×`height` 8-bit RGB (row 0
/// first), shown `delay_ms` milliseconds each and looped forever. The first frame is also the
/// still image a reader without APNG support shows.
pub fn save_apng_into(
    set: &mut FileSet,
    path: &Path,
    width: usize,
    height: usize,
    frames: &[Vec<u8>],
    delay_ms: u16,
) -> Result<(), IoError> {
    debug_assert!(frames.iter().all(|f| f.len() == width * height * 3));
    set.write(path, |w| {
        let err = std::io::Error::other;
        let mut encoder = png::Encoder::new(w, width as u32, height as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        // Made to be shared (a README, a report): a smaller file is worth the encoder's time.
        encoder.set_compression(png::Compression::Balanced);
        encoder.set_animated(frames.len() as u32, 0).map_err(err)?;
        encoder.set_frame_delay(delay_ms, 1000).map_err(err)?;
        let mut writer = encoder.write_header().map_err(err)?;
        for frame in frames {
            writer.write_image_data(frame).map_err(err)?;
        }
        writer.finish().map_err(err)
    })
}

/// Stages a 16-bit RGBA PNG into `set`.
pub fn save_png16_into(set: &mut FileSet, path: &Path, image: &bumpmap_math::Rgba16Image) -> Result<(), IoError> {
    save_png16_samples_into(set, path, image.width, image.height, Png16::Rgba, image.texels.as_flattened())
}

/// The colour types [`save_png16_samples_into`] writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Png16 {
    /// One channel.
    Gray,
    /// Three channels.
    Rgb,
    /// Four channels.
    Rgba,
}

/// Stages a 16-bit PNG of `width`×`height` pixels of `color`'s channels (`samples`, row 0
/// first) into `set`.
pub fn save_png16_samples_into(
    set: &mut FileSet,
    path: &Path,
    width: usize,
    height: usize,
    color: Png16,
    samples: &[u16],
) -> Result<(), IoError> {
    set.write(path, |w| write_png16(w, width, height, color, samples))
}

/// The bytes [`save_png16_samples_into`] writes, in memory (what a web page offers to save).
pub fn png16_file_bytes(width: usize, height: usize, color: Png16, samples: &[u16]) -> Result<Vec<u8>, IoError> {
    let mut out = Vec::new();
    write_png16(&mut out, width, height, color, samples)
        .map_err(|e| IoError::Texture { path: "a PNG in memory".into(), reason: e.to_string() })?;
    Ok(out)
}

/// The 16-bit PNG encoding of the files this crate writes: fast compression, adaptive filters,
/// a row at a time (PNG stores each channel big-endian), so no second copy of the image is made.
fn write_png16(
    w: impl std::io::Write,
    width: usize,
    height: usize,
    color: Png16,
    samples: &[u16],
) -> std::io::Result<()> {
    let (color, channels) = match color {
        Png16::Gray => (png::ColorType::Grayscale, 1),
        Png16::Rgb => (png::ColorType::Rgb, 3),
        Png16::Rgba => (png::ColorType::Rgba, 4),
    };
    debug_assert_eq!(samples.len(), width * height * channels);
    let mut encoder = png::Encoder::new(w, width as u32, height as u32);
    encoder.set_color(color);
    encoder.set_depth(png::BitDepth::Sixteen);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    let mut stream = writer.stream_writer_with_size(1 << 20).map_err(std::io::Error::other)?;
    let mut row = Vec::with_capacity(width * channels * 2);
    for texels in samples.chunks_exact((width * channels).max(1)) {
        row.clear();
        row.extend(texels.iter().flat_map(|c| c.to_be_bytes()));
        std::io::Write::write_all(&mut stream, &row)?;
    }
    stream.finish().map_err(std::io::Error::other)
}

/// The file of level `k` of a PNG output `out`: `out` itself for level 0, then `n.mip1.png`,
/// `n.mip2.png`, … beside it (`n` its stem): how `bumpmap normalmap` writes a mip chain as
/// PNG files and how its readers find the levels.
pub fn level_path(out: &Path, k: usize) -> std::path::PathBuf {
    if k == 0 {
        return out.to_path_buf();
    }
    let stem = out.file_stem().unwrap_or_default().to_string_lossy();
    out.with_file_name(format!("{stem}.mip{k}.png"))
}
