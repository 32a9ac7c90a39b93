//! Normal map files and arrays decoded into signed vectors, as `inspect` and `height` read them.

use std::path::{Path, PathBuf};

use bumpmap_io::{AnyTexture, StoredLevels};
use bumpmap_math::Image;
use bumpmap_math::encoding::Texel;
use bumpmap_math::inspect::{is_xy_only, rebuild_z, signed_levels};
use glam::Vec4;

use super::StoredAs;
use crate::Error;

/// What inspecting or integrating a map holds at once per texel of level 0: its vectors with
/// their levels (16 bytes × 4/3), the slopes (8), two half spectra (8), the transforms'
/// transposes (8) and the heights (4).
pub const WORKING_BYTES_PER_TEXEL: u64 = 50;

/// A map's texels decoded: signed vectors (level 0 first; xyz the direction as stored, w the
/// alpha), how they were stored, and whether Z was rebuilt from X and Y.
#[derive(Clone, Debug, PartialEq)]
pub struct DecodedMap {
    /// The levels, level 0 first.
    pub levels: Vec<Image<Vec4>>,
    /// How the file stored them.
    pub stored: StoredAs,
    /// Whether Z was rebuilt (BC5, or an RGB image with blue empty everywhere).
    pub two_channel: bool,
}

impl DecodedMap {
    /// `levels` as stored; a map holding X and Y only (BC5, whose Z the reader rebuilt, or blue
    /// empty everywhere) gets Z rebuilt as a shader would.
    pub fn new(mut levels: Vec<Image<Vec4>>, stored: StoredAs) -> Self {
        let two_channel = stored == StoredAs::Bc5 || levels.first().is_some_and(is_xy_only);
        if two_channel && stored != StoredAs::Bc5 {
            levels.iter_mut().for_each(rebuild_z);
        }
        Self { levels, stored, two_channel }
    }

    /// Floating-point texels (RGBA; alpha 1 where there is none): signed (−1..1 as stored)
    /// when any channel of RGB is below −0.01, else 0..1 (`2v − 1`).
    pub fn from_float(img: &Image<[f32; 4]>) -> Self {
        let signed = img.texels.iter().any(|t| t[..3].iter().any(|&c| c < -0.01));
        let texels = img
            .texels
            .iter()
            .map(|&[r, g, b, a]| {
                let v = Vec4::new(r, g, b, a);
                if signed { v } else { (v.truncate() * 2.0 - 1.0).extend(a) }
            })
            .collect();
        let stored = if signed { StoredAs::FloatSigned } else { StoredAs::FloatUnsigned };
        Self::new(vec![Image::new(img.width, img.height, texels)], stored)
    }

    /// Unorm texels (8 or 16 bits) already in memory.
    pub fn from_unorm<T: Texel>(levels: &[Image<T>], stored: StoredAs) -> Self {
        Self::new(signed_levels(levels), stored)
    }

    /// Refuses, naming `what` and the bytes, a map of `texels` (level 0's) whose vectors and
    /// the inspection's slopes and spectra would not fit: [`WORKING_BYTES_PER_TEXEL`] each.
    pub fn check_memory(what: &str, texels: usize) -> Result<(), Error> {
        let bytes = (texels as u64).saturating_mul(WORKING_BYTES_PER_TEXEL);
        bumpmap_math::buffer::ensure_available(bytes, "inspecting the map (its vectors, slopes and spectra)")
            .map_err(|source| Error::OutOfMemory { what: what.to_string(), source })
    }
}

/// Reads a normal map file as [`DecodedMap`]: PNG (8 or 16 bits), TGA, TIFF, EXR, JPEG, DDS or
/// KTX2 (their levels, BC5 and BC7 included); floating point as [`DecodedMap::from_float`]. A
/// PNG's smaller levels are the `NAME.mip1.png`, `NAME.mip2.png`, … beside it, as `bumpmap
/// normalmap` writes them, each half the size of the level before, read only from the same
/// folder ([`bumpmap_io::siblings::beside`]: a link leading elsewhere is an error).
pub fn read_map(path: &Path) -> Result<DecodedMap, Error> {
    let mut map = read_file(path)?;
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) && map.levels.len() == 1 {
        for k in 1.. {
            let last = &map.levels[map.levels.len() - 1];
            if (last.width, last.height) == (1, 1) {
                break;
            }
            let want = (bumpmap_math::mip::next_size(last.width), bumpmap_math::mip::next_size(last.height));
            let full = (map.levels[0].width, map.levels[0].height);
            let Some(file) = bumpmap_io::siblings::png_level(path, k, full, want)? else {
                break;
            };
            let level = read_file(&file)?.levels.swap_remove(0);
            if (level.width, level.height) != want {
                return Err(Error::Io(bumpmap_io::IoError::Texture {
                    path: file,
                    reason: format!(
                        "is {}x{}, but as level {k} of a {}x{} map it must be {}x{}",
                        level.width, level.height, map.levels[0].width, map.levels[0].height, want.0, want.1
                    ),
                }));
            }
            map.levels.push(level);
        }
    }
    Ok(map)
}

/// One file's own levels, without the `NAME.mipK.png` files beside a PNG: what `height`
/// reads (it needs level 0 only, and a broken level beside it is no reason to refuse).
pub fn read_file(path: &Path) -> Result<DecodedMap, Error> {
    decoded(bumpmap_io::load_any_texture(path)?, &path.display().to_string())
}

/// A map file's bytes already in memory (a DDS, a KTX2 or an image, floating point too), as
/// [`read_file`] reads the file; `name` is the file messages name, `limits` bound the decoding.
pub fn read_bytes(bytes: &[u8], name: &Path, limits: &bumpmap_io::DecodeLimits) -> Result<DecodedMap, Error> {
    decoded(bumpmap_io::read_any_texture(bytes, name, limits)?, &name.display().to_string())
}

/// `texture` (named `what`) as vectors, refused where they and the inspection would not fit.
fn decoded(texture: AnyTexture, what: &str) -> Result<DecodedMap, Error> {
    use bumpmap_io::texture_file::TextureFormat;
    let (w, h) = match &texture {
        AnyTexture::Stored(t) => t.levels.size(),
        AnyTexture::Float(img) => (img.width, img.height),
    };
    DecodedMap::check_memory(what, w * h)?;
    Ok(match texture {
        AnyTexture::Stored(t) => {
            let stored = match (t.format, &t.levels) {
                (TextureFormat::Bc5, _) => StoredAs::Bc5,
                (TextureFormat::Bc7, _) => StoredAs::Bc7,
                (_, StoredLevels::Rgba16(_)) => StoredAs::Unorm16,
                _ => StoredAs::Unorm8,
            };
            match &t.levels {
                StoredLevels::Rgba8(l) => DecodedMap::from_unorm(l, stored),
                StoredLevels::Rgba16(l) => DecodedMap::from_unorm(l, stored),
            }
        }
        AnyTexture::Float(img) => DecodedMap::from_float(&img),
    })
}

/// The image and texture files directly in `folder` (by extension, sorted), skipping links
/// that lead outside it and the `NAME.mipK.png` levels of a `NAME.png` there (read with it):
/// what `inspect FOLDER` reads.
pub fn maps_in_folder(folder: &Path) -> Result<Vec<PathBuf>, Error> {
    const EXTENSIONS: [&str; 9] = ["png", "tga", "tif", "tiff", "exr", "dds", "ktx2", "jpg", "jpeg"];
    let read_err = |source| Error::Io(bumpmap_io::IoError::Read { path: folder.to_path_buf(), source });
    let root = folder.canonicalize().map_err(read_err)?;
    let mut out = Vec::new();
    for entry in std::fs::read_dir(folder).map_err(read_err)? {
        let path = entry.map_err(read_err)?.path();
        let known = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| EXTENSIONS.iter().any(|k| k.eq_ignore_ascii_case(e)));
        let inside = path.canonicalize().is_ok_and(|p| p.parent() == Some(root.as_path()) && p.is_file());
        if known && inside {
            out.push(path);
        }
    }
    // A PNG's smaller levels (`NAME.mipK.png` beside `NAME.png`) are read with it, not alone.
    let level_of_another = |p: &PathBuf| {
        let name = p.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        name.rsplit_once(".mip").is_some_and(|(stem, rest)| {
            rest.strip_suffix(".png").is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
                && out.iter().any(|q| q.file_name().and_then(|n| n.to_str()) == Some(&format!("{stem}.png")))
        })
    };
    let mut maps: Vec<PathBuf> = out.iter().filter(|p| !level_of_another(p)).cloned().collect();
    maps.sort();
    Ok(maps)
}
