//! What a normal map made elsewhere is: its Y convention, whether it is a normal map at all,
//! how its smaller levels were made, whether it tiles.
//!
//! Everything here reads decoded vectors, [`Image<Vec4>`] with the signed components in xyz and
//! the alpha (or whatever the file holds there) in w, as [`signed_levels`] makes them from 8-
//! or 16-bit unorm texels. Each question has its own module:
//! - [`convention`]: DirectX or OpenGL, by the curl test;
//! - texels: unit lengths, facing, gray ([`TexelStats`], [`MapKind`]), and the seam ([`Seam`]);
//! - mips: box-filtered, length in alpha, renormalized or another filter ([`MipReport`]).
//!
//! What this module does not do: read files, know compression formats, or word a verdict for
//! a person (that is `bumpmap::inspect`).

pub mod convention;
mod mips;
mod texels;

pub use convention::{CROP, ConventionVerdict, Undecidable, centre_crop, detect_convention};
pub use mips::{
    ALPHA_HOLDS_LENGTH, LevelCheck, MipFilter, MipReport, OTHER_ABOVE, SMOOTH_ABOVE, TELLING_TEXELS,
    classify as classify_mips,
};
pub use texels::{MEAN_SLOPE_TILES, MapKind, SEAM_SAMPLES, Seam, TexelStats};

use glam::Vec4;

use crate::encoding::{Encoding, Texel};
use crate::image::Image;

/// A map's level 0 and smaller levels answered, every question.
#[derive(Clone, Debug, PartialEq)]
pub struct Inspection {
    /// Level 0's width and height.
    pub size: (usize, usize),
    /// How many levels the map carries.
    pub levels: usize,
    /// Level 0's texels, counted.
    pub texels: TexelStats,
    /// What they say it is.
    pub kind: MapKind,
    /// The curl test.
    pub convention: ConventionVerdict,
    /// How the smaller levels were made (`None`: one level).
    pub mips: Option<MipReport>,
    /// How level 0 meets itself when it repeats.
    pub seam: Seam,
    /// Whether Z was rebuilt from X and Y (BC5, or RG with blue empty): lengths were not judged.
    pub two_channel: bool,
}

/// Every question asked of `levels` (level 0 first; signed xyz, w as stored). `two_channel`:
/// Z was rebuilt from X and Y, so lengths are 1 by construction.
pub fn inspect(levels: &[Image<Vec4>], two_channel: bool) -> Option<Inspection> {
    let level0 = levels.first()?;
    let texels = TexelStats::of(level0);
    Some(Inspection {
        size: (level0.width, level0.height),
        levels: levels.len(),
        kind: texels.kind(two_channel),
        texels,
        convention: detect_convention(level0),
        mips: classify_mips(levels),
        seam: Seam::of(level0),
        two_channel,
    })
}

/// Unorm texels (8 or 16 bits) as signed vectors: `2c/max − 1` in xyz, `a/max` in w.
pub fn signed_levels<T: Texel>(levels: &[Image<T>]) -> Vec<Image<Vec4>> {
    use rayon::prelude::*;
    levels
        .iter()
        .map(|l| {
            Image::new(l.width, l.height, l.texels.par_iter().map(|t| Vec4::from(t.unpack(Encoding::Unorm))).collect())
        })
        .collect()
}

/// Whether every texel's blue is the lowest value and its red and green are within the unit
/// disc: a two-channel (XY) map stored in an RGB image, Z left for the shader to rebuild.
pub fn is_xy_only(level: &Image<Vec4>) -> bool {
    !level.texels.is_empty() && level.texels.iter().all(|t| t.z <= -0.99 && t.x * t.x + t.y * t.y <= 1.02)
}

/// Rebuilds Z as `√(1 − x² − y²)` (0 outside the unit disc), as a shader reads a two-channel map.
pub fn rebuild_z(level: &mut Image<Vec4>) {
    for t in &mut level.texels {
        t.z = (1.0 - t.x * t.x - t.y * t.y).max(0.0).sqrt();
    }
}

#[cfg(test)]
mod tests;
