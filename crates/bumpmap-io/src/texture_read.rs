//! Texture files in: a normal map made elsewhere (or by `bumpmap normalmap`) with the levels it
//! carries — a PNG or other image (one level, 8 or 16 bits), or a DDS or KTX2 container (every
//! level, uncompressed RGBA8/BGRA8/RGBA16 or BC5/BC7 blocks decoded by `image_dds`'s decoder) —
//! and heights (R8, R16, and R16G16 for their min–max bounds, widened to RGBA as a texture
//! unit's register mapping would: red repeated, or red and green with blue 0).
//!
//! Headers are checked before anything is decoded: the size against
//! [`MAX_DIMENSION`](crate::image_file::MAX_DIMENSION), one 2D face (no cube map, array or
//! volume), a linear format (an sRGB normal map is a broken one), no supercompression, and every
//! level's bytes present as the header declares them. BC5 stores X and Y only; Z is rebuilt as
//! `√(1 − x² − y²)` and A is 1, as a shader does.
//!
//! DDS and KTX2 are read in `texture_read/containers.rs`, a PNG's level files in `chain.rs`.
//!
//! What this module does not do: interpret the texels (green up or down, unit length, the
//! smaller levels' alpha): that is `bumpmap_math::imported`.

use std::path::Path;

use bumpmap_math::{Image, Rgba8Image, Rgba16Image};

use crate::error::IoError;
use crate::image_file::DecodeLimits;
use crate::texture_file::TextureFormat;

mod chain;
mod containers;

use containers::{KTX2_IDENTIFIER, read_dds, read_ktx2};

pub use chain::load_texture_chain;

/// The largest texture file read, in bytes (a 16384² RGBA16 level with its mips is 2.7 GiB;
/// such a file is refused before it is read).
pub const MAX_TEXTURE_FILE_BYTES: u64 = 1 << 31;

/// A texture file's levels as stored: level 0 first, each the next smaller size.
#[derive(Clone, Debug, PartialEq)]
pub enum StoredLevels {
    /// 8 bits a channel (RGBA8, BGRA8 reordered, and decoded BC5 and BC7).
    Rgba8(Vec<Rgba8Image>),
    /// 16 bits a channel.
    Rgba16(Vec<Rgba16Image>),
}

impl StoredLevels {
    /// How many levels the file carries.
    pub fn len(&self) -> usize {
        match self {
            StoredLevels::Rgba8(l) => l.len(),
            StoredLevels::Rgba16(l) => l.len(),
        }
    }

    /// Whether there is no level (never, for a texture that loaded).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Level 0's width and height.
    pub fn size(&self) -> (usize, usize) {
        match self {
            StoredLevels::Rgba8(l) => l.first().map_or((0, 0), |l| (l.width, l.height)),
            StoredLevels::Rgba16(l) => l.first().map_or((0, 0), |l| (l.width, l.height)),
        }
    }
}

/// A texture read from a file.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredTexture {
    /// The levels, decoded.
    pub levels: StoredLevels,
    /// How the file stored them.
    pub format: TextureFormat,
}

fn bad(path: &Path, reason: impl std::fmt::Display) -> IoError {
    IoError::Texture { path: path.to_path_buf(), reason: reason.to_string() }
}

/// The width and height of level 0 as a texture file's header declares them, read without
/// decoding anything (DDS and KTX2 by their magic numbers, any other image by `image`'s
/// header reader): what a file found by name, or one that must match another's size, is
/// checked by before its texels take any memory.
pub fn declared_size(path: &Path) -> Result<(usize, usize), IoError> {
    use std::io::Read as _;
    let read_err = |source| IoError::Read { path: path.to_path_buf(), source };
    // A DDS header is its magic number and 124 bytes; a KTX2 header is 80.
    let mut head = Vec::with_capacity(128);
    std::fs::File::open(path).map_err(read_err)?.take(128).read_to_end(&mut head).map_err(read_err)?;
    if head.len() >= ktx2::Header::LENGTH && head.starts_with(&KTX2_IDENTIFIER) {
        let bytes: &[u8; ktx2::Header::LENGTH] = head[..ktx2::Header::LENGTH].try_into().expect("80 bytes");
        let h = ktx2::Header::from_bytes(bytes).map_err(|e| bad(path, format!("not a readable KTX2 file: {e:?}")))?;
        return Ok((h.pixel_width as usize, h.pixel_height.max(1) as usize));
    }
    if head.starts_with(b"DDS ") {
        let h = ddsfile::Header::read(&head[4..]).map_err(|e| bad(path, format!("not a readable DDS file: {e}")))?;
        return Ok((h.width as usize, h.height as usize));
    }
    let (w, h) = image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .map_err(read_err)?
        .into_dimensions()
        .map_err(|e| bad(path, format!("not a readable image: {e}")))?;
    Ok((w as usize, h as usize))
}

/// Reads a texture file: `.dds`, `.ktx2`, or any image `image` decodes (by its contents) at 8
/// or 16 bits a channel.
pub fn load_texture(path: &Path) -> Result<StoredTexture, IoError> {
    unorm_only(load_any_texture(path)?, path)
}

/// [`load_texture`], an image's decoding bounded by `limits` where given (the whole file read
/// into memory first, at most [`MAX_TEXTURE_FILE_BYTES`]): what a reader of untrusted sets of
/// files found by name (a fuzzer's) asks for.
pub fn load_texture_within(path: &Path, limits: Option<&DecodeLimits>) -> Result<StoredTexture, IoError> {
    let Some(limits) = limits else { return load_texture(path) };
    let read_err = |source| IoError::Read { path: path.to_path_buf(), source };
    let meta = std::fs::metadata(path).map_err(read_err)?;
    if !meta.is_file() {
        return Err(bad(path, "is not a regular file"));
    }
    if meta.len() > MAX_TEXTURE_FILE_BYTES {
        return Err(bad(path, format!("{} bytes; the limit is {MAX_TEXTURE_FILE_BYTES}", meta.len())));
    }
    read_texture(&std::fs::read(path).map_err(read_err)?, path, limits)
}

/// [`load_texture`], but a floating-point image (EXR, float TIFF) is read too, as
/// [`AnyTexture::Float`].
pub fn load_any_texture(path: &Path) -> Result<AnyTexture, IoError> {
    let meta = std::fs::metadata(path).map_err(|source| IoError::Read { path: path.to_path_buf(), source })?;
    if !meta.is_file() {
        return Err(bad(path, "is not a regular file"));
    }
    let mut magic = [0u8; 12];
    {
        use std::io::Read as _;
        let mut f = std::fs::File::open(path).map_err(|source| IoError::Read { path: path.to_path_buf(), source })?;
        let n = f.read(&mut magic).map_err(|source| IoError::Read { path: path.to_path_buf(), source })?;
        if n < 4 {
            return Err(bad(path, format!("{n} bytes is too short for an image")));
        }
    }
    if magic.starts_with(b"DDS ") || magic == KTX2_IDENTIFIER {
        if meta.len() > MAX_TEXTURE_FILE_BYTES {
            return Err(bad(path, format!("{} bytes; the limit is {MAX_TEXTURE_FILE_BYTES}", meta.len())));
        }
        let bytes = std::fs::read(path).map_err(|source| IoError::Read { path: path.to_path_buf(), source })?;
        return read_texture(&bytes, path, &DecodeLimits::default()).map(AnyTexture::Stored);
    }
    if let Some(gray) = crate::image_file::gray_exr_path(path)? {
        return Ok(AnyTexture::Float(gray));
    }
    Ok(image_levels(crate::image_file::decode_path(path)?))
}

/// [`load_texture`] for a file's bytes already in memory; `name` is the file errors name and
/// `limits` bound an image's decoding (a container's levels are bounded by its bytes: every
/// level must be there before one is decoded).
pub fn read_texture(bytes: &[u8], name: &Path, limits: &DecodeLimits) -> Result<StoredTexture, IoError> {
    unorm_only(read_any_texture(bytes, name, limits)?, name)
}

/// [`load_any_texture`] for a file's bytes already in memory (floating point too: an EXR),
/// named and bounded as [`read_texture`] is.
pub fn read_any_texture(bytes: &[u8], name: &Path, limits: &DecodeLimits) -> Result<AnyTexture, IoError> {
    if bytes.starts_with(b"DDS ") {
        read_dds(bytes, name).map(AnyTexture::Stored)
    } else if bytes.starts_with(&KTX2_IDENTIFIER) {
        read_ktx2(bytes, name).map(AnyTexture::Stored)
    } else if let Some(gray) = crate::image_file::gray_exr_bytes(bytes, name, limits)? {
        Ok(AnyTexture::Float(gray))
    } else {
        Ok(image_levels(crate::image_file::decode_bytes(bytes, name, limits)?))
    }
}

/// A texture whose texels may also be floating point: what `bumpmap inspect` and
/// `bumpmap height` read (an EXR or float TIFF normal map, which [`load_texture`] refuses
/// because the renderers sample unorm texels).
#[derive(Clone, Debug, PartialEq)]
pub enum AnyTexture {
    /// Unsigned-normalized texels, or a container's blocks decoded (as [`load_texture`] reads).
    Stored(StoredTexture),
    /// One level of 32-bit float RGBA (alpha 1 where the file has none), as stored: a normal
    /// map in float stores −1..1 or 0..1, which is for the reader to tell.
    Float(Image<[f32; 4]>),
}

/// The unorm texture, or the refusal of a floating-point one (the renderers sample unorm
/// texels).
fn unorm_only(texture: AnyTexture, path: &Path) -> Result<StoredTexture, IoError> {
    match texture {
        AnyTexture::Stored(t) => Ok(t),
        AnyTexture::Float(_) => Err(bad(
            path,
            "floating-point texels: a normal map is drawn from 8- or 16-bit unsigned channels (floating-point maps differ in how they store −1..1; `bumpmap inspect` reads them)",
        )),
    }
}

/// One image's texels at the depth they were stored, as one level: 8 or 16 bits unorm, any
/// other depth as 32-bit float.
fn image_levels(img: image::DynamicImage) -> AnyTexture {
    use image::ColorType::*;
    let (w, h) = (img.width() as usize, img.height() as usize);
    // Converted by value: the decoded image is dropped once converted, so no third copy
    // outlives the decoder's estimate.
    match img.color() {
        L8 | La8 | Rgb8 | Rgba8 => {
            let rgba = img.into_rgba8();
            let level = Rgba8Image::new(w, h, rgba.pixels().map(|p| p.0).collect());
            AnyTexture::Stored(StoredTexture { levels: StoredLevels::Rgba8(vec![level]), format: TextureFormat::Rgba8 })
        }
        L16 | La16 | Rgb16 | Rgba16 => {
            let rgba = img.into_rgba16();
            let level = Rgba16Image::new(w, h, rgba.pixels().map(|p| p.0).collect());
            AnyTexture::Stored(StoredTexture {
                levels: StoredLevels::Rgba16(vec![level]),
                format: TextureFormat::Rgba16,
            })
        }
        _ => {
            let rgba = img.into_rgba32f();
            AnyTexture::Float(Image::new(w, h, rgba.pixels().map(|p| p.0).collect()))
        }
    }
}

impl From<&StoredLevels> for Vec<Image<[u8; 4]>> {
    /// Every level at 8 bits (16-bit levels rounded).
    fn from(levels: &StoredLevels) -> Self {
        match levels {
            StoredLevels::Rgba8(l) => l.clone(),
            StoredLevels::Rgba16(l) => l.iter().map(Rgba16Image::to_rgba8).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture_file::{Level as WriteLevel, TextureLayout, write_dds, write_ktx2};

    fn chain() -> Vec<Rgba8Image> {
        let texel = |x: usize, y: usize| [(x * 40) as u8, (y * 60) as u8, 200, 255 - x as u8];
        vec![
            Rgba8Image::new(6, 4, (0..24).map(|i| texel(i % 6, i / 6)).collect()),
            Rgba8Image::new(3, 2, (0..6).map(|i| texel(i % 3, i / 3)).collect()),
            Rgba8Image::new(1, 1, vec![[1, 2, 3, 4]]),
        ]
    }

    fn tmp(name: &str) -> std::path::PathBuf {
        std::env::temp_dir().join(format!("bumpmap-read-{}-{name}", std::process::id()))
    }

    #[test]
    fn our_dds_and_ktx2_read_back_level_for_level() {
        let data = chain();
        let layout = TextureLayout { faces: vec![data.iter().map(WriteLevel::from).collect()] };
        for (ext, write) in [
            ("dds", write_dds as fn(&Path, &TextureLayout, TextureFormat) -> Result<(), IoError>),
            ("ktx2", write_ktx2),
        ] {
            for format in [TextureFormat::Rgba8, TextureFormat::Rgba16] {
                let path = tmp(&format!("t.{ext}"));
                write(&path, &layout, format).unwrap();
                let got = load_texture(&path).unwrap();
                assert_eq!(got.format, format, "{ext}");
                let levels: Vec<Rgba8Image> = (&got.levels).into();
                assert_eq!(levels, data, "{ext} {format:?}");
                std::fs::remove_file(&path).unwrap();
            }
        }
    }

    #[test]
    fn a_legacy_dds_without_alpha_pixels_reads_its_padding_as_opaque() {
        // X8B8G8R8: RGB masks, 32 bits, no ALPHA_PIXELS flag; the padding byte is 0.
        let mut bytes = b"DDS ".to_vec();
        let mut put = |v: u32| bytes.extend_from_slice(&v.to_le_bytes());
        for v in [124, 0x1 | 0x2 | 0x4 | 0x1000, 1, 2, 8, 0, 1] {
            put(v);
        }
        (0..11).for_each(|_| put(0));
        for v in [32, 0x40, 0, 32, 0xff, 0xff00, 0xff_0000, 0] {
            put(v);
        }
        for v in [0x1000, 0, 0, 0, 0] {
            put(v);
        }
        bytes.extend_from_slice(&[10, 20, 30, 0, 40, 50, 60, 0]);
        let got = read_texture(&bytes, Path::new("x8.dds"), &DecodeLimits::default()).unwrap();
        assert_eq!(
            got.levels,
            StoredLevels::Rgba8(vec![Rgba8Image::new(2, 1, vec![[10, 20, 30, 255], [40, 50, 60, 255]])])
        );
    }

    #[test]
    fn a_chain_shorter_than_its_header_says_is_refused() {
        let data = chain();
        let layout = TextureLayout { faces: vec![data.iter().map(WriteLevel::from).collect()] };
        let path = tmp("short.dds");
        write_dds(&path, &layout, TextureFormat::Rgba8).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        let limits = DecodeLimits::default();
        let err = read_texture(&bytes[..bytes.len() - 4], Path::new("short.dds"), &limits).unwrap_err().to_string();
        assert!(
            err.contains("short.dds")
                && err.contains("holds 120 bytes")
                && err.contains("3 level(s) from 6x4")
                && err.contains("take 124"),
            "{err}"
        );
        // A mip count the size cannot have.
        let mut more = bytes.clone();
        more[28..32].copy_from_slice(&9u32.to_le_bytes());
        let err = read_texture(&more, Path::new("m.dds"), &limits).unwrap_err().to_string();
        assert!(err.contains("declares 9 mip levels, but a 6x4 texture has at most 3"), "{err}");
    }
}
