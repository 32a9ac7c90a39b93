//! The transfer functions `D̂_u`, `D̂_v` of the derivative models, frequency by frequency.

use realfft::num_complex::Complex32;

use super::{Derivative, TIKHONOV};

/// `D̂_u`, `D̂_v` at each kept frequency. For a kernel, `Σ w·e^{i(ω_u·dx + ω_v·dy)}` (a tap
/// reading the texel `dx` further along multiplies its spectrum by `e^{iω·dx}`), summed per
/// row offset once and per column offset at each frequency.
pub(super) struct Transfer {
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
    pub(super) fn new(w: usize, h: usize, derivative: Derivative) -> Self {
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
    pub(super) fn regularization(&self, kx: usize, ky: usize) -> f32 {
        match self.derivative {
            Derivative::Spectral => 0.0,
            Derivative::Kernel(_) => TIKHONOV * (self.omega_u[kx].powi(2) + self.omega_v[ky].powi(2)),
        }
    }

    #[inline]
    pub(super) fn at(&self, kx: usize, ky: usize) -> (Complex32, Complex32) {
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
