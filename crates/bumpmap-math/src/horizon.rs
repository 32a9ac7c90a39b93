//! Horizon maps (Max 1988; Sloan & Cohen 2000) and the three things they give: bumps that
//! shadow each other, ambient occlusion, and bent normals.
//!
//! For each texel and each of [`AZIMUTHS`] directions in the texture plane, how high the heights
//! around it rise: `rise = max over d > 0 of (h(p + d·dir) − h(p)) / d`, heights per texel of
//! level 0. The rise does not depend on how deep the heights are drawn, so one horizon map serves
//! every depth: at `depth` texels per unit of height the horizon's elevation is
//! `atan(depth · rise)`. A texel stores [`encode_rise`]`(rise) = atan(rise) / 90°` in [0, 1] —
//! the elevation the horizon would have at a depth of one texel — so 8-bit files keep
//! resolution where rises are small, and a texture unit's filtering of it stays monotone.
//!
//! Direction `k` points at `k · 45°` from +x (along +s) toward +y (along +t, down the image as
//! displayed): 0 is +x, 2 is +y, 4 is −x, 6 is −y. The rise is searched on the heights' C¹
//! interpolant (`crate::interpolant`, the surface `crate::height_trace` casts rays at): its slope
//! at the texel, every quarter of the first step (where the surface bends most for its
//! distance), then texel centres and, over the first eight steps, the midpoints between them, out to [`MAX_REACH`] steps or until no height left in the field could rise higher.
//! Over repeating heights the far steps go block by block where a max pyramid shows a block
//! too low to rise above the horizon found (`reach`: the same horizons, bit for bit).
//!
//! What this module does not do: light a fragment (the lighting model multiplies by
//! [`visibility`]), or read and write files.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::buffer::OutOfMemory;
use crate::buffer::try_vec;
use crate::encoding::{Encoding, Texel};
use crate::image::Image;
use crate::interpolant::{HeightGrid, sample_texels, wrap_index};
use crate::kernel::Wrap;
use crate::levels::{chain_sizes, footprint, next_size};
use crate::normalmap::{YConvention, encode_unit};

/// Directions per texel: 8, as Sloan & Cohen store them in two RGBA textures.
pub const AZIMUTHS: usize = 8;
/// The farthest a horizon is searched, in steps of a texel (√2 texels diagonally): a whole
/// height's rise over 256 texels is an elevation under 1° at a depth of 4 texels.
pub const MAX_REACH: usize = 256;
/// Half the width of the shadow's soft edge (Sloan & Cohen's smooth step), in the encoded
/// elevation ([`encode_rise`]: 0.02 is 1.8° at a depth of one texel).
pub const HORIZON_EDGE: f32 = 0.02;

/// One texel's horizons: [`encode_rise`] of the rise in each direction.
pub type Horizons = [f32; AZIMUTHS];

/// The interpolant's samples a quarter of a step apart over the first step (¼, ½, ¾), where the
/// surface bends most for its distance.
const NEAR_SAMPLES: usize = 4;

/// Steps whose midpoints are searched too; farther out, where a bump between two centres
/// changes the rise by less, only the centres are.
const MIDPOINT_STEPS: i64 = 8;

/// The texel step of direction `k`: (±1 or 0, ±1 or 0).
const STEPS: [(i64, i64); AZIMUTHS] = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1)];

/// The unit vector of direction `k` in texel space (x along +s, y along +t).
pub fn azimuth(k: usize) -> Vec2 {
    let a = k as f32 * std::f32::consts::FRAC_PI_4;
    Vec2::new(a.cos(), a.sin())
}

/// A rise (heights per texel, ≥ 0) as a texel stores it: `atan(rise) / 90°`.
#[inline]
pub fn encode_rise(rise: f32) -> f32 {
    rise.max(0.0).atan() * std::f32::consts::FRAC_2_PI
}

/// The rise a stored value means: `tan(value · 90°)`.
#[inline]
pub fn decode_rise(value: f32) -> f32 {
    (value.clamp(0.0, 1.0) * std::f32::consts::FRAC_PI_2).tan()
}

/// One level of horizons, row-major, row 0 = t = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct HorizonLevel {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `width·height` texels.
    pub texels: Vec<Horizons>,
}

impl HorizonLevel {
    /// GL's LINEAR lookup with REPEAT at texture coordinates (s, t), every direction, as
    /// `crate::height_mips::HeightLevel::bilinear` reads heights.
    #[inline]
    pub fn bilinear(&self, s: f32, t: f32) -> Horizons {
        let (i0, i1, a) = crate::interpolant::linear_repeat(s, self.width);
        let (j0, j1, b) = crate::interpolant::linear_repeat(t, self.height);
        let (r0, r1) = (j0 * self.width, j1 * self.width);
        let (ca, cb) = (1.0 - a, 1.0 - b);
        let [p00, p10, p01, p11] = [r0 + i0, r0 + i1, r1 + i0, r1 + i1].map(|i| &self.texels[i]);
        std::array::from_fn(|k| {
            let v = p00[k] * (ca * cb);
            let v = p10[k].mul_add(a * cb, v);
            let v = p01[k].mul_add(ca * b, v);
            p11[k].mul_add(a * b, v)
        })
    }
}

/// A horizon map with its mip levels: each smaller level the mean of the stored values it
/// covers, so at a distance the shadow's edge widens instead of flickering.
#[derive(Clone, Debug, PartialEq)]
pub struct HorizonMap {
    levels: Vec<HorizonLevel>,
}

/// Why levels cannot be a [`HorizonMap`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum HorizonError {
    /// A buffer the machine would not give.
    #[error(transparent)]
    OutOfMemory(#[from] OutOfMemory),
    /// A level of the wrong size for its place in the chain.
    #[error("horizon level {level} is {got_w}x{got_h}, but level {level} of a {w0}x{h0} level 0 is {want_w}x{want_h}")]
    LevelSize {
        /// The level.
        level: usize,
        /// Its size.
        got_w: usize,
        /// Its size.
        got_h: usize,
        /// The size it should have.
        want_w: usize,
        /// The size it should have.
        want_h: usize,
        /// Level 0's size.
        w0: usize,
        /// Level 0's size.
        h0: usize,
    },
    /// No levels.
    #[error("a horizon map needs at least level 0")]
    Empty,
    /// A stored value that is not a number in [0, 1].
    #[error("horizon at ({x}, {y}) of level {level}, direction {direction}, is {value}, not a number in [0, 1]")]
    NotAHorizon {
        /// The level.
        level: usize,
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The direction.
        direction: usize,
        /// The value.
        value: f32,
    },
}

impl HorizonMap {
    /// The horizons of `heights` (read beyond the edges as `wrap` says), every level. Texels run
    /// in parallel by rows.
    pub fn from_heights(heights: &(impl HeightGrid + Sync), wrap: Wrap) -> Result<Self, HorizonError> {
        Self::from_heights_told(heights, wrap, &|_, _| {})
    }

    /// [`Self::from_heights`], telling `progress(rows done, rows)` as level 0's rows finish (from
    /// any thread); a `progress` that panics stops the rows not begun, and its panic goes on
    /// ([`crate::progress::Told`]).
    pub fn from_heights_told(
        heights: &(impl HeightGrid + Sync),
        wrap: Wrap,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Self, HorizonError> {
        let (w, h) = (heights.width(), heights.height());
        let mut texels = try_vec(w * h, "the horizon map's level 0")?;
        texels.resize(w * h, [0.0; AZIMUTHS]);
        let range = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), (x, y)| {
                (lo.min(heights.at(x, y)), hi.max(heights.at(x, y)))
            });
        // Repeating heights skip the far steps a max pyramid bounds (`reach`).
        let maxima = match wrap {
            Wrap::Repeat => Some(MaxPyramid::new(heights)?),
            _ => None,
        };
        let told = crate::progress::Told::new(progress, h);
        texels.par_chunks_mut(w.max(1)).enumerate().for_each(|(y, row)| {
            if told.stopped() {
                return;
            }
            for (x, texel) in row.iter_mut().enumerate() {
                *texel = search(heights, wrap, range, maxima.as_ref(), x, y);
            }
            told.step();
        });
        told.finish();
        Self::from_level0(HorizonLevel { width: w, height: h, texels })
    }

    /// Level 0 as given and every smaller level made from it.
    pub fn from_level0(level0: HorizonLevel) -> Result<Self, HorizonError> {
        Self::from_levels(vec![level0])
    }

    /// Levels as a file holds them: level 0 alone (the others are made) or a chain, each level
    /// the size its place says (a chain cut short is completed).
    pub fn from_levels(mut levels: Vec<HorizonLevel>) -> Result<Self, HorizonError> {
        let first = levels.first().ok_or(HorizonError::Empty)?;
        let (w0, h0) = (first.width, first.height);
        let sizes = chain_sizes(w0, h0);
        for (level, (l, &(ww, wh))) in levels.iter().zip(&sizes).enumerate() {
            if (l.width, l.height) != (ww, wh) || l.texels.len() != ww * wh {
                return Err(HorizonError::LevelSize {
                    level,
                    got_w: l.width,
                    got_h: l.height,
                    want_w: ww,
                    want_h: wh,
                    w0,
                    h0,
                });
            }
            for (i, t) in l.texels.iter().enumerate() {
                if let Some(direction) = t.iter().position(|v| !(0.0..=1.0).contains(v)) {
                    return Err(HorizonError::NotAHorizon {
                        level,
                        x: i % l.width,
                        y: i / l.width,
                        direction,
                        value: t[direction],
                    });
                }
            }
        }
        levels.truncate(sizes.len());
        while levels.len() < sizes.len() {
            let next = mean_level(levels.last().expect("level 0 is there"))?;
            levels.push(next);
        }
        Ok(Self { levels })
    }

    /// Level 0's width.
    pub fn width(&self) -> usize {
        self.levels[0].width
    }

    /// Level 0's height.
    pub fn height(&self) -> usize {
        self.levels[0].height
    }

    /// Every level, level 0 first, down to 1×1.
    pub fn levels(&self) -> &[HorizonLevel] {
        &self.levels
    }

    /// Level 0's ambient occlusion at `depth` texels per unit of height ([`ambient_occlusion`]).
    pub fn ambient_occlusion(&self, depth: f32) -> Vec<f32> {
        self.levels[0].texels.par_iter().map(|h| ambient_occlusion(h, depth)).collect()
    }

    /// Ambient occlusion at `depth` for level 0 and every smaller level, each the mean of the
    /// level-0 occlusion it covers (what a mipmapped occlusion texture holds).
    pub fn ambient_occlusion_levels(&self, depth: f32) -> Result<Vec<Image<f32>>, OutOfMemory> {
        let mut planes = vec![(
            self.width(),
            self.height(),
            self.ambient_occlusion(depth).into_iter().map(|v| [v]).collect::<Vec<_>>(),
        )];
        while let Some((w, h, last)) = planes.last().filter(|(w, h, _)| (*w, *h) != (1, 1)) {
            let next = mean_plane(*w, *h, last, "the occlusion's smaller levels")?;
            planes.push(next);
        }
        Ok(planes.into_iter().map(|(w, h, t)| Image::new(w, h, t.into_iter().map(|[v]| v).collect())).collect())
    }

    /// Level 0's bent normals at `depth` texels per unit of height ([`bent_normal`]).
    pub fn bent_normals(&self, depth: f32) -> Vec<Vec3> {
        self.levels[0].texels.par_iter().map(|h| bent_normal(h, depth)).collect()
    }

    /// Level 0's bent normals at `depth` as a tangent-space normal map in `normalmap`'s
    /// conventions: green along `y` ([`YConvention`]), components encoded as `encoding` says,
    /// A at its largest.
    pub fn bent_normal_map<T: Texel>(&self, depth: f32, y: YConvention, encoding: Encoding) -> Image<T> {
        let flip = if y == YConvention::TEXTURE_SPACE { 1.0 } else { -1.0 };
        let texels = self
            .bent_normals(depth)
            .into_iter()
            .map(|n| encode_unit::<T>(Vec3::new(n.x, flip * n.y, n.z), encoding))
            .collect();
        Image::new(self.width(), self.height(), texels)
    }

    /// Directions `4·half` to `4·half + 3` of `level` as RGBA texels (R the first), each stored
    /// value at `T`'s bits: what a horizon-map file holds (half 0 and half 1, two textures).
    pub fn directions<T: Texel>(&self, level: usize, half: usize) -> Image<T> {
        let l = &self.levels[level];
        let texels = l.texels.iter().map(|h| T::pack_unorm(std::array::from_fn(|c| h[4 * half + c]))).collect();
        Image::new(l.width, l.height, texels)
    }

    /// The bytes a horizon map of level 0 `width`×`height` takes with its levels (for estimates).
    pub fn bytes_for(width: usize, height: usize) -> u64 {
        let texels: u64 = chain_sizes(width, height).iter().map(|&(w, h)| (w * h) as u64).sum();
        texels * std::mem::size_of::<Horizons>() as u64
    }
}

/// The next level: each texel the mean of those it covers.
fn mean_level(last: &HorizonLevel) -> Result<HorizonLevel, OutOfMemory> {
    let (width, height, texels) =
        mean_plane(last.width, last.height, &last.texels, "the horizon map's smaller levels")?;
    Ok(HorizonLevel { width, height, texels })
}

/// The level after a `w`×`h` plane of `N` channels: each texel the mean of those it covers.
fn mean_plane<const N: usize>(
    w: usize,
    h: usize,
    texels: &[[f32; N]],
    what: &'static str,
) -> Result<(usize, usize, Vec<[f32; N]>), OutOfMemory> {
    let (nw, nh) = (next_size(w), next_size(h));
    let mut next = try_vec(nw * nh, what)?;
    for j in 0..nh {
        for i in 0..nw {
            let mut sum = [0.0f32; N];
            let mut n = 0.0f32;
            for y in footprint(j, h) {
                for x in footprint(i, w) {
                    sum.iter_mut().zip(&texels[y * w + x]).for_each(|(s, v)| *s += v);
                    n += 1.0;
                }
            }
            next.push(sum.map(|s| s / n));
        }
    }
    Ok((nw, nh, next))
}

/// The horizons of texel (`x`, `y`) of `heights`. `range` is the field's lowest and highest
/// height: the interpolant is clamped to it (as `crate::height_trace` clamps it to the slab:
/// Catmull-Rom's overshoot past a sharp edge is not part of the surface), and no search goes on
/// once the highest could not rise above the horizon found.
pub fn horizons_at(heights: &impl HeightGrid, wrap: Wrap, range: (f32, f32), x: usize, y: usize) -> Horizons {
    search(heights, wrap, range, None, x, y)
}

/// [`horizons_at`], its far steps skipped block by block where `maxima` (of `heights`, which
/// repeat) bound them below the horizon found: the same horizons, bit for bit.
fn search(
    heights: &impl HeightGrid,
    wrap: Wrap,
    range: (f32, f32),
    maxima: Option<&MaxPyramid>,
    x: usize,
    y: usize,
) -> Horizons {
    let (w, h) = (heights.width(), heights.height());
    let (lowest, highest) = range;
    let at = |i: i64, j: i64| heights.at(wrap_index(wrap, i, w), wrap_index(wrap, j, h));
    let (x, y) = (x as i64, y as i64);
    let h0 = at(x, y);
    // Catmull-Rom halfway between two texel centres: (−1, 9, 9, −1)/16 along the line.
    const HALF: [f32; 4] = [-1.0 / 16.0, 9.0 / 16.0, 9.0 / 16.0, -1.0 / 16.0];
    std::array::from_fn(|k| {
        let (dx, dy) = STEPS[k];
        let length = ((dx * dx + dy * dy) as f32).sqrt();
        // Near the texel the surface bends most for its distance: the interpolant's own
        // slope there, then quarters of the first step.
        let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        let step = Vec2::new(dx as f32, dy as f32);
        let g = sample_texels(heights, wrap, centre.x, centre.y);
        let mut best = (g.dx * step.x + g.dy * step.y) / length;
        for e in 1..NEAR_SAMPLES {
            let f = e as f32 / 4.0;
            let q = centre + step * f;
            best = best.max((sample_texels(heights, wrap, q.x, q.y).value.clamp(lowest, highest) - h0) / (f * length));
        }
        let far = |n: i64, best: f32| (highest - h0) / ((n as f32 + 0.5) * length) <= best;
        for n in 1..=MIDPOINT_STEPS {
            let (bx, by) = (x + n * dx, y + n * dy);
            best = best.max((at(bx, by) - h0) / (n as f32 * length));
            // The midpoint between centres n − 1 and n: the interpolant there is the product of
            // the halfway weights along each axis the step moves in.
            let (cx, cy) = ((x + (n - 1) * dx).min(bx), (y + (n - 1) * dy).min(by));
            let mid = match (dx, dy) {
                (0, _) => (0..4).map(|r| HALF[r] * at(x, cy - 1 + r as i64)).sum::<f32>(),
                (_, 0) => (0..4).map(|c| HALF[c] * at(cx - 1 + c as i64, y)).sum::<f32>(),
                _ => (0..4)
                    .map(|r| HALF[r] * (0..4).map(|c| HALF[c] * at(cx - 1 + c as i64, cy - 1 + r as i64)).sum::<f32>())
                    .sum::<f32>(),
            };
            best = best.max((mid.clamp(lowest, highest) - h0) / ((n as f32 - 0.5) * length));
            // Past here nothing can rise above the horizon found.
            if far(n, best) {
                return encode_rise(best);
            }
        }
        // Farther out, centres only, their indices stepped under the wrap (no division a step).
        let (mut i, mut j) =
            (wrap_index(wrap, x + MIDPOINT_STEPS * dx, w), wrap_index(wrap, y + MIDPOINT_STEPS * dy, h));
        // Steps before this one are not bounded again: the block there could rise higher.
        let mut ask_from = MIDPOINT_STEPS + 1;
        let mut n = MIDPOINT_STEPS;
        while n < MAX_REACH as i64 {
            n += 1;
            i = advance(i, dx, w, wrap);
            j = advance(j, dy, h, wrap);
            if let (Some(maxima), true) = (maxima, n >= ask_from) {
                let left = MAX_REACH as i64 - n + 1;
                match maxima.skip((i, j), (dx, dy), n, left, h0, length, best) {
                    Ok(steps) => {
                        // Every step of the block from here is no higher than the horizon found:
                        // on to its last, which the wrap does not cross inside a block.
                        n += steps - 1;
                        i = (i as i64 + dx * (steps - 1)) as usize;
                        j = (j as i64 + dy * (steps - 1)) as usize;
                        if far(n, best) {
                            break;
                        }
                        continue;
                    }
                    Err(steps) => ask_from = n + steps,
                }
            }
            best = best.max((heights.at(i, j) - h0) / (n as f32 * length));
            // Under clamp, once every coordinate the step moves is past the edge, the heights
            // stay as they are and the rise only falls.
            let out = |moves: i64, c: i64, size: usize| moves == 0 || !(0..size as i64).contains(&c);
            let beyond_edge = wrap != Wrap::Repeat && out(dx, x + n * dx, w) && out(dy, y + n * dy, h);
            if far(n, best) || beyond_edge {
                break;
            }
        }
        encode_rise(best)
    })
}

/// Index `i` of `n` moved by `d` (−1, 0 or 1) under `wrap`.
#[inline(always)]
fn advance(i: usize, d: i64, n: usize, wrap: Wrap) -> usize {
    match (d, wrap) {
        (0, _) => i,
        (1, Wrap::Repeat) => {
            if i + 1 == n {
                0
            } else {
                i + 1
            }
        }
        (_, Wrap::Repeat) => {
            if i == 0 {
                n - 1
            } else {
                i - 1
            }
        }
        (1, _) => (i + 1).min(n - 1),
        (_, _) => i.saturating_sub(1),
    }
}

/// The stored horizon toward texel-space direction (`x`, `y`): the two stored directions
/// around it interpolated linearly by angle.
#[inline]
pub fn horizon_toward(horizons: &Horizons, x: f32, y: f32) -> f32 {
    let turns = y.atan2(x) * (AZIMUTHS as f32 / std::f32::consts::TAU);
    let f = turns.rem_euclid(AZIMUTHS as f32);
    let k = (f.floor() as usize).min(AZIMUTHS - 1);
    let a = f - k as f32;
    horizons[k] + a * (horizons[(k + 1) % AZIMUTHS] - horizons[k])
}

/// How much of a light reaches a point whose (filtered) horizons are `horizons`:
/// `to_light` is toward the light in texel space (x, y in texels of level 0, z in heights).
/// 1 where the light's elevation is above the horizon toward it by more than
/// [`HORIZON_EDGE`], 0 below it by as much, a smooth step between (Sloan & Cohen's soft edge).
/// Both elevations are compared as stored, at a depth of one texel: the comparison does not
/// depend on the depth.
#[inline]
pub fn visibility(horizons: &Horizons, to_light: Vec3) -> f32 {
    let across = Vec2::new(to_light.x, to_light.y).length();
    let light = to_light.z.atan2(across) * std::f32::consts::FRAC_2_PI;
    let horizon = horizon_toward(horizons, to_light.x, to_light.y);
    smoothstep(horizon - HORIZON_EDGE, horizon + HORIZON_EDGE, light)
}

/// GLSL's and WGSL's `smoothstep`.
#[inline]
pub fn smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The elevations (radians) of one texel's horizons at `depth` texels per unit of height.
fn elevations(horizons: &Horizons, depth: f32) -> [f32; AZIMUTHS] {
    horizons.map(|v| (depth * decode_rise(v)).atan())
}

/// Ambient occlusion: the cosine-weighted fraction of the hemisphere above the base surface
/// that the horizons leave open, `(1/2π) ∫ cos² e(φ) dφ` with each direction standing for an
/// eighth of the circle (a flat texel: 1).
pub fn ambient_occlusion(horizons: &Horizons, depth: f32) -> f32 {
    elevations(horizons, depth).iter().map(|e| e.cos() * e.cos()).sum::<f32>() / AZIMUTHS as f32
}

/// The bent normal: the mean direction of the open hemisphere, cosine-weighted, in the tangent
/// frame (x along +s, y along +t, z the base normal; unit). Over directions φ open from the zenith
/// down to elevation e, `∫ cos θ · ω dω` is `(cos³e / 3) · (cos φ, sin φ)` across and
/// `(1 − sin³e) / 3` up.
pub fn bent_normal(horizons: &Horizons, depth: f32) -> Vec3 {
    let sum = elevations(horizons, depth).iter().enumerate().fold(Vec3::ZERO, |sum, (k, e)| {
        let (s, c) = e.sin_cos();
        let across = azimuth(k) * (c * c * c / 3.0);
        sum + Vec3::new(across.x, across.y, (1.0 - s * s * s) / 3.0)
    });
    sum.normalize_or(Vec3::Z)
}

mod reach;
#[cfg(test)]
mod tests;

use reach::MaxPyramid;
