//! A C¹ interpolant of a height field: bicubic Catmull-Rom through the texel centres, with its
//! exact partial derivatives, and bounds of it over a cell from its Bézier form.
//!
//! Height `i` of a row sits at texel centre `x = i + 0.5` (texel coordinates, `x = s · width`),
//! as a texture sampler sees it. Catmull-Rom interpolates the samples and its first derivative
//! is continuous across texel boundaries, so a normal made from it has no creases the heights
//! do not have. The reference renderer shades with it (Blinn's normal on the exact surface),
//! and heights as geometry displace by it (`crate::height_trace`), so both see one surface.
//!
//! A *cell* is the square between four texel centres: cell (i, j) spans texel coordinates
//! `[i + ½, i + 1½) × [j + ½, j + 1½)`, where the interpolant is one bicubic polynomial of the
//! 4×4 texels around it. Its Bézier control net bounds it ([`cell_bounds`]): Bernstein
//! polynomials are non-negative and sum to one.
//!
//! What this module does not do: smooth (a kernel) or quantize.

use crate::height::HeightField;
use crate::kernel::Wrap;

/// A grid of heights the interpolant reads: a [`HeightField`], or a level of heights a renderer
/// keeps (`crate::height_mips`).
pub trait HeightGrid {
    /// Columns.
    fn width(&self) -> usize;
    /// Rows.
    fn height(&self) -> usize;
    /// The height at column `x`, row `y` (both in range).
    fn at(&self, x: usize, y: usize) -> f32;
}

impl HeightGrid for HeightField {
    fn width(&self) -> usize {
        HeightField::width(self)
    }
    fn height(&self) -> usize {
        HeightField::height(self)
    }
    fn at(&self, x: usize, y: usize) -> f32 {
        self.get(x, y)
    }
}

/// Value and derivatives of the interpolant at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightSample {
    /// The interpolated height.
    pub value: f32,
    /// ∂F/∂x, per texel along the rows (+s).
    pub dx: f32,
    /// ∂F/∂y, per texel down the rows (+t).
    pub dy: f32,
}

/// Catmull-Rom weights of the four samples around `t ∈ [0, 1)`.
#[inline]
pub fn weights(t: f32) -> [f32; 4] {
    let (t2, t3) = (t * t, t * t * t);
    [0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0), 0.5 * (-3.0 * t3 + 4.0 * t2 + t), 0.5 * (t3 - t2)]
}

/// The derivatives of [`weights`] with respect to `t`.
#[inline]
pub fn weight_derivatives(t: f32) -> [f32; 4] {
    let t2 = t * t;
    [
        0.5 * (-3.0 * t2 + 4.0 * t - 1.0),
        0.5 * (9.0 * t2 - 10.0 * t),
        0.5 * (-9.0 * t2 + 8.0 * t + 1.0),
        0.5 * (3.0 * t2 - 2.0 * t),
    ]
}

/// The index `i` of a grid of `n` under `wrap` (repeat, or clamp for clamp and border).
#[inline]
pub fn wrap_index(wrap: Wrap, i: i64, n: usize) -> usize {
    match wrap {
        Wrap::Repeat => Wrap::Repeat.index(i, n),
        Wrap::Clamp | Wrap::Border => Wrap::Clamp.index(i, n),
    }
}

/// The 4×4 heights around cell (`i`, `j`): `p[row][column]`, rows `j − 1 … j + 2`, columns
/// `i − 1 … i + 2`, wrapped by `wrap`.
#[inline]
pub fn cell_texels(grid: &impl HeightGrid, wrap: Wrap, i: i64, j: i64) -> [[f32; 4]; 4] {
    let (w, h) = (grid.width(), grid.height());
    let cols: [usize; 4] = std::array::from_fn(|k| wrap_index(wrap, i - 1 + k as i64, w));
    std::array::from_fn(|r| {
        let row = wrap_index(wrap, j - 1 + r as i64, h);
        cols.map(|c| grid.at(c, row))
    })
}

/// The interpolant of one cell's texels ([`cell_texels`]) at fractions (`fx`, `fy`) ∈ [0, 1]²
/// of the cell, with its derivatives per texel.
#[inline]
pub fn eval_cell(p: &[[f32; 4]; 4], fx: f32, fy: f32) -> HeightSample {
    let (wx, dwx) = (weights(fx), weight_derivatives(fx));
    let (wy, dwy) = (weights(fy), weight_derivatives(fy));
    let (mut value, mut dx, mut dy) = (0.0, 0.0, 0.0);
    for j in 0..4 {
        let (mut r, mut rd) = (0.0, 0.0);
        for i in 0..4 {
            r += wx[i] * p[j][i];
            rd += dwx[i] * p[j][i];
        }
        value += wy[j] * r;
        dx += wy[j] * rd;
        dy += dwy[j] * r;
    }
    HeightSample { value, dx, dy }
}

/// The value alone of [`eval_cell`] (the root search's inner loop).
#[inline]
pub fn eval_cell_value(p: &[[f32; 4]; 4], fx: f32, fy: f32) -> f32 {
    let (wx, wy) = (weights(fx), weights(fy));
    let mut value = 0.0;
    for j in 0..4 {
        let r = wx[0] * p[j][0] + wx[1] * p[j][1] + wx[2] * p[j][2] + wx[3] * p[j][3];
        value += wy[j] * r;
    }
    value
}

/// Samples the interpolant of `grid` at texture coordinate (s, t) (one repeat = [0, 1]).
pub fn sample(grid: &impl HeightGrid, wrap: Wrap, s: f32, t: f32) -> HeightSample {
    sample_texels(grid, wrap, s * grid.width() as f32, t * grid.height() as f32)
}

/// Samples the interpolant at texel coordinates (x, y) (`x = s · width`).
pub fn sample_texels(grid: &impl HeightGrid, wrap: Wrap, x: f32, y: f32) -> HeightSample {
    let (cx, cy) = (x - 0.5, y - 0.5);
    let (i, j) = (cx.floor(), cy.floor());
    let p = cell_texels(grid, wrap, i as i64, j as i64);
    eval_cell(&p, cx - i, cy - j)
}

/// Catmull-Rom's segment between samples 1 and 2 of `p` as Bézier control points:
/// `b₁ = p₁ + (p₂ − p₀)/6`, `b₂ = p₂ − (p₃ − p₁)/6` (the Hermite tangents ½(p₂ − p₀), ½(p₃ − p₁)
/// over three).
#[inline]
fn bezier(p: [f32; 4]) -> [f32; 4] {
    [p[1], p[1] + (p[2] - p[0]) / 6.0, p[2] - (p[3] - p[1]) / 6.0, p[2]]
}

/// Bounds (min, max) of the interpolant over a cell from its texels ([`cell_texels`]): the
/// extremes of its 4×4 Bézier control net, which the patch never leaves (it may be tighter).
pub fn cell_bounds(p: &[[f32; 4]; 4]) -> (f32, f32) {
    // Rows to Bézier form along x, then columns along y.
    let rows: [[f32; 4]; 4] = p.map(bezier);
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for i in 0..4 {
        for b in bezier([rows[0][i], rows[1][i], rows[2][i], rows[3][i]]) {
            lo = lo.min(b);
            hi = hi.max(b);
        }
    }
    (lo, hi)
}

/// The texel index below `u` (texel units, centres at half-integers) and the weight of the next
/// one, for GL's LINEAR under REPEAT: `u = frac(s)·n − ½` (GL 1.2 §3.8.8).
#[inline(always)]
pub(crate) fn linear_repeat(s: f32, n: usize) -> (usize, usize, f32) {
    let nf = n as f32;
    let u = (s - s.floor()) * nf - 0.5;
    let f = u.floor();
    let a = u - f;
    // u ∈ [−½, n − ½): floor(u) ∈ [−1, n − 1].
    let i = f as i64;
    let i0 = if i < 0 { n - 1 } else { (i as usize).min(n - 1) };
    (i0, if i0 + 1 == n { 0 } else { i0 + 1 }, a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn interpolates_the_samples_at_texel_centres() {
        let field = crate::HeightPreset::Noise(4).render(9, 7);
        for y in 0..7 {
            for x in 0..9 {
                let (s, t) = ((x as f32 + 0.5) / 9.0, (y as f32 + 0.5) / 7.0);
                let got = sample(&field, Wrap::Repeat, s, t).value;
                assert!((got - field.get(x, y)).abs() < 1e-5, "({x}, {y}): {got} vs {}", field.get(x, y));
            }
        }
    }

    #[test]
    fn a_ramp_has_its_slope_everywhere_inside() {
        // F = 0.01·x: Catmull-Rom reproduces linear functions, derivative 0.01 per texel.
        let field = HeightField::from_fn(16, 4, |x, _| 0.01 * x as f32);
        for i in 0..40 {
            let s = (2.0 + i as f32 * 0.25) / 16.0;
            let h = sample(&field, Wrap::Clamp, s, 0.5);
            assert!((h.dx - 0.01).abs() < 1e-5 && h.dy.abs() < 1e-6, "{s}: {h:?}");
        }
    }

    proptest! {
        #[test]
        fn derivatives_match_finite_differences(s in 0.0f32..1.0, t in 0.0f32..1.0) {
            // C¹: a central difference converges to the analytic derivative everywhere,
            // texel boundaries included. Step 1e-3 texels; f32 noise bounds the tolerance.
            let field = crate::HeightPreset::Noise(7).render(8, 8);
            let e = 1e-3 / 8.0;
            let h = sample(&field, Wrap::Repeat, s, t);
            let fx = (sample(&field, Wrap::Repeat, s + e, t).value - sample(&field, Wrap::Repeat, s - e, t).value) / 2e-3;
            let fy = (sample(&field, Wrap::Repeat, s, t + e).value - sample(&field, Wrap::Repeat, s, t - e).value) / 2e-3;
            prop_assert!((h.dx - fx).abs() < 2e-2, "dx {} vs {}", h.dx, fx);
            prop_assert!((h.dy - fy).abs() < 2e-2, "dy {} vs {}", h.dy, fy);
        }

        #[test]
        fn the_control_net_bounds_the_cell(seed in 0u64..1000, fx in 0.0f32..=1.0, fy in 0.0f32..=1.0) {
            // Random heights (steps included, where Catmull-Rom overshoots): every value inside
            // the cell lies within the net's extremes (f32 rounding: 1e-6).
            let field = crate::HeightPreset::Noise(seed).render(6, 6);
            let steps = HeightField::from_fn(6, 6, |x, y| if (x + 2 * y + seed as usize).is_multiple_of(3) { 1.0 } else { 0.0 });
            for grid in [&field, &steps] {
                for (i, j) in [(0i64, 0i64), (2, 3), (5, 5)] {
                    let p = cell_texels(grid, Wrap::Repeat, i, j);
                    let (lo, hi) = cell_bounds(&p);
                    let v = eval_cell_value(&p, fx, fy);
                    prop_assert!(v >= lo - 1e-6 && v <= hi + 1e-6, "{v} outside [{lo}, {hi}]");
                    prop_assert_eq!(v, eval_cell(&p, fx, fy).value);
                }
            }
        }
    }

    #[test]
    fn the_bounds_are_tight_at_a_corner_and_wider_than_the_texels_at_a_step() {
        // A flat cell is bounded by its own height; next to a step Catmull-Rom overshoots the
        // texels, and the net's bounds reach past [0, 1] to hold the overshoot.
        let flat = [[0.4f32; 4]; 4];
        assert_eq!(cell_bounds(&flat), (0.4, 0.4));
        let step = [[0.0, 0.0, 1.0, 1.0]; 4];
        let (lo, hi) = cell_bounds(&[[0.0, 1.0, 1.0, 1.0]; 4]);
        assert!(hi > 1.0 && lo >= 0.0, "({lo}, {hi})");
        let (lo, hi) = cell_bounds(&step);
        assert_eq!((lo, hi), (0.0, 1.0), "a symmetric step overshoots nowhere inside its own cell");
    }
}
