//! A real two-dimensional discrete Fourier transform, rows then columns, over `realfft` and
//! `rustfft` (no transform is written here): what [`crate::integration`] solves its Poisson
//! equations with.
//!
//! The spectrum of a `width`×`height` real image keeps the non-negative column frequencies only
//! (`width/2 + 1` of them; the others are their conjugates) and every row frequency, stored
//! column by column so each column's transform runs on contiguous memory. Frequencies follow
//! `X[k] = Σ x[n]·e^{−2πi·k·n/N}`; [`inverse`] divides by `width·height`, so `inverse(forward(x))`
//! is `x`.
//!
//! What this module does not do: filter, pad or window. Rows and columns run in parallel.

use rayon::prelude::*;
use realfft::RealFftPlanner;
use realfft::num_complex::Complex32;
use rustfft::FftPlanner;

/// The half spectrum of a real image: `columns()` columns of `height` frequencies each.
pub(crate) struct Spectrum {
    pub width: usize,
    pub height: usize,
    /// Column `kx` (frequency `kx` along a row) holds `data[kx·height .. (kx+1)·height]`, row
    /// frequency `ky` at offset `ky`.
    pub data: Vec<Complex32>,
}

impl Spectrum {
    /// How many column frequencies are kept: `width/2 + 1`.
    pub fn columns(&self) -> usize {
        self.width / 2 + 1
    }
}

/// Bytes [`forward`] and [`inverse`] hold at once for a `width`×`height` image, beyond the
/// caller's: the spectrum twice (row-major and column-major) plus a row of scratch per thread.
pub(crate) fn working_bytes(width: usize, height: usize) -> u64 {
    let complex = (width as u64 / 2 + 1).saturating_mul(height as u64).saturating_mul(8);
    complex.saturating_mul(2)
}

/// The spectrum of `samples` (`width·height`, row 0 first).
pub(crate) fn forward(width: usize, height: usize, samples: &[f32]) -> Spectrum {
    debug_assert_eq!(samples.len(), width * height);
    let cw = width / 2 + 1;
    let r2c = RealFftPlanner::<f32>::new().plan_fft_forward(width);
    // Rows: real → half complex, row-major.
    let mut rows = vec![Complex32::default(); cw * height];
    rows.par_chunks_mut(cw).zip(samples.par_chunks(width)).for_each_init(
        || (r2c.make_input_vec(), r2c.make_scratch_vec()),
        |(input, scratch), (out, row)| {
            input.copy_from_slice(row);
            r2c.process_with_scratch(input, out, scratch).expect("buffers sized by the plan");
        },
    );
    let mut data = transpose(&rows, height, cw);
    drop(rows);
    let column_fft = FftPlanner::<f32>::new().plan_fft_forward(height);
    data.par_chunks_mut(height).for_each_init(
        || vec![Complex32::default(); column_fft.get_inplace_scratch_len()],
        |scratch, column| column_fft.process_with_scratch(column, scratch),
    );
    Spectrum { width, height, data }
}

/// The real image whose spectrum is `spectrum` (its conjugate-symmetric half), divided by
/// `width·height`. The imaginary parts that a real image's zero and Nyquist columns cannot have
/// are dropped.
pub(crate) fn inverse(mut spectrum: Spectrum) -> Vec<f32> {
    let (width, height, cw) = (spectrum.width, spectrum.height, spectrum.columns());
    let column_ifft = FftPlanner::<f32>::new().plan_fft_inverse(height);
    spectrum.data.par_chunks_mut(height).for_each_init(
        || vec![Complex32::default(); column_ifft.get_inplace_scratch_len()],
        |scratch, column| column_ifft.process_with_scratch(column, scratch),
    );
    let rows = transpose(&spectrum.data, cw, height);
    drop(spectrum.data);
    let c2r = RealFftPlanner::<f32>::new().plan_fft_inverse(width);
    let norm = 1.0 / (width as f32 * height as f32);
    let mut out = vec![0.0f32; width * height];
    out.par_chunks_mut(width).zip(rows.par_chunks(cw)).for_each_init(
        || (c2r.make_input_vec(), c2r.make_scratch_vec()),
        |(input, scratch), (row, half)| {
            input.copy_from_slice(half);
            input[0].im = 0.0;
            if width % 2 == 0 {
                input[cw - 1].im = 0.0;
            }
            c2r.process_with_scratch(input, row, scratch).expect("buffers sized by the plan, real ends");
            for v in row.iter_mut() {
                *v *= norm;
            }
        },
    );
    out
}

/// `src` is `rows`×`cols` row-major; the result is `cols`×`rows` row-major. In 32×32 blocks,
/// bands of output rows in parallel.
fn transpose(src: &[Complex32], rows: usize, cols: usize) -> Vec<Complex32> {
    const B: usize = 32;
    let mut dst = vec![Complex32::default(); rows * cols];
    dst.par_chunks_mut(rows * B).enumerate().for_each(|(band, out)| {
        let c0 = band * B;
        let c1 = (c0 + B).min(cols);
        for r0 in (0..rows).step_by(B) {
            for r in r0..(r0 + B).min(rows) {
                for c in c0..c1 {
                    out[(c - c0) * rows + r] = src[r * cols + c];
                }
            }
        }
    });
    dst
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_undoes_forward_on_odd_and_even_sizes() {
        for (w, h) in [(8, 8), (7, 5), (16, 3), (1, 4), (5, 1)] {
            let x: Vec<f32> = (0..w * h).map(|i| ((i * 7919) % 23) as f32 / 23.0 - 0.4).collect();
            let back = inverse(forward(w, h, &x));
            for (a, b) in x.iter().zip(&back) {
                assert!((a - b).abs() < 1e-5, "{w}x{h}: {a} came back as {b} (f32 round-off only)");
            }
        }
    }

    #[test]
    fn a_plane_wave_lands_on_its_frequency() {
        // cos(2π(2x/8 + 3y/6)): energy at column frequency 2, row frequency 3, nowhere else.
        let (w, h) = (8, 6);
        let x: Vec<f32> = (0..w * h)
            .map(|i| {
                let (c, r) = ((i % w) as f32, (i / w) as f32);
                (std::f32::consts::TAU * (2.0 * c / w as f32 + 3.0 * r / h as f32)).cos()
            })
            .collect();
        let s = forward(w, h, &x);
        for kx in 0..s.columns() {
            for ky in 0..h {
                let m = s.data[kx * h + ky].norm();
                let expect = if kx == 2 && ky == 3 { (w * h) as f32 / 2.0 } else { 0.0 };
                assert!((m - expect).abs() < 1e-3, "|X[{kx},{ky}]| = {m}, want {expect}");
            }
        }
    }
}
