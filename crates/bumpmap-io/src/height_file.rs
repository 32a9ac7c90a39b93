//! Heights as geometry in files: the heights the parallax techniques read, every level, and
//! the min–max levels the exact walk reads (`bumpmap_math::height_mips`), as one set.
//!
//! - `.png`: `H.png` (8- or 16-bit gray), `H.mip1.png`, … beside it; `H.minmax.png` (16-bit
//!   RGB: R the lower bound, G the upper, B 0) and `H.minmax.mip1.png`, …;
//! - `.ktx2` / `.dds`: `H.ktx2` (`R8_UNORM` or `R16_UNORM`, every level) and `H.minmax.ktx2`
//!   (`R16G16_UNORM`, every level).
//!
//! Heights are stored rounded to the nearest step; bounds are rounded outward (the lower down,
//! the upper up), so they still bound the interpolant of the stored heights. What this module
//! does not do: make the heights or their bounds (`bumpmap_math`), or decide what a missing
//! min–max file means (the techniques that need one say so).

use std::path::{Path, PathBuf};

use bumpmap_math::height_mips::{HeightChain, HeightLevel, MinMaxLevel};
use bumpmap_math::{HeightMips, Image};

use crate::atomic::FileSet;
use crate::error::IoError;
use crate::image_file::DecodeLimits;
use crate::image_file::{
    Png16, PngLayout, level_path, png_file_bytes, png16_file_bytes, save_png_into, save_png16_samples_into,
};
use crate::texture_file::{Level, TextureFormat, TextureLayout, write_dds_into, write_ktx2_into};
use crate::texture_read::{StoredLevels, load_texture_within};

/// Bits a stored height has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeightBits {
    /// 8 bits (`R8_UNORM`, 8-bit gray PNG).
    Eight,
    /// 16 bits (`R16_UNORM`, 16-bit gray PNG).
    Sixteen,
}

impl HeightBits {
    /// The bits a map's options ask for: 16 is [`HeightBits::Sixteen`], anything else (8, the
    /// options' only other value) [`HeightBits::Eight`].
    pub fn of(bits: u8) -> Self {
        if bits == 16 { HeightBits::Sixteen } else { HeightBits::Eight }
    }
}

/// The container a heights file is, by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Container {
    Png,
    Ktx2,
    Dds,
}

pub(crate) fn container(path: &Path) -> Result<Container, IoError> {
    match path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).as_deref() {
        Some("png") => Ok(Container::Png),
        Some("ktx2") => Ok(Container::Ktx2),
        Some("dds") => Ok(Container::Dds),
        _ => Err(IoError::UnsupportedOutput { path: path.to_path_buf(), expected: ".png, .dds or .ktx2" }),
    }
}

/// [`container`] for a file to read, `what` naming what it holds: one of another extension is
/// an input that cannot be read, not an output format.
pub(crate) fn container_to_read(path: &Path, what: &str) -> Result<Container, IoError> {
    container(path).map_err(|_| IoError::Texture {
        path: path.to_path_buf(),
        reason: format!("{what} are read from .png, .dds or .ktx2 files (as normalmap writes them)"),
    })
}

/// Checks that `path`, a file of `what` (heights, horizon maps) to read, has an extension they
/// are read from, naming it.
pub fn check_container(path: &Path, what: &str) -> Result<(), IoError> {
    container_to_read(path, what).map(|_| ())
}

/// The min–max file beside heights `path`: `H.minmax.EXT`.
pub fn minmax_path(path: &Path) -> PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let ext = path.extension().map(|e| e.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!("{stem}.minmax.{ext}"))
}

/// Every file [`write_heights_into`] writes for `path` and `levels` levels, level 0 first.
pub fn heights_files(path: &Path, levels: usize) -> Result<Vec<PathBuf>, IoError> {
    let minmax = minmax_path(path);
    Ok(match container(path)? {
        Container::Png => {
            (0..levels).map(|k| level_path(path, k)).chain((0..levels).map(|k| level_path(&minmax, k))).collect()
        }
        Container::Ktx2 | Container::Dds => vec![path.to_path_buf(), minmax],
    })
}

/// `v` in [0, 1] rounded to 8 bits.
pub(crate) fn unorm8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// `v` in [0, 1] rounded to 16 bits.
pub(crate) fn unorm16(v: f32) -> u16 {
    (v.clamp(0.0, 1.0) * 65535.0).round() as u16
}

/// Stages `heights` at `bits` and their min–max levels (16 bits, rounded outward) into `set`, by
/// `path`'s extension (`.png`, `.ktx2`, `.dds`). Heights without min–max levels get none.
pub fn write_heights_into(
    set: &mut FileSet,
    path: &Path,
    heights: &HeightMips,
    bits: HeightBits,
) -> Result<(), IoError> {
    let kind = container(path)?;
    let gray8: Vec<Image<u8>>;
    let gray16: Vec<Image<u16>>;
    let levels: Vec<Level> = match bits {
        HeightBits::Eight => {
            gray8 = heights
                .levels()
                .iter()
                .map(|l| Image::new(l.width, l.height, l.texels.iter().map(|&v| unorm8(v)).collect()))
                .collect();
            gray8.iter().map(Level::Gray8).collect()
        }
        HeightBits::Sixteen => {
            gray16 = heights
                .levels()
                .iter()
                .map(|l| Image::new(l.width, l.height, l.texels.iter().map(|&v| unorm16(v)).collect()))
                .collect();
            gray16.iter().map(Level::Gray16).collect()
        }
    };
    let format = if bits == HeightBits::Eight { TextureFormat::R8 } else { TextureFormat::R16 };
    write_levels(set, path, kind, levels, format)?;
    if let Some(minmax) = heights.minmax() {
        let bounds: Vec<Image<[u16; 2]>> = minmax
            .iter()
            .map(|l| {
                let outward = |[lo, hi]: [f32; 2]| {
                    [(lo.clamp(0.0, 1.0) * 65535.0).floor() as u16, (hi.clamp(0.0, 1.0) * 65535.0).ceil() as u16]
                };
                Image::new(l.width, l.height, l.texels.iter().map(|&b| outward(b)).collect())
            })
            .collect();
        write_levels(set, &minmax_path(path), kind, bounds.iter().map(Level::Rg16).collect(), TextureFormat::Rg16)?;
    }
    Ok(())
}

/// One gray level of `values` in [0, 1] (`width`×`height`, row 0 first) at `bits`, as the PNG
/// file [`write_heights_into`] writes for level 0 of a `.png` (and
/// `horizon_file::write_gray_into` for an occlusion map), in memory: what a web page saves.
///
/// ```
/// use bumpmap_io::height_file::{HeightBits, gray_png_bytes};
/// let png = gray_png_bytes((2, 1), &[0.0, 1.0], HeightBits::Sixteen).unwrap();
/// assert_eq!(&png[1..4], b"PNG");
/// assert_eq!((png[24], png[25]), (16, 0), "16 bits a sample, gray");
/// ```
pub fn gray_png_bytes((width, height): (usize, usize), values: &[f32], bits: HeightBits) -> Result<Vec<u8>, IoError> {
    match bits {
        HeightBits::Eight => {
            let bytes: Vec<u8> = values.iter().map(|&v| unorm8(v)).collect();
            png_file_bytes(width, height, PngLayout::Gray8, &bytes)
        }
        HeightBits::Sixteen => {
            let samples: Vec<u16> = values.iter().map(|&v| unorm16(v)).collect();
            png16_file_bytes(width, height, Png16::Gray, &samples)
        }
    }
}

/// One set of levels into `path`: PNG files a level each, or one container.
pub(crate) fn write_levels(
    set: &mut FileSet,
    path: &Path,
    kind: Container,
    levels: Vec<Level>,
    format: TextureFormat,
) -> Result<(), IoError> {
    match kind {
        Container::Png => {
            for (k, level) in levels.iter().enumerate() {
                let file = level_path(path, k);
                match *level {
                    Level::Gray8(l) => save_png_into(set, &file, l.width, l.height, PngLayout::Gray8, &l.texels)?,
                    Level::Gray16(l) => save_png16_samples_into(set, &file, l.width, l.height, Png16::Gray, &l.texels)?,
                    Level::Rg16(l) => {
                        let rgb: Vec<u16> = l.texels.iter().flat_map(|&[lo, hi]| [lo, hi, 0]).collect();
                        save_png16_samples_into(set, &file, l.width, l.height, Png16::Rgb, &rgb)?
                    }
                    Level::Rgba8(l) => save_png_into(set, &file, l.width, l.height, PngLayout::Rgba8, l.as_bytes())?,
                    Level::Rgba16(l) => crate::image_file::save_png16_into(set, &file, l)?,
                    Level::Rgba32F(_) => unreachable!("no PNG holds floats; callers write them to KTX2 or DDS"),
                }
            }
            Ok(())
        }
        Container::Ktx2 => write_ktx2_into(set, path, &TextureLayout { faces: vec![levels] }, format),
        Container::Dds => write_dds_into(set, path, &TextureLayout { faces: vec![levels] }, format),
    }
}

/// A level read back: width, height, and the four channels of each texel in [0, 1].
pub(crate) type RgbaLevel = (usize, usize, Vec<[f32; 4]>);

/// Every level a texture file holds, each texel's four channels as fractions of their largest
/// value: a container's own levels, or a PNG and the `NAME.mipK.png` files beside it (as many
/// as there are, up to 1×1). `check` sees each file before it is read, and its decoded format
/// after.
pub(crate) fn read_levels_checked(
    path: &Path,
    limits: Option<&DecodeLimits>,
    check: &impl Fn(&Path, Option<TextureFormat>) -> Result<(), IoError>,
) -> Result<Vec<RgbaLevel>, IoError> {
    let kind = container_to_read(path, "heights, horizons and bounds")?;
    let read = |file: &Path| -> Result<Vec<RgbaLevel>, IoError> {
        check(file, None)?;
        let stored = load_texture_within(file, limits)?;
        check(file, Some(stored.format))?;
        // Four floats a texel of every level, beside the stored texels still held.
        let texels: u64 = match &stored.levels {
            StoredLevels::Rgba8(l) => l.iter().map(|l| l.texels.len() as u64).sum(),
            StoredLevels::Rgba16(l) => l.iter().map(|l| l.texels.len() as u64).sum(),
        };
        bumpmap_math::buffer::ensure_available(texels.saturating_mul(16), "reading its texels as numbers")
            .map_err(|source| IoError::OutOfMemory { path: file.to_path_buf(), source })?;
        fn unit<T: Copy + Into<f32>>(levels: Vec<Image<[T; 4]>>, max: f32) -> Vec<RgbaLevel> {
            levels
                .into_iter()
                .map(|l| (l.width, l.height, l.texels.iter().map(|p| p.map(|c| c.into() / max)).collect()))
                .collect()
        }
        Ok(match stored.levels {
            StoredLevels::Rgba8(levels) => unit(levels, 255.0),
            StoredLevels::Rgba16(levels) => unit(levels, 65535.0),
        })
    };
    let mut levels = read(path)?;
    if kind == Container::Png {
        let full = levels.first().map_or((0, 0), |(w, h, _)| (*w, *h));
        for k in 1.. {
            let Some((w, h)) = levels.last().map(|(w, h, _)| (*w, *h)) else { break };
            if (w, h) == (1, 1) {
                break;
            }
            let want = (bumpmap_math::levels::next_size(w), bumpmap_math::levels::next_size(h));
            let Some(file) = crate::siblings::png_level(path, k, full, want)? else { break };
            levels.extend(read(&file)?);
        }
    }
    Ok(levels)
}

/// A level read back: width, height, and two channels of each texel.
type PairLevel = (usize, usize, Vec<[f32; 2]>);

/// Every level a heights file holds ([`read_levels_checked`]), channel 0 and channel
/// `channels − 1` of each texel. Heights (`channels` 1) must be gray: a container of `R8` or
/// `R16`, an image whose channels are equal; a normal map, a horizon map or a colour image given
/// for heights is refused, never read as its red channel.
fn read_levels(path: &Path, channels: usize, limits: Option<&DecodeLimits>) -> Result<Vec<PairLevel>, IoError> {
    let bad = |file: &Path, reason: String| IoError::Texture { path: file.to_path_buf(), reason };
    let png = container_to_read(path, "heights")? == Container::Png;
    // The formats written: heights R8 or R16 (a gray PNG of 8 or 16 bits), bounds R16G16 (a
    // 16-bit RGB PNG, blue 0). Anything else is another map, refused before it is used.
    let format_fits = |file: &Path, format: Option<TextureFormat>| match format {
        Some(f) if channels == 1 && !png && !matches!(f, TextureFormat::R8 | TextureFormat::R16) => {
            Err(bad(file, format!("holds {}, not heights: a heights file is one channel (R8 or R16)", f.dxgi_name())))
        }
        Some(f) if channels == 2 && f != if png { TextureFormat::Rgba16 } else { TextureFormat::Rg16 } => Err(bad(
            file,
            format!(
                "holds {}, not min–max bounds: bounds are R16G16 in .ktx2 and .dds, 16-bit RGB with blue 0 in .png \
                 (as normalmap --height-out writes them)",
                f.dxgi_name()
            ),
        )),
        _ => Ok(()),
    };
    let levels = read_levels_checked(path, limits, &format_fits)?;
    if channels == 2 && png {
        for (w, _, texels) in &levels {
            if let Some(k) = texels.iter().position(|t| t[2] != 0.0) {
                return Err(bad(
                    path,
                    format!(
                        "is not min–max bounds: its texel ({}, {}) has blue {:.3}, and bounds hold the lower bound in \
                         red, the upper in green, 0 in blue (as normalmap --height-out writes them)",
                        k % w,
                        k / w,
                        texels[k][2]
                    ),
                ));
            }
        }
    }
    if channels == 1 && png {
        // Gray PNGs read back with three equal channels; a colour image does not.
        const STEP: f32 = 1.5 / 255.0;
        for (w, _, texels) in &levels {
            if let Some(k) = texels.iter().position(|t| (t[1] - t[0]).abs() > STEP || (t[2] - t[0]).abs() > STEP) {
                return Err(bad(
                    path,
                    format!(
                        "is a colour image, not heights: its texel ({}, {}) is ({:.3}, {:.3}, {:.3}); heights are gray \
                         (normalmap --height-out writes them). A normal map is given with --normal-map",
                        k % w,
                        k / w,
                        texels[k][0],
                        texels[k][1],
                        texels[k][2]
                    ),
                ));
            }
        }
    }
    Ok(levels.into_iter().map(|(w, h, t)| (w, h, t.into_iter().map(|p| [p[0], p[channels - 1]]).collect())).collect())
}

/// Every file [`load_heights`] may read for `path`: `path`, its min–max file, and for PNG the
/// `.mipK.png` levels beside each (no output may replace one).
pub fn files_read(path: &Path) -> Result<Vec<PathBuf>, IoError> {
    let minmax = minmax_path(path);
    let has_minmax = crate::siblings::beside(path, &minmax)?.is_some();
    let mut files = vec![path.to_path_buf()];
    if has_minmax {
        files.push(minmax.clone());
    }
    if container_to_read(path, "heights")? == Container::Png {
        files.extend(crate::siblings::png_levels(path)?);
        if has_minmax {
            files.extend(crate::siblings::png_levels(&minmax)?);
        }
    }
    Ok(files)
}

/// Heights `normalmap --height-out` wrote (or any gray image, `.ktx2` or `.dds` of R8/R16, with
/// its levels or alone), with the min–max levels from `H.minmax.EXT` where that file is there.
/// Level counts and sizes are checked, naming the file.
pub fn load_heights(path: &Path) -> Result<HeightMips, IoError> {
    load_heights_within(path, None)
}

/// [`load_heights`], each image's decoding bounded by `limits` where given
/// ([`crate::texture_read::load_texture_within`]).
pub fn load_heights_within(path: &Path, limits: Option<&DecodeLimits>) -> Result<HeightMips, IoError> {
    let bad = |file: &Path, reason: String| IoError::Texture { path: file.to_path_buf(), reason };
    container_to_read(path, "heights")?;
    // The bounds found by name beside the heights: their size, from the headers, before either
    // is decoded (a huge file beside small heights is refused, not read).
    let minmax_file = minmax_path(path);
    let has_minmax = crate::siblings::beside(path, &minmax_file)?.is_some();
    if has_minmax {
        let ((w, h), (mw, mh)) = (crate::declared_size(path)?, crate::declared_size(&minmax_file)?);
        if (mw, mh) != (w, h) {
            return Err(bad(&minmax_file, format!("is {mw}x{mh}, but the heights {} are {w}x{h}", path.display())));
        }
    }
    let levels: Vec<HeightLevel> = read_levels(path, 1, limits)?
        .into_iter()
        .map(|(width, height, t)| HeightLevel { width, height, texels: t.into_iter().map(|[v, _]| v).collect() })
        .collect();
    let minmax = if has_minmax {
        Some(
            read_levels(&minmax_file, 2, limits)?
                .into_iter()
                .map(|(width, height, texels)| MinMaxLevel { width, height, texels })
                .collect::<Vec<_>>(),
        )
    } else {
        None
    };
    let size = levels.first().map(|l| (l.width, l.height));
    if let (Some(m), Some((w, h))) = (&minmax, size)
        && m.first().map(|l| (l.width, l.height)) != Some((w, h))
    {
        let (mw, mh) = m.first().map_or((0, 0), |l| (l.width, l.height));
        return Err(bad(&minmax_file, format!("is {mw}x{mh}, but the heights {} are {w}x{h}", path.display())));
    }
    HeightMips::from_levels(levels, minmax).map_err(|e| {
        let file = if e.chain() == Some(HeightChain::MinMax) { &minmax_file } else { path };
        bad(file, e.to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A folder of the test's own, removed when the test ends (pass or fail): a run leaves
    /// nothing in the system's temporary folder.
    struct Scratch(PathBuf);

    impl Scratch {
        fn new(test: &str) -> Self {
            let dir = std::env::temp_dir().join(format!("bumpmap-heights-{}-{test}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            Self(dir)
        }

        fn file(&self, name: &str) -> PathBuf {
            self.0.join(name)
        }
    }

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    #[test]
    fn heights_and_bounds_read_back_as_written_in_every_container() {
        let field = bumpmap_math::HeightPreset::Bricks.render(12, 8);
        let heights = HeightMips::from_field(&field).unwrap();
        let scratch = Scratch::new("containers");
        for name in ["h.png", "h.ktx2", "h.dds"] {
            let path = scratch.file(name);
            let mut set = FileSet::new(&[]);
            write_heights_into(&mut set, &path, &heights, HeightBits::Sixteen).unwrap();
            let written = set.commit().unwrap();
            assert_eq!(crate::declared_size(&path).unwrap(), (12, 8), "{name}: the header's size");
            assert_eq!(crate::declared_size(&minmax_path(&path)).unwrap(), (12, 8), "{name}");
            assert_eq!(written, heights_files(&path, heights.levels().len()).unwrap(), "{name}");
            let back = load_heights(&path).unwrap();
            assert_eq!(back.levels().len(), heights.levels().len());
            for (a, b) in back.levels().iter().zip(heights.levels()) {
                let worst = a.texels.iter().zip(&b.texels).map(|(x, y)| (x - y).abs()).fold(0.0, f32::max);
                assert!(worst <= 0.5 / 65535.0 + 1e-7, "{name}: {worst}");
            }
            // Rounded outward: still bounds of the heights read back.
            for (a, b) in back.minmax().unwrap().iter().zip(heights.minmax().unwrap()) {
                for (x, y) in a.texels.iter().zip(&b.texels) {
                    assert!(x[0] <= y[0] && x[1] >= y[1] && y[0] - x[0] < 2.0 / 65535.0, "{name}: {x:?} vs {y:?}");
                }
            }
            for f in written {
                std::fs::remove_file(f).unwrap();
            }
        }
    }

    #[test]
    fn a_missing_bounds_file_leaves_none_and_a_short_chain_is_named() {
        let field = bumpmap_math::HeightPreset::Dimples.render(8, 8);
        let heights = HeightMips::from_field(&field).unwrap();
        let scratch = Scratch::new("alone");
        let path = scratch.file("alone.png");
        let mut set = FileSet::new(&[]);
        write_heights_into(&mut set, &path, &heights, HeightBits::Eight).unwrap();
        let written = set.commit().unwrap();
        assert_eq!(written.len(), 8, "8×8: four levels of heights, four of bounds");
        // The bounds' last level lost: named, with what it should have.
        std::fs::remove_file(&written[7]).unwrap();
        let err = load_heights(&path).unwrap_err().to_string();
        assert!(
            err.contains("alone.minmax.png") && err.contains("min–max has 3 levels; a 8x8 level 0 takes all 4"),
            "{err}"
        );
        // No bounds file at all: heights without bounds.
        for f in &written[4..7] {
            std::fs::remove_file(f).unwrap();
        }
        assert!(load_heights(&path).unwrap().minmax().is_none());
        // Heights' level 0 alone: its chain is made.
        for f in &written[1..4] {
            std::fs::remove_file(f).unwrap();
        }
        let back = load_heights(&path).unwrap();
        assert_eq!(back.levels().len(), 4);
        std::fs::remove_file(&written[0]).unwrap();
        assert!(load_heights(&scratch.file("h.tga")).unwrap_err().to_string().contains(".png, .dds or .ktx2"));
    }
}
