//! A C¹ interpolant of a height field: bicubic Catmull-Rom through the texel centres, with its
//! exact partial derivatives.
//!
//! Height `i` of a row sits at texel centre `x = i + 0.5` (texel coordinates, `x = s · width`),
//! as a texture sampler sees it; wrapping follows the normal map's [`Wrap`] (repeat, or clamp
//! for clamp and border). Catmull-Rom interpolates the samples and its first derivative is
//! continuous across texel boundaries, so the perturbed normal has no creases the heights do
//! not have. What this module does not do: smooth (a kernel) or quantize.

use bumpmap_math::{HeightField, Wrap};

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

/// Catmull-Rom weights of the four samples around `t ∈ [0, 1)` and of its derivative.
#[inline]
fn weights(t: f32) -> ([f32; 4], [f32; 4]) {
    let (t2, t3) = (t * t, t * t * t);
    let w = [
        0.5 * (-t3 + 2.0 * t2 - t),
        0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
        0.5 * (-3.0 * t3 + 4.0 * t2 + t),
        0.5 * (t3 - t2),
    ];
    let d = [
        0.5 * (-3.0 * t2 + 4.0 * t - 1.0),
        0.5 * (9.0 * t2 - 10.0 * t),
        0.5 * (-9.0 * t2 + 8.0 * t + 1.0),
        0.5 * (3.0 * t2 - 2.0 * t),
    ];
    (w, d)
}

/// Samples the interpolant of `field` at texture coordinate (s, t) (one repeat = [0, 1]).
pub fn sample(field: &HeightField, wrap: Wrap, s: f32, t: f32) -> HeightSample {
    let (w, h) = (field.width(), field.height());
    let x = s * w as f32 - 0.5;
    let y = t * h as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (wx, dwx) = weights(x - x0);
    let (wy, dwy) = weights(y - y0);
    let (x0, y0) = (x0 as i64, y0 as i64);
    let (mut value, mut dx, mut dy) = (0.0, 0.0, 0.0);
    for j in 0..4 {
        let row = wrap_index(wrap, y0 - 1 + j as i64, h);
        let (mut r, mut rd) = (0.0, 0.0);
        for i in 0..4 {
            let f = field.get(wrap_index(wrap, x0 - 1 + i as i64, w), row);
            r += wx[i] * f;
            rd += dwx[i] * f;
        }
        value += wy[j] * r;
        dx += wy[j] * rd;
        dy += dwy[j] * r;
    }
    HeightSample { value, dx, dy }
}

fn wrap_index(wrap: Wrap, i: i64, n: usize) -> usize {
    match wrap {
        Wrap::Repeat => Wrap::Repeat.index(i, n),
        Wrap::Clamp | Wrap::Border => Wrap::Clamp.index(i, n),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn interpolates_the_samples_at_texel_centres() {
        let field = bumpmap_math::HeightPreset::Noise(4).render(9, 7);
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
            let field = bumpmap_math::HeightPreset::Noise(7).render(8, 8);
            let e = 1e-3 / 8.0;
            let h = sample(&field, Wrap::Repeat, s, t);
            let fx = (sample(&field, Wrap::Repeat, s + e, t).value - sample(&field, Wrap::Repeat, s - e, t).value) / 2e-3;
            let fy = (sample(&field, Wrap::Repeat, s, t + e).value - sample(&field, Wrap::Repeat, s, t - e).value) / 2e-3;
            prop_assert!((h.dx - fx).abs() < 2e-2, "dx {} vs {}", h.dx, fx);
            prop_assert!((h.dy - fy).abs() < 2e-2, "dy {} vs {}", h.dy, fy);
        }
    }
}
