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

use glam::Vec4;
use realfft::num_complex::Complex32;

use crate::buffer::OutOfMemory;
use crate::image::Image;
use crate::kernel::Kernel;
use crate::normalmap::YConvention;

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

impl Derivative {
    /// `spectral`, or the kernel's name.
    pub fn name(self) -> &'static str {
        match self {
            Derivative::Spectral => "spectral",
            Derivative::Kernel(k) => k.name(),
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
    /// A scale of zero, or not finite.
    #[error("the slope scale must be a finite number other than 0, got {0}")]
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
        let apply = |taps: &[crate::kernel::Tap]| -> Vec<f32> {
            (0..width * height)
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

/// Refuses what [`Slopes::from_normals`] would: a scale of 0 or not finite, fewer than 2×2
/// texels, a texel that is not a number.
pub fn check_normals(normals: &Image<Vec4>, scale: f32) -> Result<(), IntegrationError> {
    use rayon::prelude::*;
    if !scale.is_finite() || scale == 0.0 {
        return Err(IntegrationError::BadScale(scale));
    }
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

/// How well each derivative model explains a map's slopes: the least-squares residual it
/// leaves, `Σ_ω |D̂_v·P̂ − D̂_u·Q̂|² / (|D̂_u|² + |D̂_v|²)` — the part of the slopes no height
/// field could have made under that model, which for the model that made the map is the
/// encoding's noise alone (and the same noise for every model, so the residuals compare).
///
/// Slopes cannot tell a kernel `K` from `K` times a symmetric smoothing `F`: `K·F` applied to
/// `h` is `K` applied to `F·h`, so both explain the map exactly (Sobel 5×5 is Sobel 3×3 with
/// one more [1 2 1] smoothing each way). Of the models that explain the slopes equally well
/// the sharpest kernel is taken: its heights are the smoother explanation, and made into a map by that
/// kernel they give the map back. Deconvolving a smoothing the map never had would amplify
/// its noise instead.
#[derive(Clone, Debug, PartialEq)]
pub struct DerivativeFit {
    /// Each candidate ([`Derivative::Spectral`] and every kernel) with its residual energy per
    /// texel and its sharpness (the mean of `|D̂_u|² + |D̂_v|²`), smallest residual first.
    pub residuals: Vec<(Derivative, f32, f32)>,
    /// The slopes' own energy per texel, on the same frequencies (the scale for
    /// [`FIT_TIE_FLOOR`]).
    pub energy: f32,
}

/// Residuals within this factor of the smallest (and [`FIT_TIE_FLOOR`]) explain the slopes
/// equally well: noise moves a residual by a few percent.
pub const FIT_TIE: f32 = 1.25;

/// Residuals below this fraction of the slopes' own energy are all noise-free fits.
pub const FIT_TIE_FLOOR: f32 = 1e-7;

impl DerivativeFit {
    /// The sharpest kernel among those that explain the slopes as well as the best; `iω` only
    /// where no kernel does (a map `bumpmap normalmap --kernel K` can make again is the more
    /// useful explanation).
    pub fn best(&self) -> Derivative {
        let Some(&(_, least, _)) = self.residuals.first() else { return Derivative::Spectral };
        self.residuals
            .iter()
            .filter(|r| r.1 <= FIT_TIE * least + FIT_TIE_FLOOR * self.energy && r.0 != Derivative::Spectral)
            .max_by(|a, b| a.2.total_cmp(&b.2))
            .map_or(Derivative::Spectral, |r| r.0)
    }
}

/// At most this many frequencies are visited to fit a derivative (a stride over both axes
/// keeps a 4096² map's fit to a 64th of its spectrum).
const FIT_FREQUENCIES: usize = 1 << 18;

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

/// Every candidate's residual over a strided subset of the spectrum.
fn fit(spectra: &(crate::fourier::Spectrum, crate::fourier::Spectrum), w: usize, h: usize) -> DerivativeFit {
    let (p, q) = spectra;
    let cw = p.columns();
    let stride = ((cw * h) as f64 / FIT_FREQUENCIES as f64).sqrt().ceil().max(1.0) as usize;
    let candidates: Vec<Derivative> =
        std::iter::once(Derivative::Spectral).chain(Kernel::ALL.into_iter().map(Derivative::Kernel)).collect();
    use rayon::prelude::*;
    // Per texel of the solved size, per frequency visited.
    let norm = cw.div_ceil(stride) as f64 * h.div_ceil(stride) as f64 * (w * h) as f64;
    let mut energy = 0.0f64;
    for kx in (0..cw).step_by(stride) {
        for ky in (0..h).step_by(stride) {
            let i = kx * h + ky;
            energy += (p.data[i].norm_sqr() + q.data[i].norm_sqr()) as f64;
        }
    }
    let mut residuals: Vec<(Derivative, f32, f32)> = candidates
        .par_iter()
        .map(|&d| {
            let transfer = Transfer::new(w, h, d);
            let (mut sum, mut sharpness) = (0.0f64, 0.0f64);
            for kx in (0..cw).step_by(stride) {
                for ky in (0..h).step_by(stride) {
                    let (du, dv) = transfer.at(kx, ky);
                    let denom = du.norm_sqr() as f64 + dv.norm_sqr() as f64;
                    sharpness += denom;
                    if denom > 1e-12 {
                        let i = kx * h + ky;
                        let wide = |c: Complex32| realfft::num_complex::Complex64::new(c.re as f64, c.im as f64);
                        sum += (wide(dv) * wide(p.data[i]) - wide(du) * wide(q.data[i])).norm_sqr() / denom;
                    }
                }
            }
            (d, (sum / norm) as f32, (sharpness * (w * h) as f64 / norm) as f32)
        })
        .collect();
    residuals.sort_by(|a, b| a.1.total_cmp(&b.1));
    DerivativeFit { residuals, energy: (energy / norm) as f32 }
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

/// `D̂_u`, `D̂_v` at each kept frequency. For a kernel, `Σ w·e^{i(ω_u·dx + ω_v·dy)}` (a tap
/// reading the texel `dx` further along multiplies its spectrum by `e^{iω·dx}`), summed per
/// row offset once and per column offset at each frequency.
struct Transfer {
    h: usize,
    /// `ω_u` of each kept column frequency (0 ≤ ω_u ≤ π).
    omega_u: Vec<f32>,
    /// `ω_v` of each row frequency, in (−π, π].
    omega_v: Vec<f32>,
    derivative: Derivative,
    /// For a kernel: per tap row `dy`, `Σ_dx w·e^{iω_u·dx}` at each column frequency, for
    /// `D̂_u` and for `D̂_v`.
    rows_u: Vec<(i32, Vec<Complex32>)>,
    rows_v: Vec<(i32, Vec<Complex32>)>,
    /// For a kernel: `e^{iω_v·dy}` at each row frequency, for each `dy` its rows use (indexed
    /// by `dy + PHASE_RADIUS`).
    phases: Vec<Vec<Complex32>>,
    w_even: bool,
}

/// The largest `|dy|` a kernel's taps reach ([`Kernel::radius`] at most).
const PHASE_RADIUS: i32 = 3;

impl Transfer {
    fn new(w: usize, h: usize, derivative: Derivative) -> Self {
        let omega = |k: usize, n: usize| {
            let k = if k > n / 2 { k as f32 - n as f32 } else { k as f32 };
            std::f32::consts::TAU * k / n as f32
        };
        let omega_u: Vec<f32> = (0..w / 2 + 1).map(|k| omega(k, w)).collect();
        let omega_v: Vec<f32> = (0..h).map(|k| omega(k, h)).collect();
        let rows = |taps: Vec<crate::kernel::Tap>| -> Vec<(i32, Vec<Complex32>)> {
            let mut dys: Vec<i32> = taps.iter().map(|t| t.dy).collect();
            dys.sort_unstable();
            dys.dedup();
            dys.into_iter()
                .map(|dy| {
                    let sums = omega_u
                        .iter()
                        .map(|&wu| {
                            taps.iter()
                                .filter(|t| t.dy == dy)
                                .map(|t| Complex32::from_polar(t.weight, wu * t.dx as f32))
                                .sum()
                        })
                        .collect();
                    (dy, sums)
                })
                .collect()
        };
        let (rows_u, rows_v, phases) = match derivative {
            Derivative::Kernel(k) => {
                debug_assert!(k.radius() <= PHASE_RADIUS);
                let phases = (-PHASE_RADIUS..=PHASE_RADIUS)
                    .map(|dy| omega_v.iter().map(|&wv| Complex32::from_polar(1.0, wv * dy as f32)).collect())
                    .collect();
                (rows(k.taps_du()), rows(k.taps_dv()), phases)
            }
            Derivative::Spectral => (Vec::new(), Vec::new(), Vec::new()),
        };
        Self { h, omega_u, omega_v, derivative, rows_u, rows_v, phases, w_even: w.is_multiple_of(2) }
    }

    /// `ε·|ω|²` for a kernel ([`TIKHONOV`]), 0 for `iω`.
    #[inline]
    fn regularization(&self, kx: usize, ky: usize) -> f32 {
        match self.derivative {
            Derivative::Spectral => 0.0,
            Derivative::Kernel(_) => TIKHONOV * (self.omega_u[kx].powi(2) + self.omega_v[ky].powi(2)),
        }
    }

    #[inline]
    fn at(&self, kx: usize, ky: usize) -> (Complex32, Complex32) {
        match self.derivative {
            Derivative::Spectral => {
                // The Nyquist frequency's derivative has no sign a real image can carry: 0.
                let nyquist_u = self.w_even && kx == self.omega_u.len() - 1;
                let nyquist_v = self.h.is_multiple_of(2) && ky == self.h / 2;
                let du = if nyquist_u { 0.0 } else { self.omega_u[kx] };
                let dv = if nyquist_v { 0.0 } else { self.omega_v[ky] };
                (Complex32::new(0.0, du), Complex32::new(0.0, dv))
            }
            Derivative::Kernel(_) => {
                let sum = |rows: &[(i32, Vec<Complex32>)]| -> Complex32 {
                    rows.iter().map(|(dy, s)| s[kx] * self.phases[(dy + PHASE_RADIUS) as usize][ky]).sum()
                };
                (sum(&self.rows_u), sum(&self.rows_v))
            }
        }
    }
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
mod tests {
    use super::*;

    fn rms(a: &[f32], b: &[f32]) -> f32 {
        let ma = a.iter().sum::<f32>() / a.len() as f32;
        let mb = b.iter().sum::<f32>() / b.len() as f32;
        (a.iter().zip(b).map(|(x, y)| ((x - ma) - (y - mb)).powi(2)).sum::<f32>() / a.len() as f32).sqrt()
    }

    fn bumps(w: usize, h: usize) -> Vec<f32> {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f32 / w as f32, (i / w) as f32 / h as f32);
                let t = std::f32::consts::TAU;
                3.0 * (t * x).sin() * (2.0 * t * y).cos() + 1.5 * (t * (3.0 * x + y)).cos() + (t * 5.0 * y).sin()
            })
            .collect()
    }

    #[test]
    fn the_kernel_method_inverts_the_forward_difference_exactly() {
        // Periodic, non-square, with a component at every frequency (the forward difference
        // sees them all): exact up to f32 round-off through two transforms.
        let (w, h) = (40, 24);
        let heights: Vec<f32> = (0..w * h).map(|i| ((i * 7919 + 13) % 101) as f32 / 10.0).collect();
        let kernel = Kernel::Forward;
        let got = integrate(&Slopes::of_heights(w, h, &heights, kernel), IntegrationMethod::kernel(kernel)).unwrap();
        let e = rms(&heights, &got);
        assert!(e < 2e-3, "rms {e} of heights spanning 10");
    }

    #[test]
    fn smoothing_kernels_are_inverted_away_from_the_frequencies_they_cannot_see() {
        // Smooth heights (no content at Nyquist): every kernel's inverse gives them back.
        let (w, h) = (48, 32);
        let heights = bumps(w, h);
        for kernel in Kernel::ALL {
            let got =
                integrate(&Slopes::of_heights(w, h, &heights, kernel), IntegrationMethod::kernel(kernel)).unwrap();
            let e = rms(&heights, &got);
            assert!(e < 1e-3, "{kernel:?}: rms {e} of heights spanning about 11");
        }
    }

    #[test]
    fn frankot_chellappa_recovers_band_limited_heights_from_their_exact_slopes() {
        let (w, h) = (64, 48);
        let t = std::f32::consts::TAU;
        let heights = bumps(w, h);
        // The analytic slopes of `bumps`, per texel.
        let (mut du, mut dv) = (Vec::new(), Vec::new());
        for i in 0..w * h {
            let (x, y) = ((i % w) as f32 / w as f32, (i / w) as f32 / h as f32);
            let (sx, sy) = (t / w as f32, t / h as f32);
            du.push(sx * (3.0 * (t * x).cos() * (2.0 * t * y).cos() - 4.5 * (t * (3.0 * x + y)).sin()));
            dv.push(
                sy * (-6.0 * (t * x).sin() * (2.0 * t * y).sin() - 1.5 * (t * (3.0 * x + y)).sin()
                    + 5.0 * (t * 5.0 * y).cos()),
            );
        }
        let got = integrate(&Slopes { width: w, height: h, du, dv }, IntegrationMethod::FRANKOT_CHELLAPPA).unwrap();
        assert!(rms(&heights, &got) < 1e-3, "rms {}", rms(&heights, &got));
    }

    #[test]
    fn the_dct_method_recovers_a_surface_that_does_not_tile() {
        // A tilted paraboloid: not periodic, so fft smears its edges; dct does not.
        let (w, h) = (48, 40);
        let f = |x: f32, y: f32| 0.02 * (x - 10.0).powi(2) + 0.3 * y - 0.01 * x * y;
        let heights: Vec<f32> = (0..w * h).map(|i| f((i % w) as f32, (i / w) as f32)).collect();
        let du: Vec<f32> = (0..w * h).map(|i| 0.04 * ((i % w) as f32 - 10.0) - 0.01 * (i / w) as f32).collect();
        let dv: Vec<f32> = (0..w * h).map(|i| 0.3 - 0.01 * (i % w) as f32).collect();
        let s = Slopes { width: w, height: h, du, dv };
        let range = heights.iter().cloned().fold(f32::MIN, f32::max) - heights.iter().cloned().fold(f32::MAX, f32::min);
        let dct = rms(
            &heights,
            &integrate(&s, IntegrationMethod { boundary: Boundary::Free, derivative: Derivative::Spectral }).unwrap(),
        ) / range;
        let fft = rms(&heights, &integrate(&s, IntegrationMethod::FRANKOT_CHELLAPPA).unwrap()) / range;
        assert!(dct < 0.01, "dct: rms {dct} of the range");
        assert!(fft > 5.0 * dct, "fft ({fft}) should be far worse than dct ({dct}) on a surface that does not tile");
    }

    #[test]
    fn slopes_follow_the_y_convention_and_the_scale() {
        let n = Vec4::new(-0.2, 0.1, 0.9, 1.0);
        let img = Image::new(2, 2, vec![n; 4]);
        let down = Slopes::from_normals(&img, YConvention::YDown, 2.0).unwrap();
        let up = Slopes::from_normals(&img, YConvention::YUp, 2.0).unwrap();
        assert!((down.du[0] - 0.2 / 1.8).abs() < 1e-6 && (down.dv[0] + 0.1 / 1.8).abs() < 1e-6);
        assert_eq!(up.dv[0], -down.dv[0]);
        assert!(matches!(Slopes::from_normals(&img, YConvention::YUp, 0.0), Err(IntegrationError::BadScale(_))));
        let one = Image::new(1, 3, vec![n; 3]);
        assert!(matches!(Slopes::from_normals(&one, YConvention::YUp, 1.0), Err(IntegrationError::TooSmall { .. })));
        let nan = Image::new(2, 2, vec![n, n, Vec4::new(f32::NAN, 0.0, 1.0, 1.0), n]);
        assert_eq!(
            Slopes::from_normals(&nan, YConvention::YUp, 1.0).unwrap_err(),
            IntegrationError::NotANumber { x: 0, y: 1 }
        );
    }
}
