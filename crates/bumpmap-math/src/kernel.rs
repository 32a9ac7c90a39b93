//! Finite-difference kernels for ∂F/∂u and ∂F/∂v, and how they treat the field's edges.
//!
//! Every kernel is normalized so that on the ramp F = a·u it returns exactly `a` per texel:
//! `--scale` then means the same thing for every kernel. A kernel is a list of taps for ∂F/∂u;
//! ∂F/∂v uses the same taps transposed. Derivatives point toward increasing texel index (the
//! next column, the next row: Kilgard Appendix E's "right" and "up").
//!
//! [`gaussian7_smoothed`] gives the heights as the 7×7 derivative of a Gaussian sees them, for a
//! ground truth that differentiates exactly (the reference renderer) but should share that
//! kernel's smoothing.

use crate::HeightField;

/// Which finite difference approximates the partial derivatives of the height field.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Kernel {
    /// `F(u+1) − F(u)`: the paper's right/up differences (Kilgard Appendix E). Its result sits
    /// half a texel to the right and up of the texel centre (Kilgard §5.4).
    #[default]
    Forward,
    /// `(F(u+1) − F(u−1)) / 2`.
    Central,
    /// 3×3 Sobel.
    Sobel3,
    /// 5×5 Sobel: derivative [−1 −2 0 2 1] times smoothing [1 4 6 4 1].
    Sobel5,
    /// 3×3 Prewitt.
    Prewitt3,
    /// 3×3 Scharr: derivative [−1 0 1] times smoothing [3 10 3].
    Scharr3,
    /// Peercy's 7×7 derivative of a Gaussian (σ = 1 texel).
    Gaussian7,
}

crate::named!(Kernel {
    Forward => "forward": "F(u+1) − F(u): the paper's right/up differences (Kilgard Appendix E)",
    Central => "central": "(F(u+1) − F(u−1)) / 2",
    Sobel3 => "sobel3": "3×3 Sobel",
    Sobel5 => "sobel5": "5×5 Sobel",
    Prewitt3 => "prewitt3": "3×3 Prewitt (what DirectXTex uses)",
    Scharr3 => "scharr3": "3×3 Scharr",
    Gaussian7 => "gaussian7": "7×7 derivative of a Gaussian, σ = 1 (Peercy et al.)",
});

/// One tap of a derivative kernel: the height at texel offset (dx, dy) times `weight`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tap {
    /// Column offset.
    pub dx: i32,
    /// Row offset.
    pub dy: i32,
    /// Weight of the height there.
    pub weight: f32,
}

impl Kernel {
    /// Every kernel.
    pub const ALL: [Kernel; 7] = [
        Kernel::Forward,
        Kernel::Central,
        Kernel::Sobel3,
        Kernel::Sobel5,
        Kernel::Prewitt3,
        Kernel::Scharr3,
        Kernel::Gaussian7,
    ];

    /// The kernel called `name` (any case).
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| crate::Named::name(*k).eq_ignore_ascii_case(name))
    }

    /// How far the kernel reaches from the centre texel, in texels.
    pub fn radius(self) -> i32 {
        match self {
            Kernel::Forward | Kernel::Central | Kernel::Sobel3 | Kernel::Prewitt3 | Kernel::Scharr3 => 1,
            Kernel::Sobel5 => 2,
            Kernel::Gaussian7 => 3,
        }
    }

    /// The taps of ∂F/∂u, zero weights left out. ∂F/∂v is the transpose.
    pub fn taps_du(self) -> Vec<Tap> {
        match self {
            // Exactly two taps in this order, so `1·F(u+1) + (−1)·F(u)` rounds like the paper's
            // `c − cx` (negation is exact): the byte-exact Appendix E test depends on it.
            Kernel::Forward => vec![Tap { dx: 1, dy: 0, weight: 1.0 }, Tap { dx: 0, dy: 0, weight: -1.0 }],
            Kernel::Central => separable(&[-1.0, 0.0, 1.0], &[1.0]),
            Kernel::Sobel3 => separable(&[-1.0, 0.0, 1.0], &[1.0, 2.0, 1.0]),
            Kernel::Sobel5 => separable(&[-1.0, -2.0, 0.0, 2.0, 1.0], &[1.0, 4.0, 6.0, 4.0, 1.0]),
            Kernel::Prewitt3 => separable(&[-1.0, 0.0, 1.0], &[1.0, 1.0, 1.0]),
            Kernel::Scharr3 => separable(&[-1.0, 0.0, 1.0], &[3.0, 10.0, 3.0]),
            Kernel::Gaussian7 => {
                let g = gaussian7();
                // x·g(x) ∝ −g′(x): the derivative of the same Gaussian that smooths across.
                let d: Vec<f32> = (-3..=3).zip(&g).map(|(i, g)| i as f32 * g).collect();
                separable(&d, &g)
            }
        }
    }

    /// The taps of ∂F/∂v: those of ∂F/∂u with dx and dy swapped.
    pub fn taps_dv(self) -> Vec<Tap> {
        self.taps_du().into_iter().map(|t| Tap { dx: t.dy, dy: t.dx, weight: t.weight }).collect()
    }
}

/// The seven samples of the Gaussian `exp(−x²/2)` (σ = 1 texel) at x = −3…3, unnormalized:
/// the smoothing of [`Kernel::Gaussian7`] and of [`gaussian7_smoothed`].
fn gaussian7() -> [f32; 7] {
    std::array::from_fn(|i| (-((i as f32 - 3.0).powi(2)) / 2.0).exp())
}

/// The heights as Peercy's 7×7 derivative of a Gaussian sees them: `field` convolved with the
/// same Gaussian (σ = 1 texel, seven taps a side, normalized) along both axes, edges as `wrap`
/// says. Differentiating the result (for instance by a C¹ interpolant, as the reference
/// renderer does) measures nearly what [`Kernel::Gaussian7`] measures on `field`: the two sample
/// the Gaussian's derivative differently, which on the pinwheel leaves 9.3 % of the slopes' RMS
/// (measured in this module's tests). A ground truth for techniques that share that kernel, free of most of the
/// kernel's own smoothing. With `Wrap::Border` the edges clamp.
pub fn gaussian7_smoothed(field: &HeightField, wrap: Wrap) -> HeightField {
    let g = gaussian7();
    let sum: f32 = g.iter().sum();
    let (w, h) = (field.width(), field.height());
    let heights = field.to_f32();
    let pass = |src: &[f32], along_x: bool| -> Vec<f32> {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as i64, (i / w) as i64);
                (-3..=3i64)
                    .map(|k| {
                        let at = if along_x {
                            y as usize * w + wrap.index(x + k, w)
                        } else {
                            wrap.index(y + k, h) * w + x as usize
                        };
                        g[(k + 3) as usize] * src[at]
                    })
                    .sum::<f32>()
                    / sum
            })
            .collect()
    };
    let smoothed = pass(&pass(&heights, true), false);
    HeightField::new(w, h, smoothed).expect("same size as the field")
}

/// Outer product of a centred derivative row and a centred smoothing column, normalized so a
/// unit ramp along u gives 1.
fn separable(derivative: &[f32], smoothing: &[f32]) -> Vec<Tap> {
    let (rd, rs) = ((derivative.len() / 2) as i32, (smoothing.len() / 2) as i32);
    let ramp: f32 = derivative.iter().enumerate().map(|(i, w)| (i as i32 - rd) as f32 * w).sum::<f32>()
        * smoothing.iter().sum::<f32>();
    let mut taps = Vec::new();
    for (j, s) in smoothing.iter().enumerate() {
        for (i, d) in derivative.iter().enumerate() {
            let weight = d * s / ramp;
            if weight != 0.0 {
                taps.push(Tap { dx: i as i32 - rd, dy: j as i32 - rs, weight });
            }
        }
    }
    taps
}

/// What a kernel reads beyond the edge of the height field.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Wrap {
    /// The field tiles (`GL_REPEAT`): indices wrap around. The paper's default.
    #[default]
    Repeat,
    /// Indices clamp to the nearest edge texel.
    Clamp,
    /// Kilgard Appendix E's border case: the input is one texel wider and taller than the
    /// output, and the extra last column and row are read instead of wrapping. Taps that still
    /// fall outside the input clamp.
    Border,
}

crate::named!(Wrap {
    Repeat => "repeat": "The field tiles: edges read the opposite edge",
    Clamp => "clamp": "Edges repeat the last texel",
    Border => "border": "Kilgard's border case: the input is one texel wider and taller than the output",
});

impl Wrap {
    /// Maps a possibly out-of-range index into `0..n`. `n` must be positive.
    #[inline(always)]
    pub fn index(self, i: i64, n: usize) -> usize {
        debug_assert!(n > 0);
        match self {
            Wrap::Repeat => i.rem_euclid(n as i64) as usize,
            Wrap::Clamp | Wrap::Border => i.clamp(0, n as i64 - 1) as usize,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Named;

    #[test]
    fn every_kernel_returns_the_slope_of_a_ramp() {
        for k in Kernel::ALL {
            let du: f32 = k.taps_du().iter().map(|t| t.dx as f32 * 0.25 * t.weight).sum();
            let dv_on_u_ramp: f32 = k.taps_dv().iter().map(|t| t.dx as f32 * t.weight).sum();
            // Normalization is a single division; f32 rounding of ≤ 49 taps stays below 1e-6.
            assert!((du - 0.25).abs() < 1e-6, "{}: ramp 0.25/texel gave {du}", k.name());
            assert!(dv_on_u_ramp.abs() < 1e-6, "{}: ∂F/∂v of a u-ramp gave {dv_on_u_ramp}", k.name());
            assert!(k.taps_du().iter().all(|t| t.dx.abs() <= k.radius() && t.dy.abs() <= k.radius()));
            assert_eq!(Kernel::parse(k.name()), Some(k));
        }
    }

    #[test]
    fn differentiating_the_smoothed_field_measures_nearly_what_gaussian7_measures() {
        // The pinwheel that Peercy's study uses: blade edges a texel or so wide, the hardest case
        // for the kernel. Gaussian7 on the field against central differences (what a Catmull-Rom
        // interpolant's derivative is at texel centres) on the smoothed field, along x.
        let field = crate::HeightPreset::Pinwheel.render(256, 256);
        let (w, h) = (field.width(), field.height());
        let smoothed = gaussian7_smoothed(&field, Wrap::Repeat);
        let at = |f: &HeightField, x: usize, dx: i32, y: usize, dy: i32| {
            f.get(Wrap::Repeat.index(x as i64 + dx as i64, w), Wrap::Repeat.index(y as i64 + dy as i64, h))
        };
        let taps = Kernel::Gaussian7.taps_du();
        let (mut worst, mut peak) = (0.0f32, 0.0f32);
        let (mut diff_sq, mut unsmoothed_sq, mut slope_sq) = (0.0f64, 0.0f64, 0.0f64);
        for y in 0..h {
            for x in 0..w {
                let kernel: f32 = taps.iter().map(|t| t.weight * at(&field, x, t.dx, y, t.dy)).sum();
                let central = (at(&smoothed, x, 1, y, 0) - at(&smoothed, x, -1, y, 0)) / 2.0;
                let unsmoothed = (at(&field, x, 1, y, 0) - at(&field, x, -1, y, 0)) / 2.0;
                worst = worst.max((kernel - central).abs());
                peak = peak.max(kernel.abs());
                diff_sq += ((kernel - central) as f64).powi(2);
                unsmoothed_sq += ((kernel - unsmoothed) as f64).powi(2);
                slope_sq += (kernel as f64).powi(2);
            }
        }
        let (rms, unsmoothed_rms) = ((diff_sq / slope_sq).sqrt(), (unsmoothed_sq / slope_sq).sqrt());
        // The two operators differ only in how they sample the Gaussian's derivative (x·g(x)
        // against (g(x−1) − g(x+1))/2). Measured (deterministic): 9.3 % of the slopes' RMS,
        // 14.6 % of the steepest slope at worst (near the centre, where the blades are
        // narrowest); without smoothing, central differences miss by 49 % RMS.
        assert!(rms < 0.1, "RMS difference {rms} of the slopes' RMS");
        assert!(worst < 0.16 * peak, "worst difference {worst} against a peak slope of {peak}");
        assert!(unsmoothed_rms > 4.0 * rms, "unsmoothed {unsmoothed_rms} against smoothed {rms}");
        // Smoothing keeps a constant field and the mean of a tiling one.
        let flat = gaussian7_smoothed(&HeightField::from_fn(9, 5, |_, _| 0.25), Wrap::Repeat);
        assert!(flat.to_f32().iter().all(|&v| (v - 0.25).abs() < 1e-6));
        let mean = |f: &HeightField| f.to_f32().iter().map(|&v| v as f64).sum::<f64>() / (w * h) as f64;
        assert!((mean(&smoothed) - mean(&field)).abs() < 1e-5);
    }

    #[test]
    fn wrap_modes_index_as_documented() {
        assert_eq!(Wrap::Repeat.index(-1, 5), 4);
        assert_eq!(Wrap::Repeat.index(5, 5), 0);
        assert_eq!(Wrap::Clamp.index(-3, 5), 0);
        assert_eq!(Wrap::Clamp.index(9, 5), 4);
    }
}
