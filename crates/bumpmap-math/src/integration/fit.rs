//! Which derivative model made a map's slopes: every candidate's least-squares residual.

use realfft::num_complex::Complex32;

use super::{Derivative, Transfer};
use crate::fourier::Spectrum;
use crate::kernel::Kernel;

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

/// Every candidate's residual over a strided subset of the spectrum.
pub(super) fn fit(spectra: &(Spectrum, Spectrum), w: usize, h: usize) -> DerivativeFit {
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
