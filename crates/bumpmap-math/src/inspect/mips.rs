//! How a file's smaller levels were made, and what that costs at a distance.
//!
//! Each level is set against the 2×2 means of the level above it under three models:
//! - box-filtered: the stored vector is the mean itself, shorter than 1 where the normals it
//!   averages disagree;
//! - length in alpha (this project's files, Kilgard §5.3): the direction of the mean in RGB, its
//!   length in A;
//! - renormalized (what most tools write): the direction of the mean at unit length, the
//!   shortening thrown away.
//!
//! The model with the smallest mean error names the filter; none within [`OTHER_ABOVE`] is
//! another filter (a Kaiser or Lanczos kernel, sharpening). The cost of renormalizing is the
//! mean length the box chain from level 0 would have kept: diffuse light is linear in the
//! normal, so a renormalized level lights the distant surface up to `1/length` brighter than
//! the bumps it stands for average up close, and keeps distant highlights as sharp as near ones
//! (Kilgard §2.4.2, §5.3).
//!
//! What this module does not do: repair the levels (`bumpmap render --rebuild-mips` does).

use glam::{Vec3, Vec4, Vec4Swizzles};

use crate::image::Image;
use crate::levels::footprint;

/// How the smaller levels were made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MipFilter {
    /// The mean, unnormalized.
    Box,
    /// The mean's direction in RGB, its length in alpha.
    LengthInAlpha,
    /// The mean's direction at unit length.
    Renormalized,
    /// Neighbouring normals barely differ, so every model fits: nothing is lost either way.
    Smooth,
    /// None of the three: another filter.
    Other,
}

impl MipFilter {
    /// The name in reports: `box`, `length-in-alpha`, `renormalized`, `smooth`, `other`.
    pub fn name(self) -> &'static str {
        match self {
            MipFilter::Box => "box",
            MipFilter::LengthInAlpha => "length-in-alpha",
            MipFilter::Renormalized => "renormalized",
            MipFilter::Smooth => "smooth",
            MipFilter::Other => "other",
        }
    }
}

/// The mean vector error (of unit-length vectors) beyond which no model fits an uncompressed
/// map (8-bit quantization leaves 0.004); a compressed map adds `4·√3` times its level 0's RMS
/// length error (BC7's levels are off by up to 0.08).
pub const OTHER_ABOVE: f32 = 0.04;

/// The mean length of a level's box-filtered normals above which the level is smooth: the
/// models differ by less than 3 % (what renormalizing can brighten), within what BC7 leaves.
pub const SMOOTH_ABOVE: f32 = 0.97;

/// The fewest texels a level needs to tell the models apart.
pub const TELLING_TEXELS: usize = 64;

/// Alpha holds the mean's length where it is this much closer to the length than to 1 (the
/// mean `|alpha − length|` against the mean `1 − length`): a renormalized level's alpha of 1
/// is as far from the length as the shortening itself.
pub const ALPHA_HOLDS_LENGTH: f32 = 0.5;

/// One level checked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelCheck {
    /// The level's index (1 is half size).
    pub level: usize,
    /// Its width and height.
    pub size: (usize, usize),
    /// Mean error of each model: box, length in alpha, renormalized. Length in alpha's counts
    /// the direction (as renormalized's does) and how far alpha is from the mean's length.
    pub errors: [f32; 3],
    /// The mean of `|alpha − the mean's length|`: small only where alpha holds the length.
    pub alpha_error: f32,
    /// The mean of `1 − the mean's length`: how far an alpha of 1 would be from it.
    pub shortening: f32,
    /// The mean length of the box-filtered chain from level 0 at this size.
    pub box_length: f32,
}

/// What the smaller levels are.
#[derive(Clone, Debug, PartialEq)]
pub struct MipReport {
    /// The filter that fits the levels best.
    pub filter: MipFilter,
    /// Each level below 0.
    pub levels: Vec<LevelCheck>,
}

impl MipReport {
    /// The level whose cost is quoted: the first at an eighth of the size or smaller (what a
    /// surface a few metres off samples), else the last.
    pub fn quoted(&self) -> Option<&LevelCheck> {
        self.levels.iter().find(|l| l.level >= 3).or(self.levels.last())
    }

    /// Diffuse light at the quoted level, renormalized, over what it should be: `1/length`.
    pub fn renormalized_brightening(&self) -> Option<f32> {
        self.quoted().map(|l| 1.0 / l.box_length.max(1e-3))
    }
}

/// Checks `levels` (level 0 first; signed xyz, length or anything in w). `None` for one level.
pub fn classify(levels: &[Image<Vec4>]) -> Option<MipReport> {
    if levels.len() < 2 {
        return None;
    }
    // A compressed map's levels are as noisy as its level 0: its lengths' error, in all three
    // directions, widens what still counts as a fit.
    let length_rms = (levels[0].texels.iter().map(|t| (t.xyz().length() - 1.0).powi(2) as f64).sum::<f64>()
        / levels[0].texels.len().max(1) as f64)
        .sqrt() as f32;
    let tolerance = OTHER_ABOVE + 4.0 * 3f32.sqrt() * length_rms;
    let mut checks = Vec::new();
    let mut chain: Image<Vec3> =
        Image::new(levels[0].width, levels[0].height, levels[0].texels.iter().map(|t| t.xyz()).collect());
    for (k, pair) in levels.windows(2).enumerate() {
        let (above, level) = (&pair[0], &pair[1]);
        let (w, h) = (level.width, level.height);
        if footprint_size(above.width) != w || footprint_size(above.height) != h {
            break;
        }
        let mut errors = [0.0f64; 3];
        let (mut alpha_error, mut shortening) = (0.0f64, 0.0f64);
        for y in 0..h {
            for x in 0..w {
                let (mut raw, mut weighted, mut n) = (Vec3::ZERO, Vec3::ZERO, 0.0f32);
                for yy in footprint(y, above.height) {
                    for xx in footprint(x, above.width) {
                        let t = above.texel(xx, yy);
                        raw += t.xyz();
                        weighted += t.xyz().normalize_or_zero() * t.w;
                        n += 1.0;
                    }
                }
                let (raw, weighted) = (raw / n, weighted / n);
                let s = level.texel(x, y);
                errors[0] += (s.xyz() - raw).length() as f64;
                let alpha = (s.w - weighted.length()).abs();
                errors[1] += ((s.xyz() - weighted.normalize_or_zero()).length() + alpha) as f64;
                alpha_error += alpha as f64;
                shortening += (1.0 - weighted.length()).abs() as f64;
                errors[2] += (s.xyz() - raw.normalize_or_zero()).length() as f64;
            }
        }
        chain = box_down(&chain);
        let box_length = chain.texels.iter().map(|v| v.length() as f64).sum::<f64>() / chain.texels.len() as f64;
        let count = (w * h) as f64;
        checks.push(LevelCheck {
            level: k + 1,
            size: (w, h),
            errors: errors.map(|e| (e / count) as f32),
            alpha_error: (alpha_error / count) as f32,
            shortening: (shortening / count) as f32,
            box_length: box_length as f32,
        });
    }
    // Judged on the levels where the models differ: those whose normals shorten.
    let telling: Vec<&LevelCheck> =
        checks.iter().filter(|c| c.box_length < SMOOTH_ABOVE && c.size.0 * c.size.1 >= TELLING_TEXELS).collect();
    let filter = if checks.is_empty() {
        MipFilter::Other
    } else if telling.is_empty() {
        if checks.iter().all(|c| c.errors.iter().cloned().fold(f32::MAX, f32::min) <= tolerance) {
            MipFilter::Smooth
        } else {
            MipFilter::Other
        }
    } else {
        // Weighted by texels: level 1 speaks loudest.
        let mut total = [0.0f64; 5];
        let mut weight = 0.0f64;
        for c in &telling {
            let wgt = (c.size.0 * c.size.1) as f64;
            for (t, e) in total.iter_mut().zip(c.errors.iter().chain([&c.alpha_error, &c.shortening])) {
                *t += wgt * *e as f64;
            }
            weight += wgt;
        }
        let [boxed, _, renormalized, alpha, shortening] = total.map(|t| (t / weight) as f32);
        // Length in alpha shares renormalized's directions; its alpha tells them apart.
        if boxed.min(renormalized) > tolerance {
            MipFilter::Other
        } else if alpha <= ALPHA_HOLDS_LENGTH * shortening {
            MipFilter::LengthInAlpha
        } else if boxed < renormalized {
            MipFilter::Box
        } else {
            MipFilter::Renormalized
        }
    };
    Some(MipReport { filter, levels: checks })
}

fn footprint_size(n: usize) -> usize {
    crate::levels::next_size(n)
}

/// The next level of a box chain: 2×2 means (3 wide at an odd edge), unnormalized.
fn box_down(level: &Image<Vec3>) -> Image<Vec3> {
    let (w, h) = (footprint_size(level.width), footprint_size(level.height));
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let (mut s, mut n) = (Vec3::ZERO, 0.0);
            for yy in footprint(y, level.height) {
                for xx in footprint(x, level.width) {
                    s += level.texel(xx, yy);
                    n += 1.0;
                }
            }
            out.push(s / n);
        }
    }
    Image::new(w, h, out)
}
