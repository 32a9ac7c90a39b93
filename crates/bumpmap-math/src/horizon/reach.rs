//! A max pyramid over the heights, to bound a horizon search's far steps: where every height in
//! an aligned block ahead lies too low to rise above the horizon found so far, the steps inside
//! that block change nothing and are skipped. The skip is exact: a skipped step's rise is at most
//! the block's bound in floating point too (subtraction, multiplication and division are
//! monotone), so the horizons are bit-identical to the search that takes every step.
//!
//! Only heights that repeat are searched this way: there a step moves the wrapped index by one
//! and stays in its block until it crosses the block's edge. Under clamp the search takes every
//! step, as before.
//!
//! What this module does not do: search (`super::horizons_at`), or bound the near steps and the
//! midpoints, which read the interpolant rather than the texel centres.

use crate::buffer::{OutOfMemory, try_vec};
use crate::interpolant::HeightGrid;

/// The most levels kept above the heights: blocks of up to 2⁸ = 256 texels a side, the search's
/// whole reach ([`super::MAX_REACH`]).
const LEVELS: usize = 8;

/// The heights' maxima over aligned blocks of 2^l texels a side, levels 1 to [`LEVELS`] (a block
/// at the field's right or bottom edge is cut short there).
pub(super) struct MaxPyramid {
    /// Each level's width and its maxima, row by row; level 1 first.
    levels: Vec<(usize, Vec<f32>)>,
    width: usize,
    height: usize,
}

impl MaxPyramid {
    /// The pyramid of `heights`, about a third of a float a texel.
    pub(super) fn new(heights: &impl HeightGrid) -> Result<Self, OutOfMemory> {
        let (width, height) = (heights.width(), heights.height());
        let mut levels: Vec<(usize, Vec<f32>)> = Vec::new();
        let (mut w, mut h) = (width, height);
        while levels.len() < LEVELS && (w > 1 || h > 1) {
            let (nw, nh) = (w.div_ceil(2), h.div_ceil(2));
            let mut next = try_vec(nw * nh, "the horizon search's max pyramid")?;
            for by in 0..nh {
                for bx in 0..nw {
                    let mut top = f32::NEG_INFINITY;
                    for y in 2 * by..(2 * by + 2).min(h) {
                        for x in 2 * bx..(2 * bx + 2).min(w) {
                            top = top.max(match levels.last() {
                                Some((lw, below)) => below[y * lw + x],
                                None => heights.at(x, y),
                            });
                        }
                    }
                    next.push(top);
                }
            }
            levels.push((nw, next));
            (w, h) = (nw, nh);
        }
        Ok(Self { levels, width, height })
    }

    /// The block of level `level` (1 or more) that texel (`i`, `j`) lies in: its maximum, and how
    /// many steps of (`dx`, `dy`) from that texel, itself counted, stay inside it.
    fn block(&self, level: usize, i: usize, j: usize, dx: i64, dy: i64) -> (f32, i64) {
        let (lw, maxima) = &self.levels[level - 1];
        let top = maxima[(j >> level) * lw + (i >> level)];
        let inside = |c: usize, size: usize, d: i64| {
            let start = c >> level << level;
            match d {
                0 => i64::MAX,
                1 => ((start + (1 << level)).min(size) - c) as i64,
                _ => (c - start) as i64 + 1,
            }
        };
        (top, inside(i, self.width, dx).min(inside(j, self.height, dy)))
    }

    /// How many steps from step `n`, at texel (`i`, `j`), can be skipped without missing a rise
    /// above `best` (heights `h0` at the start, `length` texels a step, at most `left` steps
    /// left): the steps inside the block of about n/2 texels a side there, or `None` where that
    /// block could rise higher. Also returns how many steps that block spans from here, so that a
    /// block that could rise higher is not asked again.
    pub(super) fn skip(
        &self,
        (i, j): (usize, usize),
        (dx, dy): (i64, i64),
        n: i64,
        left: i64,
        h0: f32,
        length: f32,
        best: f32,
    ) -> Result<i64, i64> {
        let level = (n.max(2).ilog2() as usize - 1).clamp(1, self.levels.len().max(1));
        if self.levels.is_empty() {
            return Err(1);
        }
        let (top, steps) = self.block(level, i, j, dx, dy);
        let steps = steps.min(left);
        let rise = top - h0;
        // The largest rise a step of the block can have: the nearest step's where the block's top
        // is above the start, the farthest's where it is below.
        let bound = if rise >= 0.0 { rise / (n as f32 * length) } else { rise / ((n + steps - 1) as f32 * length) };
        if bound <= best { Ok(steps) } else { Err(steps) }
    }
}
