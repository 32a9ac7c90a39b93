//! What block compression added to a map, estimated from the slopes no height field explains.

use bumpmap_math::Image;
use bumpmap_math::integration::{Boundary, Derivative, DerivativeFit, Slopes, fit_derivative, integrate_fitted};
use glam::Vec4;

/// Texels leaning further than this `n_z` (60°) from the surface normal are steep.
const STEEP_NZ: f32 = 0.5;

/// The share of steep texels beyond which the compression estimate is not given: there 8-bit
/// rounding's slope error grows as `1/n_z²` and the least-squares solve spreads it onto the
/// shallow texels around, so the residual stops measuring the compression (measured: bricks at
/// scale 8 read 6× the true error, with 20 % of texels steep).
const STEEP_SHARE: f64 = 0.02;

/// The angle block compression added, estimated from what no height field explains: a map
/// made from heights holds a gradient, so the heights integrated under the kernel that fits it
/// best ([`DerivativeFit`]) leave, as the slopes' residual,
/// the part of the encoding's noise that is not itself a gradient: half of it, for noise that
/// favours no direction. A slope error `δ` tilts a texel's normal by about `δ·n_z²`. 8-bit
/// rounding's own share (0.18° RMS) is taken out. `slopes` are level 0's as the decided
/// convention reads them (undecided, the slopes are not read the way they were made: no
/// estimate). `None` where no kernel explains the map or more than [`STEEP_SHARE`] of the
/// texels are steep. The fit made on the way comes back too, so the report names the kernel
/// without fitting again.
pub(super) fn estimate(
    level0: &Image<Vec4>,
    slopes: &Slopes,
    boundary: Boundary,
) -> (Option<f32>, Option<DerivativeFit>) {
    const ROUNDING_DEGREES: f32 = 0.18;
    let steep = level0.texels.iter().filter(|t| t.z < STEEP_NZ).count();
    if steep as f64 > STEEP_SHARE * level0.texels.len() as f64 {
        return (None, fit_derivative(slopes, boundary).ok());
    }
    let Ok((heights, fit)) = integrate_fitted(slopes, boundary) else { return (None, None) };
    let Derivative::Kernel(kernel) = fit.best() else { return (None, Some(fit)) };
    let again = Slopes::of_heights(slopes.width, slopes.height, &heights, kernel);
    // A free boundary's heights do not wrap: the kernel's taps across the edge are left out.
    let r = if boundary == Boundary::Free { kernel.radius() as usize } else { 0 };
    let (w, h) = (slopes.width, slopes.height);
    let (mut sum, mut n) = (0.0f64, 0usize);
    for y in r..h.saturating_sub(r) {
        for x in r..w.saturating_sub(r) {
            let i = y * w + x;
            let nz2 = (level0.texels[i].z.max(0.0) as f64).powi(2);
            let e2 = ((slopes.du[i] - again.du[i]) as f64).powi(2) + ((slopes.dv[i] - again.dv[i]) as f64).powi(2);
            sum += e2 * nz2 * nz2;
            n += 1;
        }
    }
    let degrees = (2.0 * sum / n.max(1) as f64).sqrt().to_degrees() as f32;
    (Some((degrees.powi(2) - ROUNDING_DEGREES.powi(2)).max(0.0).sqrt()), Some(fit))
}
