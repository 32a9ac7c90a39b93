//! Height field → tangent-space normal map, level 0 (Kilgard Eq. 25, 27, 28; Peercy Eq. 8–11).
//!
//! The perturbed normal of a height field on a square patch is `n ∝ (−s·∂F/∂u, −s·∂F/∂v, 1)`
//! (Kilgard Eq. 25 renormalized as Eq. 27, Peercy's surface-independent Eq. 10), range-compressed
//! into RGB (Eq. 28) with A = 255 at level 0. The mip chain lives in `mip.rs`; this module only
//! evaluates derivatives and normals, a row at a time, with no per-texel allocation.

use glam::Vec3;

use crate::encoding::{Encoding, Texel};
use crate::height::HeightField;
use crate::image::{Image, Rgba8Image};
use crate::kernel::{Kernel, Tap, Wrap};

/// Which way the green channel points, stated against the image as displayed (first row at
/// the top), as the file formats and the tools that read them state it.
///
/// This crate's texture space has t = 0 at the first row and t growing down the image, so the
/// normal's Y component, along +t, points *down* the displayed image: [`YConvention::YDown`] is
/// what the renderers sample ([`YConvention::TEXTURE_SPACE`]). Files for glTF, Blender and
/// Unity want [`YConvention::YUp`], whose green is the texture-space Y negated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum YConvention {
    /// Green is +Y toward the top of the image as displayed: glTF 2.0 (`normalTexture`: "+Y is
    /// up"), OpenGL, Blender, Maya, Unity.
    YUp,
    /// Green is +Y toward the bottom of the image as displayed: DirectX, Unreal, 3ds Max — and
    /// this crate's texture space.
    YDown,
}

impl YConvention {
    /// The convention of this crate's texture space (what its renderers sample).
    pub const TEXTURE_SPACE: Self = Self::YDown;
}

crate::named!(YConvention {
    YUp => "opengl" | "y-up": "Green up: +Y toward the top of the image as displayed (glTF, OpenGL, Blender, Maya, Unity)",
    YDown => "directx" | "y-down": "Green down: +Y toward the bottom of the image as displayed (DirectX, Unreal, 3ds Max)",
});

/// Everything that decides how a height field becomes a normal map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalMapOptions {
    /// The finite-difference kernel for ∂F/∂u and ∂F/∂v.
    pub kernel: Kernel,
    /// Multiplies the derivatives: heights are in [0, 1] and derivatives are per texel, so
    /// `scale` is the height of a unit step measured in texels.
    pub scale: f32,
    /// What the kernel reads beyond the edges.
    pub wrap: Wrap,
    /// Which way green points; the default is [`YConvention::TEXTURE_SPACE`] (for rendering).
    /// A normal map written for other tools usually wants [`YConvention::YUp`].
    pub y_convention: YConvention,
    /// How the components become bytes.
    pub encoding: Encoding,
}

impl Default for NormalMapOptions {
    fn default() -> Self {
        Self {
            kernel: Kernel::Forward,
            scale: 4.0,
            wrap: Wrap::Repeat,
            y_convention: YConvention::TEXTURE_SPACE,
            encoding: Encoding::Unorm,
        }
    }
}

/// Why a normal map cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NormalMapError {
    /// `Wrap::Border` on an input narrower or shorter than 2.
    #[error("--wrap border needs an input at least 2x2 (one extra column and row), got {0}x{1}")]
    BorderTooSmall(usize, usize),
    /// A scale that is not finite or beyond `MAX_SCALE`.
    #[error("scale must be a number in [-1e6, 1e6], got {0}")]
    BadScale(f32),
    /// The map is too big for the machine's memory.
    #[error(transparent)]
    OutOfMemory(#[from] crate::buffer::OutOfMemory),
}

/// The largest |scale| accepted: beyond it the squared slope could overflow single precision.
pub const MAX_SCALE: f32 = 1e6;

/// The output size for an input of `w`×`h` texels: the same, or one smaller for the border case.
pub fn output_size(w: usize, h: usize, options: &NormalMapOptions) -> Result<(usize, usize), NormalMapError> {
    if options.scale.is_nan() || options.scale.abs() > MAX_SCALE {
        return Err(NormalMapError::BadScale(options.scale));
    }
    match options.wrap {
        Wrap::Border if w < 2 || h < 2 => Err(NormalMapError::BorderTooSmall(w, h)),
        Wrap::Border => Ok((w - 1, h - 1)),
        _ => Ok((w, h)),
    }
}

/// Evaluates the derivative taps over whole rows. Holds per-thread scratch so rows are computed
/// with no allocation.
pub(crate) struct RowEvaluator<'a> {
    field: &'a HeightField,
    options: NormalMapOptions,
    du_taps: Vec<Tap>,
    dv_taps: Vec<Tap>,
    out_width: usize,
}

/// Per-thread buffers for one row: the derivatives, then the normal's components in place
/// (structure of arrays, so the normalization runs as SIMD lanes).
#[derive(Default)]
pub(crate) struct RowScratch {
    /// ∂F/∂u, then n.x.
    pub(crate) nx: Vec<f32>,
    /// ∂F/∂v, then n.y.
    pub(crate) ny: Vec<f32>,
    pub(crate) nz: Vec<f32>,
    /// Height rows converted to floats, keyed by row index (see [`HeightField::row`]).
    rows: [(usize, Vec<f32>); 8],
}

impl<'a> RowEvaluator<'a> {
    pub(crate) fn new(field: &'a HeightField, options: NormalMapOptions) -> Result<Self, NormalMapError> {
        let (out_width, _) = output_size(field.width(), field.height(), &options)?;
        Ok(Self { field, options, du_taps: options.kernel.taps_du(), dv_taps: options.kernel.taps_dv(), out_width })
    }

    /// Accumulates `Σ weight·F(x+dx, y+dy)` for one output row into `acc`.
    #[inline(always)]
    fn apply(&self, taps: &[Tap], y: usize, acc: &mut Vec<f32>, rows: &mut [(usize, Vec<f32>); 8]) {
        let (w, h) = (self.field.width(), self.field.height());
        let n = self.out_width;
        acc.clear();
        acc.resize(n, 0.0);
        for tap in taps {
            let sy = self.options.wrap.index(y as i64 + tap.dy as i64, h);
            // A slot per row index mod 8: a kernel reads at most 7 rows, and the next output
            // row reuses most of them. A slot holds its row index + 1 (0 = empty).
            let (key, buf) = &mut rows[sy % 8];
            let src = match self.field.float_row(sy) {
                Some(row) => row,
                None => {
                    if *key != sy + 1 {
                        self.field.row(sy, buf);
                        *key = sy + 1;
                    }
                    &buf[..]
                }
            };
            let wt = tap.weight;
            // Interior: x + dx stays inside the row, a straight slice the compiler vectorizes.
            // On a row narrower than the kernel there is no interior (lo = hi): every x wraps.
            let lo = ((-tap.dx).max(0) as usize).min(n);
            let hi = (w as i64 - tap.dx as i64).min(n as i64).max(lo as i64) as usize;
            if hi > lo {
                let shifted = &src[(lo as i64 + tap.dx as i64) as usize..(hi as i64 + tap.dx as i64) as usize];
                for (a, &s) in acc[lo..hi].iter_mut().zip(shifted) {
                    *a += wt * s;
                }
            }
            for x in (0..lo.min(n)).chain(hi..n) {
                acc[x] += wt * src[self.options.wrap.index(x as i64 + tap.dx as i64, w)];
            }
        }
    }

    /// Computes output row `y`: its unit normals into `scratch` and their bytes into `out`.
    #[inline]
    pub(crate) fn process_row<T: Texel>(&self, y: usize, scratch: &mut RowScratch, out: &mut [T]) {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2, checked just above.
            unsafe { self.process_row_avx2(y, scratch, out) };
            return;
        }
        self.process_row_generic(y, scratch, out);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn process_row_avx2<T: Texel>(&self, y: usize, scratch: &mut RowScratch, out: &mut [T]) {
        self.process_row_generic(y, scratch, out);
    }

    #[inline(always)]
    fn process_row_generic<T: Texel>(&self, y: usize, scratch: &mut RowScratch, out: &mut [T]) {
        self.normals_generic(y, scratch);
        encode_row(scratch, out, self.options.encoding);
    }

    /// The row kernel, inlined into each instruction-set variant.
    #[inline(always)]
    fn normals_generic(&self, y: usize, scratch: &mut RowScratch) {
        let RowScratch { nx, ny, nz, rows } = scratch;
        self.apply(&self.du_taps, y, nx, rows);
        self.apply(&self.dv_taps, y, ny, rows);
        nz.resize(nx.len(), 0.0);
        let s = self.options.scale;
        // Texture-space Y is along +t, down the image; Y up negates it.
        let flip = if self.options.y_convention == YConvention::YUp { -1.0 } else { 1.0 };
        // The paper's double-precision reciprocal only matters for its own byte encoding;
        // unorm takes the single-precision one, half the work per lane.
        if self.options.encoding == Encoding::Kilgard {
            for ((x, y), z) in nx.iter_mut().zip(ny.iter_mut()).zip(nz.iter_mut()) {
                let n = perturbed_normal(-s * *x, -s * *y, flip);
                (*x, *y, *z) = (n.x, n.y, n.z);
            }
        } else {
            for ((x, y), z) in nx.iter_mut().zip(ny.iter_mut()).zip(nz.iter_mut()) {
                let (a, b) = (-s * *x, -s * *y);
                let recip = 1.0 / (a * a + b * b + 1.0).sqrt();
                (*x, *y, *z) = (a * recip, flip * (b * recip), recip);
            }
        }
    }

    /// Computes the unit normals of output row `y` and hands each (x, n) to `sink` (for tests).
    #[cfg(test)]
    pub(crate) fn row(&self, y: usize, scratch: &mut RowScratch, mut sink: impl FnMut(usize, Vec3)) {
        self.normals_generic(y, scratch);
        for x in 0..scratch.nx.len() {
            sink(x, Vec3::new(scratch.nx[x], scratch.ny[x], scratch.nz[x]));
        }
    }
}

/// Range-compresses a row of unit normals into RGBA with A at its largest (Kilgard Eq. 28).
#[inline(always)]
pub(crate) fn encode_row<T: Texel>(scratch: &RowScratch, out: &mut [T], enc: Encoding) {
    let n = out.len();
    let (nx, ny, nz) = (&scratch.nx[..n], &scratch.ny[..n], &scratch.nz[..n]);
    // One loop per encoding keeps the match out of the lanes.
    match enc {
        Encoding::Unorm => {
            for i in 0..n {
                out[i] = T::pack_opaque(nx[i], ny[i], nz[i], Encoding::Unorm);
            }
        }
        Encoding::Kilgard => {
            for i in 0..n {
                out[i] = T::pack_opaque(nx[i], ny[i], nz[i], Encoding::Kilgard);
            }
        }
    }
}

/// Kilgard Eq. 27 from the scaled, negated derivatives `a = −s·∂F/∂u`, `b = −s·∂F/∂v`.
///
/// Evaluated as Appendix E does (`1/sqrt` in double precision of `a² + b² + 1` summed left to
/// right in single precision), so the `kilgard` encoding matches the paper's code to the byte.
#[inline(always)]
pub fn perturbed_normal(a: f32, b: f32, y_sign: f32) -> Vec3 {
    let sqrlen = a * a + b * b + 1.0;
    let recip = (1.0 / (sqrlen as f64).sqrt()) as f32;
    Vec3::new(a * recip, y_sign * (b * recip), recip)
}

/// Level 0 only: each texel's unit normal range-compressed in RGB, A = 255.
pub fn normal_map_level0(field: &HeightField, options: &NormalMapOptions) -> Result<Rgba8Image, NormalMapError> {
    normal_map_level0_texels(field, options)
}

/// [`normal_map_level0`] in texels of 8 or 16 bits (A = 65535 at 16 bits).
pub fn normal_map_level0_texels<T: Texel>(
    field: &HeightField,
    options: &NormalMapOptions,
) -> Result<Image<T>, NormalMapError> {
    use rayon::prelude::*;
    let (w, h) = output_size(field.width(), field.height(), options)?;
    let eval = RowEvaluator::new(field, *options)?;
    let mut texels = crate::buffer::try_zeroed::<T>(w * h, "the normal map")?;
    texels.par_chunks_mut(w).enumerate().for_each_init(RowScratch::default, |scratch, (y, row)| {
        eval.process_row(y, scratch, row);
    });
    Ok(Image { width: w, height: h, texels })
}

/// Range-compresses a unit normal with A at its largest (Kilgard Eq. 28; level 0's length is 1).
#[inline(always)]
pub fn encode_unit<T: Texel>(n: Vec3, enc: Encoding) -> T {
    T::pack_opaque(n.x, n.y, n.z, enc)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Named;

    #[test]
    fn images_narrower_or_shorter_than_the_kernel_give_unit_normals() {
        // A 1- to 3-texel-wide (or tall) image under a 5×5 or 7×7 kernel: every tap wraps.
        for kernel in crate::Kernel::ALL {
            for wrap in [crate::Wrap::Repeat, crate::Wrap::Clamp, crate::Wrap::Border] {
                for (w, h) in [(1, 9), (2, 9), (3, 9), (9, 1), (9, 2), (2, 2), (4, 3)] {
                    let data: Vec<f32> = (0..w * h).map(|i| ((i * 37) % 11) as f32 / 10.0).collect();
                    let field = HeightField::new(w, h, data).unwrap();
                    let options = NormalMapOptions { kernel, wrap, ..Default::default() };
                    match normal_map_level0(&field, &options) {
                        Ok(map) => {
                            let (ow, oh) = output_size(w, h, &options).unwrap();
                            assert_eq!((map.width, map.height), (ow, oh));
                            for y in 0..oh {
                                for x in 0..ow {
                                    let (n, _) = map.decode(x, y, options.encoding);
                                    assert!((n.length() - 1.0).abs() < 0.02, "{kernel:?} {wrap:?} {w}x{h}: {n}");
                                }
                            }
                        }
                        // Border needs one extra column and row.
                        Err(NormalMapError::BorderTooSmall(..)) => assert!(w < 2 || h < 2),
                        Err(e) => panic!("{kernel:?} {wrap:?} {w}x{h}: {e}"),
                    }
                }
            }
        }
    }

    fn field(w: usize, h: usize, f: impl Fn(f32, f32) -> f32) -> HeightField {
        HeightField::from_fn(w, h, |x, y| f(x as f32, y as f32))
    }

    #[test]
    fn flat_field_points_straight_up() {
        let f = field(7, 5, |_, _| 0.3);
        for k in Kernel::ALL {
            let opts = NormalMapOptions { kernel: k, ..Default::default() };
            let map = normal_map_level0(&f, &opts).unwrap();
            assert!(map.texels.iter().all(|&t| t == [128, 128, 255, 255]), "{}", k.name());
        }
    }

    #[test]
    fn ramp_gives_the_analytic_tilt() {
        // F = 0.01·u + 0.02·v, scale 4: n ∝ (−0.04, −0.08, 1) everywhere away from the wrap seam.
        let f = field(32, 32, |x, y| 0.01 * x + 0.02 * y);
        let want = Vec3::new(-0.04, -0.08, 1.0).normalize();
        for k in Kernel::ALL {
            let opts = NormalMapOptions { kernel: k, wrap: Wrap::Clamp, ..Default::default() };
            let eval = RowEvaluator::new(&f, opts).unwrap();
            let mut scratch = RowScratch::default();
            eval.row(16, &mut scratch, |x, n| {
                if (4..28).contains(&x) {
                    // Heights are f32 near 0.5, so differences carry ~1e-7 relative error.
                    assert!((n - want).length() < 1e-5, "{} at x={x}: {n} vs {want}", k.name());
                }
            });
        }
        let up = NormalMapOptions { y_convention: YConvention::YUp, ..Default::default() };
        let down = normal_map_level0(&f, &NormalMapOptions::default()).unwrap();
        let gl = normal_map_level0(&f, &up).unwrap();
        let (a, b) = (down.texel(5, 5), gl.texel(5, 5));
        assert!(a[1] < 128 && b[1] > 128, "green flips between conventions: {a:?} vs {b:?}");
        assert_eq!((a[0], a[2]), (b[0], b[2]));
    }

    #[test]
    fn border_case_reads_the_extra_column_and_row() {
        let f = field(5, 4, |x, y| if x == 4.0 || y == 3.0 { 1.0 } else { 0.0 });
        let opts = NormalMapOptions { wrap: Wrap::Border, ..Default::default() };
        let map = normal_map_level0(&f, &opts).unwrap();
        assert_eq!((map.width, map.height), (4, 3));
        // Only the last output column sees the raised extra column (slope +1 → n.x < 0).
        assert!(map.texel(3, 0)[0] < 100 && map.texel(2, 0)[0] == 128);
        assert!(map.texel(0, 2)[1] < 100 && map.texel(0, 1)[1] == 128);
        let tiny = field(1, 3, |_, _| 0.0);
        assert_eq!(normal_map_level0(&tiny, &opts), Err(NormalMapError::BorderTooSmall(1, 3)));
    }
}
