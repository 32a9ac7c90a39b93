//! Normal map → heights: the slopes a normal map holds, integrated back to the surface they
//! came from (survey: Quéau, Durou & Aujol, *Normal Integration: A Survey*, JMIV 2018).
//!
//! A texel's normal `n ∝ (−s·∂h/∂u, −s·∂h/∂v, 1)` (Kilgard Eq. 25) gives the slopes
//! `p = −n_x/n_z`, `q = −n_y/n_z` in texture space (green read along +t, so a Y-up map's green is
//! negated first). The heights are the least-squares solution of `D_u h = p`, `D_v h = q`; in
//! the Fourier domain, with `D̂` the transfer function of the difference assumed to have made
//! the slopes,
//!
//! `Ĥ = (conj(D̂_u)·P̂ + conj(D̂_v)·Q̂) / (|D̂_u|² + |D̂_v|²)`, `Ĥ(0, 0) = 0`.
//!
//! A method ([`IntegrationMethod`]) is two choices:
//! - the boundary: `fft` takes the map as periodic (right for maps that tile); `dct` solves on
//!   the map mirrored into a 2W×2H image (slopes negated in the mirrored copies) — the even
//!   extension the DCT-II assumes, which makes the solution the Poisson one with a free
//!   (Neumann) boundary, for maps that do not tile, at four times the work;
//! - the derivative: `D̂ = iω` is Frankot & Chellappa's; `D̂` the transfer function of the
//!   [`Kernel`] that made the map is its exact inverse, up to the constant, wherever
//!   `|D̂_u|² + |D̂_v|²` is not small (for the forward difference: every frequency but zero;
//!   central differences and their smoothed cousins lose the Nyquist row and column, which
//!   [`TIKHONOV`] keeps from amplifying noise).
//!
//! The result has mean zero and is in texels (the slope's unit) divided by the scale given.
//!
//! What this module does not do: decide the Y convention, the boundary or the kernel a map was
//! made with (that is [`crate::inspect`]), read files, or rescale the result to [0, 1].

use crate::Named;
use glam::Vec4;
use realfft::num_complex::Complex32;

use crate::buffer::OutOfMemory;
use crate::image::Image;
use crate::kernel::Kernel;
use crate::normalmap::YConvention;

mod fit;
mod transfer;

use fit::fit;
pub use fit::{DerivativeFit, FIT_TIE, FIT_TIE_FLOOR};
use transfer::Transfer;

/// Where the map ends: what the solve assumes beyond its edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Boundary {
    /// The map tiles: the Fourier solve over the periodic map (`fft`).
    Periodic,
    /// The map does not tile: the solve over its mirrored 2W×2H extension, which is the DCT's
    /// Poisson solution with a free (Neumann) boundary (`dct`).
    Free,
}

impl Boundary {
    /// `fft` or `dct`, the method's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Boundary::Periodic => "fft",
            Boundary::Free => "dct",
        }
    }
}

/// The difference assumed to have made the slopes: its transfer function is `D̂`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Derivative {
    /// `iω`, the derivative of the band-limited interpolant: Frankot & Chellappa's.
    Spectral,
    /// A kernel's taps (Simchony, Chellappa & Shao 1990 use the central difference the same
    /// way): the exact inverse of a map that kernel made.
    Kernel(Kernel),
}

/// `spectral` and every kernel, in [`Kernel::ALL`]'s order after it.
const DERIVATIVES: [Derivative; 1 + Kernel::ALL.len()] = {
    let mut all = [Derivative::Spectral; 1 + Kernel::ALL.len()];
    let mut k = 0;
    while k < Kernel::ALL.len() {
        all[k + 1] = Derivative::Kernel(Kernel::ALL[k]);
        k += 1;
    }
    all
};

/// `spectral`, or the kernel's own name, aliases and description.
impl Named for Derivative {
    const ALL: &'static [Self] = &DERIVATIVES;

    fn name(self) -> &'static str {
        match self {
            Derivative::Spectral => "spectral",
            Derivative::Kernel(k) => k.name(),
        }
    }

    fn description(self) -> &'static str {
        match self {
            Derivative::Spectral => "iω, the band-limited derivative (Frankot–Chellappa)",
            Derivative::Kernel(k) => k.description(),
        }
    }

    fn aliases(self) -> &'static [&'static str] {
        match self {
            Derivative::Spectral => &[],
            Derivative::Kernel(k) => k.aliases(),
        }
    }
}

/// How the slopes are integrated: where the map ends, and what made its slopes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct IntegrationMethod {
    /// Periodic (`fft`) or free (`dct`).
    pub boundary: Boundary,
    /// The derivative model.
    pub derivative: Derivative,
}

impl IntegrationMethod {
    /// Frankot–Chellappa: periodic, `iω`.
    pub const FRANKOT_CHELLAPPA: Self = Self { boundary: Boundary::Periodic, derivative: Derivative::Spectral };

    /// Periodic, the kernel's transfer function: the exact inverse of `kernel`'s map.
    pub fn kernel(kernel: Kernel) -> Self {
        Self { boundary: Boundary::Periodic, derivative: Derivative::Kernel(kernel) }
    }
}

/// How much of `|ω|²` is added to a kernel's `|D̂|²` (Tikhonov): where the kernel all but loses
/// a frequency (the Nyquist row of a central difference, Sobel's and Prewitt's near-zeros), the
/// quantization noise there is amplified at most `1/(2√ε)` = 500 times what `iω` would, and
/// every other frequency is damped by about `ε` (0.0001 %).
pub const TIKHONOV: f32 = 1e-6;

/// Why heights cannot be made from a normal map.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum IntegrationError {
    /// Fewer than two texels along a side: there are no slopes to integrate.
    #[error("a {width}x{height} map has no slopes to integrate (at least 2x2 texels are needed)")]
    TooSmall {
        /// Width in texels.
        width: usize,
        /// Height in texels.
        height: usize,
    },
    /// A texel whose vector is not a number.
    #[error("texel ({x}, {y}) is not a number")]
    NotANumber {
        /// Its column.
        x: usize,
        /// Its row.
        y: usize,
    },
    /// A scale not finite, beyond ±[`MAX_SCALE`](crate::normalmap::MAX_SCALE) (the largest a
    /// normal map is made with), or closer to 0 than its inverse (the slopes divided by it would
    /// overflow into infinite heights).
    #[error("the slope scale must be from {min:e} to {max:e} in size (either sign), got {0}", min = 1.0 / crate::normalmap::MAX_SCALE, max = crate::normalmap::MAX_SCALE)]
    BadScale(f32),
    /// The transforms' buffers would not fit.
    #[error(transparent)]
    OutOfMemory(#[from] OutOfMemory),
}

/// The smallest `n_z` a slope is taken from: a texel at or beyond 87° from the surface normal
/// (or facing away) reads as a slope of 20, not as an infinity that would flood the spectrum.
pub const MIN_NZ: f32 = 0.05;

/// The slopes `∂h/∂u`, `∂h/∂v` of a normal map, per texel, in texture space (t down the image).
#[derive(Clone, Debug, PartialEq)]
pub struct Slopes {
    /// Width in texels.
    pub width: usize,
    /// Height in texels.
    pub height: usize,
    /// `∂h/∂u` (along a row, toward the next column), row 0 first.
    pub du: Vec<f32>,
    /// `∂h/∂v` (toward the next row), row 0 first.
    pub dv: Vec<f32>,
}

impl Slopes {
    /// The slopes of `normals` (signed components in xyz; w is not read) whose green points as
    /// `y_convention` says, divided by `scale` (the `--scale` that made the map: the height of a
    /// unit step in texels). `n_z` is clamped to at least [`MIN_NZ`].
    pub fn from_normals(
        normals: &Image<Vec4>,
        y_convention: YConvention,
        scale: f32,
    ) -> Result<Self, IntegrationError> {
        check_normals(normals, scale)?;
        let (w, h) = (normals.width, normals.height);
        // Texture-space Y points down the displayed image: a Y-up map's green is negated.
        let flip = if y_convention == YConvention::YUp { -1.0 } else { 1.0 };
        use rayon::prelude::*;
        let slope = |n: &Vec4| {
            let z = n.z.max(MIN_NZ) * scale;
            (-n.x / z, -flip * n.y / z)
        };
        let du: Vec<f32> = normals.texels.par_iter().map(|n| slope(n).0).collect();
        let dv: Vec<f32> = normals.texels.par_iter().map(|n| slope(n).1).collect();
        Ok(Self { width: w, height: h, du, dv })
    }

    /// The slopes of `heights` (`width·height`, row 0 first) under `kernel`, wrapping: what a
    /// normal map made from them by that kernel at scale 1 holds, before encoding.
    pub fn of_heights(width: usize, height: usize, heights: &[f32], kernel: Kernel) -> Self {
        use rayon::prelude::*;
        let apply = |taps: &[crate::kernel::Tap]| -> Vec<f32> {
            (0..width * height)
                .into_par_iter()
                .map(|i| {
                    let (x, y) = ((i % width) as i64, (i / width) as i64);
                    taps.iter()
                        .map(|t| {
                            let xx = (x + t.dx as i64).rem_euclid(width as i64) as usize;
                            let yy = (y + t.dy as i64).rem_euclid(height as i64) as usize;
                            t.weight * heights[yy * width + xx]
                        })
                        .sum()
                })
                .collect()
        };
        Self { width, height, du: apply(&kernel.taps_du()), dv: apply(&kernel.taps_dv()) }
    }
}

/// Refuses a slope scale of 0, one not finite, or one beyond ±[`MAX_SCALE`](crate::normalmap::MAX_SCALE)
/// ([`check_normals`] does too): for a caller to refuse it before reading a map.
pub fn check_scale(scale: f32) -> Result<(), IntegrationError> {
    let max = crate::normalmap::MAX_SCALE;
    if !scale.is_finite() || !(1.0 / max..=max).contains(&scale.abs()) {
        return Err(IntegrationError::BadScale(scale));
    }
    Ok(())
}

/// Refuses what [`Slopes::from_normals`] would: a scale of 0 or not finite, fewer than 2×2
/// texels, a texel that is not a number.
pub fn check_normals(normals: &Image<Vec4>, scale: f32) -> Result<(), IntegrationError> {
    use rayon::prelude::*;
    check_scale(scale)?;
    let (w, h) = (normals.width, normals.height);
    if w < 2 || h < 2 {
        return Err(IntegrationError::TooSmall { width: w, height: h });
    }
    match normals.texels.par_iter().position_first(|n| !n.is_finite()) {
        Some(i) => Err(IntegrationError::NotANumber { x: i % w, y: i / w }),
        None => Ok(()),
    }
}

/// Bytes [`integrate`] needs for a `width`×`height` map by `method`, beyond the slopes: for
/// a command to refuse a map too big before it starts.
pub fn working_bytes(width: usize, height: usize, method: IntegrationMethod) -> u64 {
    let (w, h) = match method.boundary {
        Boundary::Free => (width.saturating_mul(2), height.saturating_mul(2)),
        Boundary::Periodic => (width, height),
    };
    let real = (w as u64).saturating_mul(h as u64).saturating_mul(4);
    // Two slope planes (mirrored copies for dct), two spectra, and the result.
    real.saturating_mul(3).saturating_add(crate::fourier::working_bytes(w, h).saturating_mul(2))
}

/// The heights (`width·height`, row 0 first, mean zero, in texels) whose slopes are closest to
/// `slopes` in the least-squares sense `method` states.
pub fn integrate(slopes: &Slopes, method: IntegrationMethod) -> Result<Vec<f32>, IntegrationError> {
    let (spectra, w, h) = prepare(slopes, method.boundary)?;
    Ok(finish(slopes, method.boundary, solve(spectra, w, h, method.derivative)))
}

/// [`integrate`] with the derivative model that fits the slopes best ([`DerivativeFit`]), from
/// one pair of transforms. Returns the heights, the fit, and so the model used.
pub fn integrate_fitted(slopes: &Slopes, boundary: Boundary) -> Result<(Vec<f32>, DerivativeFit), IntegrationError> {
    let (spectra, w, h) = prepare(slopes, boundary)?;
    let fit = fit(&spectra, w, h);
    let heights = finish(slopes, boundary, solve(spectra, w, h, fit.best()));
    Ok((heights, fit))
}

/// The [`DerivativeFit`] of `slopes` alone, without integrating.
pub fn fit_derivative(slopes: &Slopes, boundary: Boundary) -> Result<DerivativeFit, IntegrationError> {
    let (spectra, w, h) = prepare(slopes, boundary)?;
    Ok(fit(&spectra, w, h))
}

/// The slopes' spectra (of the mirrored field for [`Boundary::Free`]) and the solved size.
fn prepare(
    slopes: &Slopes,
    boundary: Boundary,
) -> Result<((crate::fourier::Spectrum, crate::fourier::Spectrum), usize, usize), IntegrationError> {
    let (w, h) = (slopes.width, slopes.height);
    if w < 2 || h < 2 {
        return Err(IntegrationError::TooSmall { width: w, height: h });
    }
    let method = IntegrationMethod { boundary, derivative: Derivative::Spectral };
    crate::buffer::ensure_available(working_bytes(w, h, method), "integrating the slopes")?;
    Ok(match boundary {
        Boundary::Periodic => {
            ((crate::fourier::forward(w, h, &slopes.du), crate::fourier::forward(w, h, &slopes.dv)), w, h)
        }
        Boundary::Free => {
            let (du, dv) = mirrored(slopes);
            ((crate::fourier::forward(2 * w, 2 * h, &du), crate::fourier::forward(2 * w, 2 * h, &dv)), 2 * w, 2 * h)
        }
    })
}

/// The solved heights cut back to the map (the mirrored copies dropped), mean zero.
fn finish(slopes: &Slopes, boundary: Boundary, solved: Vec<f32>) -> Vec<f32> {
    let (w, h) = (slopes.width, slopes.height);
    let mut out = match boundary {
        Boundary::Periodic => solved,
        Boundary::Free => solved.chunks_exact(2 * w).take(h).flat_map(|row| row[..w].iter().copied()).collect(),
    };
    let mean = out.iter().map(|&v| v as f64).sum::<f64>() / out.len() as f64;
    out.iter_mut().for_each(|v| *v -= mean as f32);
    out
}

/// The least-squares heights of periodic slopes given their spectra: the filter, one inverse.
fn solve(
    spectra: (crate::fourier::Spectrum, crate::fourier::Spectrum),
    w: usize,
    h: usize,
    derivative: Derivative,
) -> Vec<f32> {
    let (mut p, q) = spectra;
    let transfer = Transfer::new(w, h, derivative);
    use rayon::prelude::*;
    p.data.par_chunks_mut(h).zip(q.data.par_chunks(h)).enumerate().for_each(|(kx, (pc, qc))| {
        for ky in 0..h {
            let (dx, dy) = transfer.at(kx, ky);
            let denom = dx.norm_sqr() + dy.norm_sqr() + transfer.regularization(kx, ky);
            // Zero only at (0, 0), whose height (the mean) no slope says: left at 0.
            pc[ky] =
                if denom > 1e-12 { (dx.conj() * pc[ky] + dy.conj() * qc[ky]) / denom } else { Complex32::default() };
        }
    });
    crate::fourier::inverse(p)
}

/// The slopes of the map mirrored into 2W×2H (half-sample symmetric, as DCT-II extends a
/// signal): `∂h/∂u` negated in the copies mirrored across a vertical edge, `∂h/∂v` in those
/// mirrored across a horizontal one.
fn mirrored(s: &Slopes) -> (Vec<f32>, Vec<f32>) {
    let (w, h) = (s.width, s.height);
    let (mut du, mut dv) = (vec![0.0; 4 * w * h], vec![0.0; 4 * w * h]);
    for y in 0..2 * h {
        let (sy, fy) = if y < h { (y, 1.0) } else { (2 * h - 1 - y, -1.0) };
        for x in 0..2 * w {
            let (sx, fx) = if x < w { (x, 1.0) } else { (2 * w - 1 - x, -1.0) };
            du[y * 2 * w + x] = fx * s.du[sy * w + sx];
            dv[y * 2 * w + x] = fy * s.dv[sy * w + sx];
        }
    }
    (du, dv)
}

#[cfg(test)]
mod tests;
