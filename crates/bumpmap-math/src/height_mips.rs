//! Heights as the techniques that treat them as geometry read them: a mip chain of heights for
//! the marches (parallax, steep parallax, POM, relief), and the min–max levels an exact ray
//! cast walks (Tevs, Ihrke & Seidel, *Maximum Mipmaps for Fast, Accurate, and Scalable
//! Dynamic Height Field Rendering*, I3D 2008).
//!
//! - Level 0 holds the heights clamped to [0, 1] and rounded to 16 bits, what a 16-bit file
//!   holds, so heights made here and heights read back from `normalmap --height-out`'s file
//!   are the same numbers. Each smaller level is the mean of the level-0 heights it covers,
//!   with the normal maps' footprints (`crate::mip`: sizes halve rounding down, an odd last
//!   texel joins the one before).
//! - Min–max level 0 holds, per cell (the square between four texel centres,
//!   `crate::interpolant`), bounds of the C¹ interpolant clamped to [0, 1] from its Bézier net;
//!   level k + 1 the extremes of the level-k nodes it covers, with the same footprints. A node
//!   at level k covers cells `[j·2ᵏ, (j + 1)·2ᵏ)` along each axis, the last node reaching to
//!   the edge ([`MinMaxLevel::node_of`]).
//!
//! Heights as geometry always wrap by REPEAT, as the texture units sample them over a surface
//! the texture repeats on. What this module does not do: trace rays (`crate::height_trace`),
//! choose a level from a footprint (the renderers' sampler rules), or read files.

use crate::buffer::OutOfMemory;
use crate::buffer::try_vec;
use crate::height::HeightField;
use crate::horizon::{HorizonError, HorizonMap};
use crate::interpolant::linear_repeat;
use crate::interpolant::{HeightGrid, cell_bounds, cell_texels};
use crate::kernel::Wrap;
pub use crate::levels::chain_sizes;
use crate::levels::{footprint, next_size};

/// One level of heights, row-major, row 0 = t = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct HeightLevel {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `width·height` heights in [0, 1].
    pub texels: Vec<f32>,
}

impl HeightGrid for HeightLevel {
    fn width(&self) -> usize {
        self.width
    }
    fn height(&self) -> usize {
        self.height
    }
    #[inline(always)]
    fn at(&self, x: usize, y: usize) -> f32 {
        self.texels[y * self.width + x]
    }
}

impl HeightLevel {
    /// GL's LINEAR lookup with REPEAT at texture coordinates (s, t): the four nearest heights
    /// weighted by `(1 − α)(1 − β)`, `α(1 − β)`, `(1 − α)β`, `αβ` (GL 1.2 Eq. 3.18), summed in
    /// that order.
    #[inline(always)]
    pub fn bilinear(&self, s: f32, t: f32) -> f32 {
        let (i0, i1, a) = linear_repeat(s, self.width);
        let (j0, j1, b) = linear_repeat(t, self.height);
        let (r0, r1) = (j0 * self.width, j1 * self.width);
        let (ca, cb) = (1.0 - a, 1.0 - b);
        let v = self.texels[r0 + i0] * (ca * cb);
        let v = self.texels[r0 + i1].mul_add(a * cb, v);
        let v = self.texels[r1 + i0].mul_add(ca * b, v);
        self.texels[r1 + i1].mul_add(a * b, v)
    }

    /// GL's NEAREST with REPEAT: the height of the texel containing (s, t).
    #[inline(always)]
    pub fn nearest(&self, s: f32, t: f32) -> f32 {
        let index = |s: f32, n: usize| (((s - s.floor()) * n as f32) as usize).min(n - 1);
        self.texels[index(t, self.height) * self.width + index(s, self.width)]
    }
}

/// One level of min–max bounds: `(min, max)` per node.
#[derive(Clone, Debug, PartialEq)]
pub struct MinMaxLevel {
    /// Nodes along x.
    pub width: usize,
    /// Nodes along y.
    pub height: usize,
    /// `width·height` bounds, row-major.
    pub texels: Vec<[f32; 2]>,
}

impl MinMaxLevel {
    /// The node of this level (level `k`) covering cell `cell` along an axis of `nodes` nodes:
    /// `min(cell >> k, nodes − 1)`, the last node taking what the halving left over.
    #[inline(always)]
    pub fn node_of(cell: usize, k: u32, nodes: usize) -> usize {
        (cell >> k).min(nodes - 1)
    }

    /// The bounds of node (x, y).
    #[inline(always)]
    pub fn at(&self, x: usize, y: usize) -> [f32; 2] {
        self.texels[y * self.width + x]
    }
}

/// Which chain of a [`HeightMips`] an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeightChain {
    /// The heights' levels.
    Heights,
    /// The min–max levels.
    MinMax,
}

impl std::fmt::Display for HeightChain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            HeightChain::Heights => "heights",
            HeightChain::MinMax => "min–max",
        })
    }
}

/// Why heights cannot become a [`HeightMips`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum HeightMipsError {
    /// A buffer the machine would not give.
    #[error(transparent)]
    OutOfMemory(#[from] OutOfMemory),
    /// A level of the wrong size for its place in the chain.
    #[error("{what} level {level} is {got_w}x{got_h}, but level {level} of a {w0}x{h0} level 0 is {want_w}x{want_h}")]
    LevelSize {
        /// Which chain.
        what: HeightChain,
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
    /// A chain that neither is level 0 alone nor reaches 1×1.
    #[error(
        "{what} has {got} levels; a {w0}x{h0} level 0 takes {} (down to 1x1)",
        if *what == HeightChain::Heights { format!("1 or all {want}") } else { format!("all {want}") }
    )]
    LevelCount {
        /// Which chain.
        what: HeightChain,
        /// Levels given.
        got: usize,
        /// The whole chain's levels.
        want: usize,
        /// Level 0's size.
        w0: usize,
        /// Level 0's size.
        h0: usize,
    },
    /// Min–max bounds that do not hold the heights: a bounds file of another field, or of
    /// another kind of file.
    #[error(
        "min–max level 0 does not hold the heights: at ({x}, {y}) the height is {value} but the bounds are [{lo}, {hi}] (bounds of other heights?)"
    )]
    BoundsMiss {
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The height there.
        value: f32,
        /// The lower bound there.
        lo: f32,
        /// The upper bound there.
        hi: f32,
    },
    /// A height that is not a number.
    #[error("height at ({x}, {y}) of level {level} is {value}, not a number in [0, 1]")]
    NotAHeight {
        /// The level.
        level: usize,
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The value.
        value: f32,
    },
}

impl HeightMipsError {
    /// The chain a level count or size error is about; `None` for the others.
    pub fn chain(&self) -> Option<HeightChain> {
        match self {
            HeightMipsError::LevelSize { what, .. } | HeightMipsError::LevelCount { what, .. } => Some(*what),
            HeightMipsError::BoundsMiss { .. } => Some(HeightChain::MinMax),
            HeightMipsError::OutOfMemory(_) | HeightMipsError::NotAHeight { .. } => None,
        }
    }
}

/// Heights with their mip levels and, where made or given, their min–max levels.
#[derive(Clone, Debug)]
pub struct HeightMips {
    levels: Vec<HeightLevel>,
    minmax: Option<Vec<MinMaxLevel>>,
    /// Made from level 0 the first time they are asked for ([`HeightMips::horizons`]).
    horizons: std::sync::OnceLock<Result<std::sync::Arc<HorizonMap>, HorizonError>>,
}

/// Equal heights and bounds; whether the horizons were made yet does not count.
impl PartialEq for HeightMips {
    fn eq(&self, other: &Self) -> bool {
        self.levels == other.levels && self.minmax == other.minmax
    }
}

impl HeightMips {
    /// The heights of `field` clamped to [0, 1] and rounded to 16 bits, every smaller level, and
    /// the min–max levels.
    pub fn from_field(field: &HeightField) -> Result<Self, HeightMipsError> {
        Self::from_field_rounded(field, 65535)
    }

    /// [`HeightMips::from_field`] with level 0 rounded to `steps` steps instead (255: what an
    /// 8-bit file holds), so that the levels and bounds made are those of the stored heights.
    pub fn from_field_rounded(field: &HeightField, steps: u32) -> Result<Self, HeightMipsError> {
        let (w, h) = (field.width(), field.height());
        let mut texels = try_vec(w * h, "the heights' level 0")?;
        let mut row = Vec::new();
        let n = steps.max(1) as f32;
        for y in 0..h {
            texels.extend(field.row(y, &mut row).iter().map(|&v| (v.clamp(0.0, 1.0) * n).round() / n));
        }
        Self::from_level0(HeightLevel { width: w, height: h, texels })
    }

    /// Level 0 as given (clamped to [0, 1], not rounded), every smaller level and the min–max
    /// levels made from it.
    pub fn from_level0(mut level0: HeightLevel) -> Result<Self, HeightMipsError> {
        check_heights(&mut level0, 0)?;
        let levels = mean_levels(level0)?;
        let minmax = minmax_levels(&levels[0])?;
        Ok(Self { levels, minmax: Some(minmax), horizons: Default::default() })
    }

    /// Levels as a file holds them: level 0 alone (the others are made) or the whole chain, and
    /// the min–max levels (the whole chain) or none. Sizes and counts are checked, heights
    /// clamped to [0, 1]; the min–max bounds are taken as they are.
    pub fn from_levels(
        mut levels: Vec<HeightLevel>,
        minmax: Option<Vec<MinMaxLevel>>,
    ) -> Result<Self, HeightMipsError> {
        let Some(first) = levels.first() else {
            return Err(HeightMipsError::LevelCount { what: HeightChain::Heights, got: 0, want: 1, w0: 0, h0: 0 });
        };
        let (w0, h0) = (first.width, first.height);
        let sizes = chain_sizes(w0, h0);
        let check = |what: HeightChain, got: &[(usize, usize)]| -> Result<(), HeightMipsError> {
            if got.len() != sizes.len() && !(what == HeightChain::Heights && got.len() == 1) {
                return Err(HeightMipsError::LevelCount { what, got: got.len(), want: sizes.len(), w0, h0 });
            }
            for (level, (&(gw, gh), &(ww, wh))) in got.iter().zip(&sizes).enumerate() {
                if (gw, gh) != (ww, wh) {
                    return Err(HeightMipsError::LevelSize {
                        what,
                        level,
                        got_w: gw,
                        got_h: gh,
                        want_w: ww,
                        want_h: wh,
                        w0,
                        h0,
                    });
                }
            }
            Ok(())
        };
        check(HeightChain::Heights, &levels.iter().map(|l| (l.width, l.height)).collect::<Vec<_>>())?;
        if let Some(m) = &minmax {
            check(HeightChain::MinMax, &m.iter().map(|l| (l.width, l.height)).collect::<Vec<_>>())?;
        }
        for (k, level) in levels.iter_mut().enumerate() {
            check_heights(level, k)?;
        }
        // The bounds of cell (x, y) hold its corner texel (x, y): what a bounds file of these
        // heights does, to the 16-bit rounding it is stored at.
        if let Some(bounds) = minmax.as_ref().and_then(|m| m.first()) {
            const ROUNDING: f32 = 1.5 / 65535.0;
            let level0 = &levels[0];
            let miss = level0
                .texels
                .iter()
                .zip(&bounds.texels)
                .position(|(v, &[lo, hi])| !(lo - ROUNDING..=hi + ROUNDING).contains(v));
            if let Some(k) = miss {
                let [lo, hi] = bounds.texels[k];
                let (x, y) = (k % level0.width, k / level0.width);
                return Err(HeightMipsError::BoundsMiss { x, y, value: level0.texels[k], lo, hi });
            }
        }
        let levels = if levels.len() == 1 { mean_levels(levels.swap_remove(0))? } else { levels };
        Ok(Self { levels, minmax, horizons: Default::default() })
    }

    /// The horizon map of level 0 (`crate::horizon`, heights wrapped around as the walk wraps
    /// them), made the first time it is asked for and kept: it does not depend on the depth.
    pub fn horizons(&self) -> Result<std::sync::Arc<HorizonMap>, HorizonError> {
        self.horizons_told(&|_, _| {})
    }

    /// [`HeightMips::horizons`], telling `progress(rows done, rows)` as level 0's rows finish
    /// where the map is made by this call (the long part: minutes for 8192²).
    pub fn horizons_told(
        &self,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<std::sync::Arc<HorizonMap>, HorizonError> {
        self.horizons
            .get_or_init(|| {
                HorizonMap::from_heights_told(&self.levels[0], Wrap::Repeat, progress).map(std::sync::Arc::new)
            })
            .clone()
    }

    /// These heights with `horizons` as their horizon map (a file's, say) instead of the one
    /// [`HeightMips::horizons`] would make; refused unless it is level 0's size.
    pub fn with_horizons(self, horizons: std::sync::Arc<HorizonMap>) -> Result<Self, HorizonError> {
        let (w, h) = (self.width(), self.height());
        if (horizons.width(), horizons.height()) != (w, h) {
            return Err(HorizonError::LevelSize {
                level: 0,
                got_w: horizons.width(),
                got_h: horizons.height(),
                want_w: w,
                want_h: h,
                w0: w,
                h0: h,
            });
        }
        let made = std::sync::OnceLock::new();
        made.get_or_init(|| Ok(horizons));
        Ok(Self { horizons: made, ..self })
    }

    /// Level 0's width.
    pub fn width(&self) -> usize {
        self.levels[0].width
    }

    /// Level 0's height.
    pub fn height(&self) -> usize {
        self.levels[0].height
    }

    /// Every level, level 0 first.
    pub fn levels(&self) -> &[HeightLevel] {
        &self.levels
    }

    /// The min–max levels, level 0 (cells) first, where they were made or given.
    pub fn minmax(&self) -> Option<&[MinMaxLevel]> {
        self.minmax.as_deref()
    }

    /// The same heights with min–max levels made from level 0 where there were none.
    pub fn with_minmax(mut self) -> Result<Self, HeightMipsError> {
        if self.minmax.is_none() {
            self.minmax = Some(minmax_levels(&self.levels[0])?);
        }
        Ok(self)
    }

    /// Bytes held, for memory estimates.
    pub fn bytes(&self) -> u64 {
        let h: usize = self.levels.iter().map(|l| l.texels.len() * 4).sum();
        let m: usize = self.minmax.iter().flatten().map(|l| l.texels.len() * 8).sum();
        (h + m) as u64
    }

    /// Bytes [`HeightMips::from_field`] needs for a `width`×`height` field (heights and min–max
    /// levels, each about 4/3 of its level 0).
    pub fn bytes_for(width: usize, height: usize) -> u64 {
        (width as u64).saturating_mul(height as u64).saturating_mul(12).saturating_mul(4) / 3
    }
}

/// Clamps a level's heights to [0, 1]; NaN is refused.
fn check_heights(level: &mut HeightLevel, k: usize) -> Result<(), HeightMipsError> {
    if let Some(i) = level.texels.iter().position(|v| v.is_nan()) {
        return Err(HeightMipsError::NotAHeight {
            level: k,
            x: i % level.width,
            y: i / level.width,
            value: level.texels[i],
        });
    }
    level.texels.iter_mut().for_each(|v| *v = v.clamp(0.0, 1.0));
    Ok(())
}

/// Level 0 and each smaller level, the mean of the level-0 heights it covers.
fn mean_levels(level0: HeightLevel) -> Result<Vec<HeightLevel>, HeightMipsError> {
    let mut levels = vec![level0];
    // How many level-0 columns (rows) each texel of the last level covers: the weights that
    // make a mean of means the mean of level 0.
    let mut cols = vec![1.0f32; levels[0].width];
    let mut rows = vec![1.0f32; levels[0].height];
    while let Some(last) = levels.last().filter(|l| (l.width, l.height) != (1, 1)) {
        let (w, h) = (last.width, last.height);
        let (nw, nh) = (next_size(w), next_size(h));
        let mut texels = try_vec(nw * nh, "the heights' smaller levels")?;
        let next_cols: Vec<f32> = (0..nw).map(|i| footprint(i, w).map(|c| cols[c]).sum()).collect();
        let next_rows: Vec<f32> = (0..nh).map(|j| footprint(j, h).map(|r| rows[r]).sum()).collect();
        for j in 0..nh {
            for i in 0..nw {
                let mut sum = 0.0f64;
                for y in footprint(j, h) {
                    for x in footprint(i, w) {
                        sum += (last.texels[y * w + x] * cols[x] * rows[y]) as f64;
                    }
                }
                texels.push((sum / (next_cols[i] * next_rows[j]) as f64) as f32);
            }
        }
        (cols, rows) = (next_cols, next_rows);
        levels.push(HeightLevel { width: nw, height: nh, texels });
    }
    Ok(levels)
}

/// The min–max levels of `level0`'s clamped interpolant.
fn minmax_levels(level0: &HeightLevel) -> Result<Vec<MinMaxLevel>, HeightMipsError> {
    let (w, h) = (level0.width, level0.height);
    let mut cells = try_vec(w * h, "the min–max level 0")?;
    for j in 0..h as i64 {
        for i in 0..w as i64 {
            let (lo, hi) = cell_bounds(&cell_texels(level0, Wrap::Repeat, i, j));
            cells.push([lo.clamp(0.0, 1.0), hi.clamp(0.0, 1.0)]);
        }
    }
    let mut levels = vec![MinMaxLevel { width: w, height: h, texels: cells }];
    while let Some(last) = levels.last().filter(|l| (l.width, l.height) != (1, 1)) {
        let (w, h) = (last.width, last.height);
        let (nw, nh) = (next_size(w), next_size(h));
        let mut texels = try_vec(nw * nh, "the min–max smaller levels")?;
        for j in 0..nh {
            for i in 0..nw {
                let mut b = [f32::INFINITY, f32::NEG_INFINITY];
                for y in footprint(j, h) {
                    for x in footprint(i, w) {
                        let [lo, hi] = last.texels[y * w + x];
                        b = [b[0].min(lo), b[1].max(hi)];
                    }
                }
                texels.push(b);
            }
        }
        levels.push(MinMaxLevel { width: nw, height: nh, texels });
    }
    Ok(levels)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interpolant::{eval_cell_value, sample_texels};

    #[test]
    fn every_level_is_the_mean_of_level_0_it_covers_for_any_size() {
        for (w, h) in [(8, 8), (7, 5), (13, 3), (1, 9)] {
            let field = crate::HeightPreset::Noise(3).render(w, h);
            let mips = HeightMips::from_field(&field).unwrap();
            assert_eq!(mips.levels().len(), chain_sizes(w, h).len());
            let mean0: f64 = mips.levels()[0].texels.iter().map(|&v| v as f64).sum::<f64>() / (w * h) as f64;
            let last = mips.levels().last().unwrap();
            assert_eq!((last.width, last.height), (1, 1));
            assert!((last.texels[0] as f64 - mean0).abs() < 1e-6, "{w}x{h}: {} vs {mean0}", last.texels[0]);
            // Level 0 is the field rounded to 16 bits.
            assert!(mips.levels()[0].texels.iter().all(|v| (v * 65535.0 - (v * 65535.0).round()).abs() < 1e-3));
        }
    }

    #[test]
    fn min_max_nodes_bound_the_interpolant_over_what_they_cover() {
        // 11×6: odd sizes, so last nodes take three children somewhere.
        let field = crate::HeightPreset::Bricks.render(11, 6);
        let mips = HeightMips::from_field(&field).unwrap();
        let level0 = &mips.levels()[0];
        let minmax = mips.minmax().unwrap();
        for step in 0..400 {
            let (x, y) = (0.5 + (step as f32 * 0.37) % 11.0, 0.5 + (step as f32 * 0.71) % 6.0);
            let v = sample_texels(level0, Wrap::Repeat, x, y).value.clamp(0.0, 1.0);
            let (cx, cy) = ((x - 0.5) as usize, (y - 0.5) as usize);
            for (k, level) in minmax.iter().enumerate() {
                let node =
                    (MinMaxLevel::node_of(cx, k as u32, level.width), MinMaxLevel::node_of(cy, k as u32, level.height));
                let [lo, hi] = level.at(node.0, node.1);
                assert!(v >= lo - 1e-6 && v <= hi + 1e-6, "level {k} node {node:?}: {v} outside [{lo}, {hi}]");
            }
        }
        // And the top node holds the extremes of the cells.
        let top = minmax.last().unwrap().texels[0];
        let cells = &minmax[0].texels;
        assert_eq!(top[0], cells.iter().map(|c| c[0]).fold(f32::INFINITY, f32::min));
        assert_eq!(top[1], cells.iter().map(|c| c[1]).fold(f32::NEG_INFINITY, f32::max));
        let p = cell_texels(level0, Wrap::Repeat, 3, 2);
        assert!(eval_cell_value(&p, 0.5, 0.5) <= cells[2 * 11 + 3][1] + 1e-6);
    }

    #[test]
    fn bilinear_blends_the_four_nearest_heights_with_repeat() {
        let level = HeightLevel { width: 4, height: 2, texels: vec![0.0, 0.1, 0.2, 0.3, 1.0, 1.0, 1.0, 1.0] };
        // At a texel centre: the texel.
        assert!((level.bilinear(1.5 / 4.0, 0.25) - 0.1).abs() < 1e-7);
        // Halfway between columns 0 and 1 of row 0.
        assert!((level.bilinear(1.0 / 4.0, 0.25) - 0.05).abs() < 1e-7);
        // s = 0 lies between the last column and the first (REPEAT); t = 0.5 between the rows.
        assert!((level.bilinear(0.0, 0.25) - 0.15).abs() < 1e-7);
        assert!((level.bilinear(1.5 / 4.0, 0.5) - 0.55).abs() < 1e-7);
        assert_eq!(level.bilinear(1.5 / 4.0 + 3.0, 0.25 - 2.0), level.bilinear(1.5 / 4.0, 0.25));
        assert_eq!(level.nearest(0.3, 0.2), 0.1);
    }

    #[test]
    fn a_files_levels_are_checked_and_a_lone_level_gets_its_chain() {
        let level = |w: usize, h: usize| HeightLevel { width: w, height: h, texels: vec![0.5; w * h] };
        let lone = HeightMips::from_levels(vec![level(4, 4)], None).unwrap();
        assert_eq!(lone.levels().len(), 3);
        assert!(lone.minmax().is_none());
        assert!(lone.clone().with_minmax().unwrap().minmax().is_some());
        let e = HeightMips::from_levels(vec![level(4, 4), level(2, 2)], None).unwrap_err();
        assert_eq!(e, HeightMipsError::LevelCount { what: HeightChain::Heights, got: 2, want: 3, w0: 4, h0: 4 });
        let e = HeightMips::from_levels(vec![level(4, 4), level(2, 3), level(1, 1)], None).unwrap_err();
        assert!(e.to_string().contains("level 1 is 2x3, but level 1 of a 4x4 level 0 is 2x2"), "{e}");
        let mut nan = level(2, 2);
        nan.texels[3] = f32::NAN;
        let e = HeightMips::from_levels(vec![nan], None).unwrap_err();
        assert!(e.to_string().starts_with("height at (1, 1) of level 0 is NaN"), "{e}");
    }
}
