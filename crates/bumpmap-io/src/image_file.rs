//! Image files: height fields and colour textures in, PNG out (`image_file/png_out.rs`).
//!
//! Rows are taken in file order: the first row of an image file is texel row 0, which is
//! texture coordinate t = 0 in OpenGL's convention (so a PNG viewer shows t growing downward).
//! Sizes are checked against [`MAX_DIMENSION`] from the header, before any pixel is decoded.

use bumpmap_math::Named;
use std::path::{Path, PathBuf};

use bumpmap_math::{HeightField, HeightPreset, Rgba8Image};
use image::{DynamicImage, ImageFormat, ImageReader, Limits};

use crate::error::IoError;

mod png_out;

pub use png_out::{
    Png16, PngLayout, level_path, png_bytes, png_file_bytes, png16_file_bytes, save_apng_into, save_png, save_png_into,
    save_png16_into, save_png16_samples_into,
};

/// The largest width or height accepted for any image, in or out.
pub const MAX_DIMENSION: u32 = 16384;

/// Which channel of a colour image holds the heights.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Channel {
    /// The grey value of a greyscale image, Rec. 709 luminance of a colour one.
    #[default]
    Luminance,
    /// Red.
    Red,
    /// Green.
    Green,
    /// Blue.
    Blue,
    /// Alpha.
    Alpha,
}

bumpmap_math::named!(Channel {
    Luminance => "luminance": "the grey value, or Rec. 709 luminance of a colour image",
    Red => "red": "red",
    Green => "green": "green",
    Blue => "blue": "blue",
    Alpha => "alpha": "alpha",
});

/// Where a height field comes from: a built-in preset or an image file.
#[derive(Clone, Debug, PartialEq)]
pub enum HeightSource {
    /// A built-in preset, `size`×`size`.
    Preset {
        /// Which preset.
        preset: HeightPreset,
        /// Its side in texels.
        size: usize,
    },
    /// An image file.
    File(PathBuf),
}

/// What [`HeightSource::parse`] reads back: `bricks@512`, or the file's path.
impl std::fmt::Display for HeightSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            HeightSource::Preset { preset, size } => write!(f, "{preset}@{size}"),
            HeightSource::File(path) => write!(f, "{}", path.display()),
        }
    }
}

impl HeightSource {
    /// A preset name (`bricks`, `noise:7`, optionally `@SIZE` as in `bricks@512`) when it parses
    /// as one and no file of that name exists; otherwise a path.
    pub fn parse(spec: &str) -> Self {
        let (name, size) = match spec.rsplit_once('@') {
            Some((n, s)) if s.parse::<usize>().is_ok() => (n, s.parse().unwrap()),
            _ => (spec, HeightPreset::DEFAULT_SIZE),
        };
        match HeightPreset::parse(name) {
            Some(preset) if !Path::new(spec).exists() && size > 0 && size <= MAX_DIMENSION as usize => {
                HeightSource::Preset { preset, size }
            }
            _ => HeightSource::File(PathBuf::from(spec)),
        }
    }

    /// The heights: the preset rendered, or the file's `channel` read (a missing file that
    /// looks like a mistyped preset says why it is neither).
    pub fn load(&self, channel: Channel) -> Result<HeightField, IoError> {
        match self {
            HeightSource::Preset { preset, size } => Ok(preset.render(*size, *size)),
            HeightSource::File(path) if !path.exists() => match preset_hint(&path.to_string_lossy()) {
                Some((hint, out_of_range)) => Err(IoError::NotAPreset { path: path.clone(), hint, out_of_range }),
                None => load_height_field(path, channel),
            },
            HeightSource::File(path) => load_height_field(path, channel),
        }
    }

    /// The file, if this source is one.
    pub fn path(&self) -> Option<&Path> {
        match self {
            HeightSource::File(p) => Some(p),
            HeightSource::Preset { .. } => None,
        }
    }
}

/// Why `spec`, which names no file, is not a preset either — when it looks like an attempt at
/// one (a preset name with a bad `@SIZE`, `noise:` with a bad seed, or a bare word).
fn preset_hint(spec: &str) -> Option<(String, bool)> {
    let sizes = format!("1..={MAX_DIMENSION}");
    if let Some((name, size)) = spec.rsplit_once('@') {
        let known = HeightPreset::parse(name).is_some();
        return Some(match size.parse::<usize>() {
            Ok(n) if known => (format!("size {n} is outside {sizes}"), true),
            Err(_) if known => (format!("'{size}' is not a size ({sizes})"), true),
            _ => (format!("unknown preset '{name}' (use {}, optionally @SIZE)", HeightPreset::NAMES), false),
        });
    }
    if let Some(seed) = spec.strip_prefix("noise:") {
        return Some((format!("noise:SEED takes a whole number, got '{seed}'"), true));
    }
    let bare = !spec.contains(['.', '/', '\\']);
    bare.then(|| (format!("unknown preset '{spec}' (use {}, optionally @SIZE)", HeightPreset::NAMES), false))
}

/// How much one image decode may take: the largest width or height, and the largest single
/// allocation the decoder may make. The command line uses [`DecodeLimits::default`]; an
/// embedding program (or a fuzzer) can be stricter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DecodeLimits {
    /// The largest width or height, in texels (at most [`MAX_DIMENSION`]).
    pub max_dimension: u32,
    /// The largest allocation the decoder may make, in bytes.
    pub max_alloc: u64,
}

impl Default for DecodeLimits {
    /// [`MAX_DIMENSION`] texels a side, 4 GiB at most (a 16384² RGBA image at 16 bits is 2 GiB).
    fn default() -> Self {
        Self { max_dimension: MAX_DIMENSION, max_alloc: 4 << 30 }
    }
}

/// The largest block of pixels an OpenEXR may declare: a DWAB block (256 scan lines) of 16384
/// RGBA floats is 64 MiB; a tile as large as a 16384² image would be 4 GiB.
const MAX_EXR_BLOCK: u64 = 256 << 20;

/// Something an image can be decoded from more than once (the header is read first, alone).
trait Source {
    type Reader: std::io::BufRead + std::io::Seek;
    fn open(&self) -> std::io::Result<Self::Reader>;
    /// Its length in bytes.
    fn len(&self) -> std::io::Result<u64>;
}

impl Source for &Path {
    type Reader = std::io::BufReader<std::fs::File>;
    fn open(&self) -> std::io::Result<Self::Reader> {
        // A FIFO or a device would block the open, or never end; a folder is no image.
        if !std::fs::metadata(self)?.is_file() {
            return Err(std::io::Error::other("not a regular file (a folder, a FIFO or a device)"));
        }
        std::fs::File::open(self).map(std::io::BufReader::new)
    }
    fn len(&self) -> std::io::Result<u64> {
        std::fs::metadata(self).map(|m| m.len())
    }
}

impl<'a> Source for &'a [u8] {
    type Reader = std::io::Cursor<&'a [u8]>;
    fn open(&self) -> std::io::Result<Self::Reader> {
        Ok(std::io::Cursor::new(self))
    }
    fn len(&self) -> std::io::Result<u64> {
        Ok(<[u8]>::len(self) as u64)
    }
}

/// OpenEXR's magic number.
const EXR_MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// Checks an OpenEXR file's every layer against the limits and against the file's length
/// before the decoder allocates for it. The decoder sizes its buffers by each layer's data
/// window, which may be far larger than the display window it reports as the image's size (a
/// 341-byte file declared a 700,000,000×1 data window in a 1×1 display window); and every
/// chunk of pixels costs at least 16 bytes in the file (its offset-table entry and its own
/// header), so a file shorter than that declares pixels it does not have.
fn check_exr(
    mut reader: impl std::io::BufRead,
    file_len: u64,
    name: &Path,
    limits: &DecodeLimits,
) -> Result<(), IoError> {
    let max = limits.max_dimension.min(MAX_DIMENSION);
    let max_block = limits.max_alloc.min(MAX_EXR_BLOCK);
    let mut magic = [0u8; 4];
    if reader.read_exact(&mut magic).is_err() || magic != EXR_MAGIC {
        return Ok(());
    }
    let bad = |reason: String| IoError::Decode { path: name.to_path_buf(), reason };
    let meta = exr::meta::MetaData::read_from_buffered(std::io::Read::chain(&magic[..], reader), false)
        .map_err(|e| bad(format!("OpenEXR header: {e}")))?;
    let mut chunks = 0u64;
    for (i, header) in meta.headers.iter().enumerate() {
        let (w, h) = (header.layer_size.0 as u64, header.layer_size.1 as u64);
        if w > max as u64 || h > max as u64 {
            return Err(bad(format!(
                "layer {i}'s data window is {w}x{h} texels; the limit is {max}x{max} (whatever the display window says)"
            )));
        }
        // The decoder reserves up to a block's uncompressed size for each chunk before reading
        // it, whatever the chunk's own length: a tile declared 64576×16384 took 1.7 GB.
        // exr's `Header::max_block_byte_size`, in saturating arithmetic (a hostile tile size
        // times many channels overflows it).
        let texels = match header.blocks {
            exr::meta::BlockDescription::Tiles(t) => (t.tile_size.0 as u64).saturating_mul(t.tile_size.1 as u64),
            exr::meta::BlockDescription::ScanLines => {
                (header.compression.scan_lines_per_block() as u64).saturating_mul(w)
            }
        };
        let block = texels.saturating_mul(header.channels.bytes_per_pixel as u64);
        if block > max_block {
            return Err(bad(format!(
                "layer {i}'s blocks of pixels would take {} each (its tiles or scan-line blocks and {} bytes a texel); the limit is {}",
                bumpmap_math::buffer::Bytes(block),
                header.channels.bytes_per_pixel,
                bumpmap_math::buffer::Bytes(max_block)
            )));
        }
        chunks = chunks.saturating_add(header.chunk_count as u64);
    }
    if chunks.saturating_mul(16) > file_len {
        return Err(bad(format!(
            "declares {chunks} chunks of pixels, at least {} bytes, but the file has {file_len}: it is cut short or its header lies",
            chunks.saturating_mul(16)
        )));
    }
    Ok(())
}

/// Decodes the image from `source`; `name` is the file the errors name.
fn decode(source: impl Source, name: &Path, limits: &DecodeLimits) -> Result<DynamicImage, IoError> {
    let read_err = |source| IoError::Read { path: name.to_path_buf(), source };
    // The magic bytes first; a TGA has none, so its extension names it when they say nothing.
    let open = || {
        let mut reader = ImageReader::new(source.open().map_err(read_err)?).with_guessed_format().map_err(read_err)?;
        if reader.format().is_none()
            && let Ok(format) = ImageFormat::from_path(name)
        {
            reader.set_format(format);
        }
        Ok::<_, IoError>(reader)
    };
    let bad = |e: image::ImageError| IoError::Decode { path: name.to_path_buf(), reason: e.to_string() };
    // The header alone, without the decoder's own memory limit, so a huge declared size is
    // reported as a size against MAX_DIMENSION rather than as "memory limit exceeded".
    let mut header = open()?;
    header.no_limits();
    let decoder = header.into_decoder().map_err(bad)?;
    let (width, height) = image::ImageDecoder::dimensions(&decoder);
    let decoded_bytes = image::ImageDecoder::total_bytes(&decoder);
    drop(decoder);
    if width == 0 || height == 0 {
        return Err(IoError::Empty { path: name.to_path_buf(), width, height });
    }
    let max = limits.max_dimension.min(MAX_DIMENSION);
    if width > max || height > max {
        return Err(IoError::TooLarge { path: name.to_path_buf(), width: width as u64, height: height as u64, max });
    }
    // The decoder's buffer is not asked for fallibly: check up front that it fits, with a
    // conversion's copy of it and a float per texel (what a height field or RGBA8 copy takes).
    let needed = decoded_bytes.saturating_mul(2).saturating_add(width as u64 * height as u64 * 4);
    bumpmap_math::buffer::ensure_available(needed, "decoding it")
        .map_err(|source| IoError::OutOfMemory { path: name.to_path_buf(), source })?;
    check_png_palette(source.open().map_err(read_err)?, name)?;
    check_exr(source.open().map_err(read_err)?, source.len().map_err(read_err)?, name, limits)?;
    let mut reader = open()?;
    let mut image_limits = Limits::default();
    image_limits.max_image_width = Some(max);
    image_limits.max_image_height = Some(max);
    image_limits.max_alloc = Some(limits.max_alloc);
    reader.limits(image_limits);
    reader.decode().map_err(bad)
}

/// Decodes the image file at `path` (see [`DecodeLimits::default`]).
pub(crate) fn decode_path(path: &Path) -> Result<DynamicImage, IoError> {
    decode(path, path, &DecodeLimits::default())
}

/// Decodes an image file's bytes; `name` is the file errors name.
pub(crate) fn decode_bytes(bytes: &[u8], name: &Path, limits: &DecodeLimits) -> Result<DynamicImage, IoError> {
    decode(bytes, name, limits)
}

/// Refuses a PNG whose PLTE chunk is not a whole number of RGB entries (1 to 256): the `png`
/// crate (0.18) panics on one while expanding the palette. Reads the chunk headers up to the
/// first IDAT only; anything else is left to the decoder.
fn check_png_palette(mut f: impl std::io::Read + std::io::Seek, name: &Path) -> Result<(), IoError> {
    use std::io::SeekFrom;
    let read_err = |source| IoError::Read { path: name.to_path_buf(), source };
    let mut signature = [0u8; 8];
    if f.read_exact(&mut signature).is_err() || signature != *b"\x89PNG\r\n\x1a\n" {
        return Ok(());
    }
    let mut header = [0u8; 8];
    while f.read_exact(&mut header).is_ok() {
        let length = u32::from_be_bytes(header[..4].try_into().expect("4 bytes"));
        match &header[4..] {
            b"PLTE" if length == 0 || length % 3 != 0 || length > 768 => {
                return Err(IoError::Decode {
                    path: name.to_path_buf(),
                    reason: format!("PLTE chunk of {length} bytes is not 1 to 256 RGB entries (3 bytes each)"),
                });
            }
            b"IDAT" | b"IEND" => return Ok(()),
            _ => {}
        }
        // The chunk's data and CRC.
        f.seek(SeekFrom::Current(length as i64 + 4)).map_err(read_err)?;
    }
    Ok(())
}

/// Loads heights from one channel of an image: in [0, 1] from 8 or 16 bits (`v/255` or
/// `v/65535`); as stored from a floating-point image (OpenEXR, 32-bit TIFF), where heights
/// are often in scene units — `--scale` then says how many texels one unit is. A NaN or
/// infinite height is an error naming the texel.
pub fn load_height_field(path: &Path, channel: Channel) -> Result<HeightField, IoError> {
    if let Some(field) = float_tiff(path, path, channel, &DecodeLimits::default())? {
        return Ok(field);
    }
    if let Some(field) = one_channel_exr(path, path, channel, &DecodeLimits::default())? {
        return Ok(field);
    }
    height_field(decode(path, path, &DecodeLimits::default())?, path, channel)
}

/// Whether the file begins with one of `magics`.
fn starts_with(source: &impl Source, name: &Path, magics: &[[u8; 4]]) -> Result<bool, IoError> {
    let mut reader = source.open().map_err(|source| IoError::Read { path: name.to_path_buf(), source })?;
    let mut magic = [0u8; 4];
    Ok(std::io::Read::read_exact(&mut reader, &mut magic).is_ok() && magics.contains(&magic))
}

/// A one-channel OpenEXR file (a `Y`, `Z` or lone `R` channel: how height data is often
/// stored), which `image` does not decode, read with the `exr` crate after its header passed
/// [`check_exr`]; `None` for any other file. Its one channel answers to luminance and red.
fn one_channel_exr(
    source: impl Source,
    name: &Path,
    channel: Channel,
    limits: &DecodeLimits,
) -> Result<Option<HeightField>, IoError> {
    use exr::prelude::*;
    let read_err = |source| IoError::Read { path: name.to_path_buf(), source };
    if !starts_with(&source, name, &[EXR_MAGIC])? {
        return Ok(None);
    }
    let bad = |e: exr::error::Error| IoError::Decode { path: name.to_path_buf(), reason: format!("OpenEXR: {e}") };
    let meta = exr::meta::MetaData::read_from_buffered(source.open().map_err(read_err)?, false).map_err(bad)?;
    if meta.headers.first().is_none_or(|h| h.channels.list.len() != 1) {
        return Ok(None);
    }
    check_exr(source.open().map_err(read_err)?, source.len().map_err(read_err)?, name, limits)?;
    if !matches!(channel, Channel::Luminance | Channel::Red) {
        return Err(IoError::NoSuchChannel {
            path: name.to_path_buf(),
            channel: channel.name(),
            has: "one channel".into(),
        });
    }
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(source.open().map_err(read_err)?)
        .map_err(bad)?;
    let layer = image.layer_data;
    let (w, h) = (layer.size.width(), layer.size.height());
    let heights: Vec<f32> = layer.channel_data.list[0].sample_data.values_as_f32().collect();
    let field = HeightField::new(w, h, heights).ok_or_else(|| IoError::Decode {
        path: name.to_path_buf(),
        reason: "OpenEXR: pixel count does not match its size".into(),
    })?;
    usable(field, name).map(Some)
}

/// A one-channel OpenEXR file ([`one_channel_exr`]: what `bumpmap height` writes) as gray
/// floating-point RGBA, `(v, v, v, 1)`, for the readers that take any map (`inspect`); `None`
/// for any other file.
pub(crate) fn gray_exr_path(path: &Path) -> Result<Option<bumpmap_math::Image<[f32; 4]>>, IoError> {
    Ok(one_channel_exr(path, path, Channel::Luminance, &DecodeLimits::default())?.map(|f| gray_rgba(&f)))
}

/// [`gray_exr_path`] of a file's bytes in memory, `name` naming it, `limits` bounding it.
pub(crate) fn gray_exr_bytes(
    bytes: &[u8],
    name: &Path,
    limits: &DecodeLimits,
) -> Result<Option<bumpmap_math::Image<[f32; 4]>>, IoError> {
    Ok(one_channel_exr(bytes, name, Channel::Luminance, limits)?.map(|f| gray_rgba(&f)))
}

/// Heights as gray RGBA, alpha 1.
fn gray_rgba(field: &HeightField) -> bumpmap_math::Image<[f32; 4]> {
    let texels = field.to_f32().into_iter().map(|v| [v, v, v, 1.0]).collect();
    bumpmap_math::Image::new(field.width(), field.height(), texels)
}

/// A one-channel floating-point TIFF (what GIS and terrain tools write heights as), which
/// `image` does not decode, read with the `tiff` crate; `None` for any other file. Its one
/// channel answers to luminance and red; the sizes are checked before any pixel is read.
fn float_tiff(
    source: impl Source,
    name: &Path,
    channel: Channel,
    limits: &DecodeLimits,
) -> Result<Option<HeightField>, IoError> {
    use tiff::decoder::{Decoder, DecodingResult, Limits};
    let read_err = |source| IoError::Read { path: name.to_path_buf(), source };
    if !starts_with(&source, name, &[*b"II*\0", *b"MM\0*"])? {
        return Ok(None);
    }
    let bad = |e: tiff::TiffError| IoError::Decode { path: name.to_path_buf(), reason: format!("TIFF: {e}") };
    let mut tiff_limits = Limits::default();
    tiff_limits.decoding_buffer_size = usize::try_from(limits.max_alloc).unwrap_or(usize::MAX);
    let Ok(decoder) = Decoder::new(source.open().map_err(read_err)?) else { return Ok(None) };
    let mut decoder = decoder.with_limits(tiff_limits);
    if !matches!(decoder.colortype(), Ok(tiff::ColorType::Gray(32 | 64))) {
        return Ok(None);
    }
    let (w, h) = decoder.dimensions().map_err(bad)?;
    let max = limits.max_dimension.min(MAX_DIMENSION);
    if w == 0 || h == 0 {
        return Err(IoError::Empty { path: name.to_path_buf(), width: w, height: h });
    }
    if w > max || h > max {
        return Err(IoError::TooLarge { path: name.to_path_buf(), width: w as u64, height: h as u64, max });
    }
    if !matches!(channel, Channel::Luminance | Channel::Red) {
        return Err(IoError::NoSuchChannel {
            path: name.to_path_buf(),
            channel: channel.name(),
            has: "one float channel".into(),
        });
    }
    let heights: Vec<f32> = match decoder.read_image().map_err(bad)? {
        DecodingResult::F32(v) => v,
        DecodingResult::F64(v) => v.into_iter().map(|x| x as f32).collect(),
        // 32-bit integer grey: not heights in float; `image` says what it makes of it.
        _ => return Ok(None),
    };
    let field = HeightField::new(w as usize, h as usize, heights).ok_or_else(|| IoError::Decode {
        path: name.to_path_buf(),
        reason: "TIFF: pixel count does not match its size".into(),
    })?;
    usable(field, name).map(Some)
}

/// `field`, or an error naming its first sample that cannot be differentiated.
fn usable(field: HeightField, path: &Path) -> Result<HeightField, IoError> {
    if let Some((x, y, v)) = field.first_unusable() {
        return Err(IoError::Decode {
            path: path.to_path_buf(),
            reason: format!(
                "the height at texel ({x}, {y}) is {v}; heights must be finite and within ±{:e}",
                bumpmap_math::height::MAX_FLOAT_HEIGHT
            ),
        });
    }
    Ok(field)
}

/// [`load_height_field`] for an image file's bytes already in memory; `name` is the file
/// that errors name.
pub fn read_height_field(
    bytes: &[u8],
    name: &Path,
    channel: Channel,
    limits: &DecodeLimits,
) -> Result<HeightField, IoError> {
    if let Some(field) = float_tiff(bytes, name, channel, limits)? {
        return Ok(field);
    }
    if let Some(field) = one_channel_exr(bytes, name, channel, limits)? {
        return Ok(field);
    }
    height_field(decode(bytes, name, limits)?, name, channel)
}

fn height_field(img: DynamicImage, path: &Path, channel: Channel) -> Result<HeightField, IoError> {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let color = img.color();
    let missing =
        || IoError::NoSuchChannel { path: path.to_path_buf(), channel: channel.name(), has: format!("{color:?}") };
    let has_color = color.has_color();
    if (matches!(channel, Channel::Red | Channel::Green | Channel::Blue) && !has_color)
        || (channel == Channel::Alpha && !color.has_alpha())
    {
        return Err(missing());
    }
    let float = matches!(color, image::ColorType::Rgb32F | image::ColorType::Rgba32F);
    let sixteen = color.bytes_per_pixel() / color.channel_count() >= 2;
    let pick = |c: [f32; 4]| match channel {
        Channel::Luminance if !has_color => c[0],
        Channel::Luminance => 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2],
        Channel::Red => c[0],
        Channel::Green => c[1],
        Channel::Blue => c[2],
        Channel::Alpha => c[3],
    };
    // Converted by value: the decoded image is dropped once converted, so at most two copies
    // are alive besides the heights, as `decode` counted.
    let field = if float {
        let rgba = img.into_rgba32f();
        let heights: Vec<f32> = rgba.pixels().map(|p| pick(p.0)).collect();
        Some(usable(HeightField::new(w, h, heights).expect("decoded image has consistent dimensions"), path)?)
    } else if sixteen {
        if !has_color && channel == Channel::Luminance {
            HeightField::from_u16(w, h, img.into_luma16().as_raw())
        } else {
            let rgba = img.into_rgba16();
            HeightField::new(w, h, rgba.pixels().map(|p| pick(p.0.map(|v| v as f32 / 65535.0))).collect())
        }
    } else if !has_color && channel == Channel::Luminance {
        HeightField::from_u8(w, h, img.into_luma8().as_raw())
    } else {
        let rgba = img.into_rgba8();
        HeightField::new(w, h, rgba.pixels().map(|p| pick(p.0.map(|v| v as f32 / 255.0))).collect())
    };
    Ok(field.expect("decoded image has consistent dimensions"))
}

/// Loads any image as 8-bit RGBA (decals, gloss maps, normal maps).
pub fn load_rgba8(path: &Path) -> Result<Rgba8Image, IoError> {
    Ok(rgba8(decode(path, path, &DecodeLimits::default())?))
}

/// [`load_rgba8`] for an image file's bytes already in memory; `name` is the file that errors
/// name.
pub fn read_rgba8(bytes: &[u8], name: &Path, limits: &DecodeLimits) -> Result<Rgba8Image, IoError> {
    Ok(rgba8(decode(bytes, name, limits)?))
}

fn rgba8(img: DynamicImage) -> Rgba8Image {
    // Converted by value: the decoded image is dropped once converted, so at most two copies
    // are alive, as `decode` counted.
    let img = img.into_rgba8();
    let (w, h) = (img.width() as usize, img.height() as usize);
    Rgba8Image::new(w, h, img.pixels().map(|p| p.0).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn preset_specs_parse() {
        assert_eq!(HeightSource::parse("bricks"), HeightSource::Preset { preset: HeightPreset::Bricks, size: 256 });
        assert_eq!(
            HeightSource::parse("noise:9@64"),
            HeightSource::Preset { preset: HeightPreset::Noise(9), size: 64 }
        );
        assert_eq!(HeightSource::parse("my/heights.png"), HeightSource::File("my/heights.png".into()));
    }
}
