//! Horizon maps, ambient occlusion and bent normals in files (`bumpmap_math::horizon`), written
//! with the normal map as one set.
//!
//! - horizons, two textures of four directions each (R the first): `.png`: `H.png` (directions
//!   0–3, RGBA at 8 or 16 bits), `H.mip1.png`, … and `H.dirs4-7.png`, `H.dirs4-7.mip1.png`, …;
//!   `.ktx2` / `.dds`: `H.ktx2` and `H.dirs4-7.ktx2`, every level (`R8G8B8A8_UNORM` or
//!   `R16G16B16A16_UNORM`). A channel holds `atan(rise) / 90°`, the rise in heights per texel of
//!   level 0; direction k points k·45° from +s toward +t (down the image as displayed);
//! - ambient occlusion: one gray level (`.png` 8/16-bit gray, `.ktx2`/`.dds` `R8_UNORM` or
//!   `R16_UNORM`), 1 open, 0 closed.
//!
//! Bent normals are a normal map and are written as one. [`load_horizons`] reads a horizon map
//! back (both textures, every level they hold). What this module does not do: make the maps.

use std::path::{Path, PathBuf};

use bumpmap_math::{HorizonLevel, HorizonMap, Image};

use crate::atomic::FileSet;
use crate::error::IoError;
use crate::height_file::{
    Container, HeightBits, RgbaLevel, container, read_levels_checked, unorm8, unorm16, write_levels,
};
use crate::image_file::DecodeLimits;
use crate::image_file::level_path;
use crate::texture_file::{Level, TextureFormat};

/// The second horizon file beside `path`: `H.dirs4-7.EXT`.
pub fn second_half_path(path: &Path) -> PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let ext = path.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!("{stem}.dirs4-7.{ext}"))
}

/// Every file [`write_horizons_into`] writes for `path` and `levels` levels.
pub fn horizon_files(path: &Path, levels: usize) -> Result<Vec<PathBuf>, IoError> {
    let second = second_half_path(path);
    Ok(match container(path)? {
        Container::Png => {
            (0..levels).map(|k| level_path(path, k)).chain((0..levels).map(|k| level_path(&second, k))).collect()
        }
        Container::Ktx2 | Container::Dds => vec![path.to_path_buf(), second],
    })
}

/// Stages the first `levels` levels of `map` at `bits` into `set`, by `path`'s extension.
pub fn write_horizons_into(
    set: &mut FileSet,
    path: &Path,
    map: &HorizonMap,
    levels: usize,
    bits: HeightBits,
) -> Result<(), IoError> {
    let kind = container(path)?;
    let levels = levels.clamp(1, map.levels().len());
    for (half, file) in [(0, path.to_path_buf()), (1, second_half_path(path))] {
        match bits {
            HeightBits::Eight => {
                let images: Vec<Image<[u8; 4]>> = (0..levels).map(|k| map.directions(k, half)).collect();
                write_levels(set, &file, kind, images.iter().map(Level::Rgba8).collect(), TextureFormat::Rgba8)?;
            }
            HeightBits::Sixteen => {
                let images: Vec<Image<[u16; 4]>> = (0..levels).map(|k| map.directions(k, half)).collect();
                write_levels(set, &file, kind, images.iter().map(Level::Rgba16).collect(), TextureFormat::Rgba16)?;
            }
        }
    }
    Ok(())
}

/// `path` if its extension is one a gray map can be written to (`.png`, `.ktx2`, `.dds`).
pub fn gray_file(path: &Path) -> Result<PathBuf, IoError> {
    container(path).map(|_| path.to_path_buf())
}

/// Stages one gray level of `values` in [0, 1] (`width`×`height`, row 0 = t = 0) at `bits` into
/// `set`, by `path`'s extension: an ambient-occlusion map.
pub fn write_gray_into(
    set: &mut FileSet,
    path: &Path,
    (width, height): (usize, usize),
    values: &[f32],
    bits: HeightBits,
) -> Result<(), IoError> {
    let kind = container(path)?;
    match bits {
        HeightBits::Eight => {
            let image = Image::new(width, height, values.iter().map(|&v| unorm8(v)).collect());
            write_levels(set, path, kind, vec![Level::Gray8(&image)], TextureFormat::R8)
        }
        HeightBits::Sixteen => {
            let image = Image::new(width, height, values.iter().map(|&v| unorm16(v)).collect());
            write_levels(set, path, kind, vec![Level::Gray16(&image)], TextureFormat::R16)
        }
    }
}

/// One texture of a horizon map read back: its levels, four directions a texel in [0, 1]. Each
/// file must be there and hold four channels (an RGBA PNG, an RGBA8 or RGBA16 container).
fn read_half(path: &Path, limits: Option<&DecodeLimits>) -> Result<Vec<RgbaLevel>, IoError> {
    crate::height_file::container_to_read(path, "horizon maps")?;
    let bad = |file: &Path, reason: String| IoError::Texture { path: file.to_path_buf(), reason };
    let png = container(path)? == Container::Png;
    read_levels_checked(path, limits, &|file: &Path, format: Option<TextureFormat>| match format {
        None if !file.is_file() => {
            Err(bad(file, "not found: a horizon map is two files of four directions each (H and H.dirs4-7)".into()))
        }
        None if png => {
            // Four channels, one direction each: a gray or RGB image holds fewer.
            let io = |source| IoError::Read { path: file.to_path_buf(), source };
            let reader = image::ImageReader::open(file).map_err(io)?.with_guessed_format().map_err(io)?;
            let decoder = reader.into_decoder().map_err(|e| bad(file, e.to_string()))?;
            let colour = image::ImageDecoder::color_type(&decoder);
            if colour.channel_count() == 4 {
                return Ok(());
            }
            Err(bad(
                file,
                format!(
                    "has {} channels ({colour:?}); a horizon map's texture holds four directions, one in each of R, G, B and A",
                    colour.channel_count()
                ),
            ))
        }
        Some(f) if !matches!(f, TextureFormat::Rgba8 | TextureFormat::Rgba16) => Err(bad(
            file,
            format!(
                "holds {} texels; a horizon map's texture holds four directions (R8G8B8A8 or R16G16B16A16_UNORM)",
                f.dxgi_name()
            ),
        )),
        _ => Ok(()),
    })
}

/// Every file [`load_horizons`] may read for `path`: `path`, `H.dirs4-7` beside it, and for PNG
/// the `.mipK.png` levels beside each (no output may replace one).
pub fn files_read(path: &Path) -> Result<Vec<PathBuf>, IoError> {
    let second = second_half_path(path);
    let mut files = vec![path.to_path_buf()];
    if crate::siblings::beside(path, &second)?.is_some() {
        files.push(second.clone());
    }
    if crate::height_file::container_to_read(path, "horizon maps")? == Container::Png {
        for file in files.clone() {
            files.extend(crate::siblings::png_levels(&file)?);
        }
    }
    Ok(files)
}

/// A horizon map written by [`write_horizons_into`] (or by another tool in the same layout):
/// `path` (directions 0–3) and `H.dirs4-7` beside it, each level of one the size of the other's,
/// level 0 alone or a chain (the rest are made). Missing files, textures of other than four
/// channels, sizes that do not match and values that are not numbers are errors naming the file.
pub fn load_horizons(path: &Path) -> Result<HorizonMap, IoError> {
    load_horizons_within(path, None)
}

/// [`load_horizons`], each image's decoding bounded by `limits` where given
/// ([`crate::texture_read::load_texture_within`]).
pub fn load_horizons_within(path: &Path, limits: Option<&DecodeLimits>) -> Result<HorizonMap, IoError> {
    let bad = |file: &Path, reason: String| IoError::Texture { path: file.to_path_buf(), reason };
    crate::height_file::container_to_read(path, "horizon maps")?;
    if std::fs::metadata(path).is_err() {
        return Err(bad(path, "not found".into()));
    }
    let second = second_half_path(path);
    if crate::siblings::beside(path, &second)?.is_none() {
        return Err(bad(
            &second,
            "not found: a horizon map is two files of four directions each (H and H.dirs4-7)".into(),
        ));
    }
    // The second half, found by name: its size from the headers before either is decoded.
    let ((w, h), (w2, h2)) = (crate::declared_size(path)?, crate::declared_size(&second)?);
    if (w2, h2) != (w, h) {
        return Err(bad(&second, format!("is {w2}x{h2}, but {} is {w}x{h}", path.display())));
    }
    let (a, b) = (read_half(path, limits)?, read_half(&second, limits)?);
    if a.len() != b.len() {
        return Err(bad(&second, format!("holds {} levels, but {} holds {}", b.len(), path.display(), a.len())));
    }
    let mut levels = Vec::with_capacity(a.len());
    for (k, ((w, h, lo), (w2, h2, hi))) in a.into_iter().zip(b).enumerate() {
        if (w, h) != (w2, h2) {
            return Err(bad(&second, format!("level {k} is {w2}x{h2}, but {}'s is {w}x{h}", path.display())));
        }
        let texels =
            lo.iter().zip(&hi).map(|(l, u)| std::array::from_fn(|c| if c < 4 { l[c] } else { u[c - 4] })).collect();
        levels.push(HorizonLevel { width: w, height: h, texels });
    }
    HorizonMap::from_levels(levels).map_err(|e| bad(path, e.to_string()))
}
