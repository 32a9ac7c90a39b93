//! LEAN mapping's moments (Olano & Baker 2010, "LEAN Mapping", with its errata): the first and
//! second moments of the surface slopes under a texel, which, unlike a normal, can be averaged
//! by any linear filter and still say how spread the slopes are.
//!
//! A unit normal N (tangent space) has the slope B = (Nx/Nz, Ny/Nz) and second moment
//! M = (Bx², Bx·By, By²). Averaged over a footprint, M − BBᵀ is the covariance of the slopes;
//! adding the material's own lobe width gives the Gaussian Σ that the specular lobe uses
//! ([`LeanMoments::specular`]). The chain here holds each level's exact mean over the level-0
//! texels it covers (the footprints of [`crate::mip`]), which a GPU's trilinear filter then
//! keeps on averaging.
//!
//! Two changes to the paper's lobe, both from reading a Gaussian over slopes as the (H·N)^s of
//! the single pass, which the reference draws per sample:
//! - The base width is 1/(s + 1), not 1/s: a flat texel's (H·N)^s holds 2π/(s + 1) over
//!   directions, and so does exp(−|h̃|²(s + 1)/2)/Hz³ below (on the bricks' torus at s = 8 this
//!   alone takes LEAN from 24.8 to 25.9 dB against the reference).
//! - One moment more: J = 1/Nz³ = (1 + |B|²)^{3/2}, the Jacobian from directions to slopes
//!   (dΩ = d(slope)/J). A tilted texel's lobe covers J times the slopes a flat one's does, so a
//!   steep facet's highlight is wider in slope space, and brings more, than a constant lobe
//!   gives it. The lobe is weighted by the Jacobian at H's own slope, 1/Hz³ (where a facet must
//!   lie to send H's highlight), and widened by J's mean ([`LeanMoments::covariance`]), so that
//!   any single texel still peaks at 1, as (H·N)^s does. Where every normal is straight up,
//!   J = 1.
//!
//! Measured on a map whose slopes are mostly flat with steep walls (the golf ball's dimples,
//! `compare`'s specular study, 1× to 16×): the paper's lobe loses 29–46 % of the highlight's
//! energy; with J's mean as the lobe's weight instead of 1/Hz³ it gains 27–36 % (the steep
//! facets' weight lands where the sphere shows little area); as here, −4 to −12 %.
//!
//! What no single Gaussian does: follow a slope distribution that is not one. The dimples'
//! slopes are peaked (half below 0.32) with long tails (to 2.6); a Gaussian of the same
//! covariance spreads the highlight a third wider than the reference's (0.54 against 0.40 of
//! the ball's radius, and 6.5 % less energy, computed from the map's slopes alone), which is
//! what the study measures.
//!
//! What this module does not do: sample the moments (the backends' texture units), or make
//! moments for object-space maps or offset maps (slopes are relative to the tangent plane's
//! normal; those maps have none).

use glam::{Vec2, Vec3};

use crate::buffer::OutOfMemory;
use crate::encoding::Encoding;
use crate::image::{Image, Rgba8Image, Rgba8Mips};
use crate::levels::{footprint, next_size};

/// The smallest Nz a slope is taken from: steeper normals are read as slope 10, so the second
/// moments (up to 200) stay well inside a half float's range on the GPU, and a normal lying in
/// the tangent plane does not give an infinite slope.
pub const MIN_NZ: f32 = 0.1;

/// The first and second moments of the slopes under one texel.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct LeanMoments {
    /// The mean slope B = (Nx/Nz, Ny/Nz).
    pub b: Vec2,
    /// The mean second moments (Bx², Bx·By, By²).
    pub m: Vec3,
    /// The mean of J = 1/Nz³, the slopes' Jacobian (≥ 1).
    pub j: f32,
}

impl LeanMoments {
    /// A flat surface: no slope, no spread.
    pub const FLAT: Self = Self { b: Vec2::ZERO, m: Vec3::ZERO, j: 1.0 };

    /// Nothing: where a weighted sum starts.
    const ZERO: Self = Self { b: Vec2::ZERO, m: Vec3::ZERO, j: 0.0 };

    /// The moments of one unit normal `n` (tangent space, +z out of the surface).
    ///
    /// ```
    /// use bumpmap_math::lean::LeanMoments;
    /// use glam::Vec3;
    ///
    /// let m = LeanMoments::of_normal(Vec3::new(0.6, 0.0, 0.8));
    /// assert_eq!(m.b.x, 0.75);
    /// assert_eq!(m.m.x, 0.75 * 0.75);
    /// ```
    pub fn of_normal(n: Vec3) -> Self {
        let z = n.z.max(MIN_NZ);
        let b = Vec2::new(n.x / z, n.y / z);
        Self { b, m: Vec3::new(b.x * b.x, b.x * b.y, b.y * b.y), j: 1.0 / (z * z * z) }
    }

    /// The six numbers in the order the textures hold them: Bx, By, Mxx, Myy | Mxy, J.
    pub fn to_array(self) -> [f32; 6] {
        [self.b.x, self.b.y, self.m.x, self.m.z, self.m.y, self.j]
    }

    /// The moments from [`LeanMoments::to_array`]'s order.
    pub fn from_array(a: [f32; 6]) -> Self {
        Self { b: Vec2::new(a[0], a[1]), m: Vec3::new(a[2], a[4], a[3]), j: a[5] }
    }

    /// CLEAN mapping (Olano & Baker 2010, §5): these moments with the slopes' spread made
    /// isotropic — σ² = ½(Mxx + Myy − |B|²) along both axes, no correlation — which is all a
    /// texture of Bx, By and Mxx + Myy (and J) can say: four channels where LEAN needs six
    /// (three and five in the paper, which has no J). The spread's total (the covariance's
    /// trace) is kept; its direction is lost, so a texel whose bumps run one way gets a round
    /// highlight. Only Mxx + Myy is read: filtering that sum is filtering the moments.
    ///
    /// ```
    /// use bumpmap_math::lean::LeanMoments;
    /// use glam::{Vec2, Vec3};
    ///
    /// // Slopes spread along x only (variance 0.09): CLEAN shares it out, 0.045 each way.
    /// let lean = LeanMoments { b: Vec2::new(0.1, 0.0), m: Vec3::new(0.01 + 0.09, 0.0, 0.0), j: 1.2 };
    /// let c = lean.isotropic().covariance(f32::INFINITY);
    /// assert!((c - Vec3::new(0.045, 0.0, 0.045)).abs().max_element() < 1e-6);
    /// assert_eq!(LeanMoments::FLAT.isotropic(), LeanMoments::FLAT);
    /// ```
    pub fn isotropic(self) -> Self {
        let (bx2, by2) = (self.b.x * self.b.x, self.b.y * self.b.y);
        let half = 0.5 * ((self.m.x + self.m.z) - (bx2 + by2));
        Self { b: self.b, m: Vec3::new(bx2 + half, self.b.x * self.b.y, by2 + half), j: self.j }
    }

    /// Σ = M − BBᵀ + I·J/(s + 1) as (Σxx, Σxy, Σyy): the spread of the slopes plus a
    /// Blinn–Phong lobe of exponent `shininess` read as a Gaussian in slope space (Olano & Baker
    /// §3.2 with the errata, whose variance is 1/s; 1/(s + 1) here, see the module's docs),
    /// widened by the mean Jacobian J so that its determinant grows as J² (the lobe of a texel
    /// tilted by θ covers J = 1/cos³θ times the slopes of a flat one's).
    pub fn covariance(self, shininess: f32) -> Vec3 {
        let inv_s = self.j / (shininess + 1.0);
        Vec3::new(
            self.m.x - self.b.x * self.b.x + inv_s,
            self.m.y - self.b.x * self.b.y,
            self.m.z - self.b.y * self.b.y + inv_s,
        )
    }

    /// The specular lobe for the unit half-angle vector `h` (tangent space): the Gaussian
    /// exp(−e/2), e = (h̃ − B)ᵀ Σ⁻¹ (h̃ − B), h̃ = (Hx/Hz, Hy/Hz), with Σ from
    /// [`LeanMoments::covariance`], over LEAN's 2π·√det Σ, times 2π/((s + 1)·Hz³) (a texel's
    /// (H·N)^s over directions, moved to slopes where H's highlight lies: the module's docs).
    /// Any single texel peaks at 1 where H lies along its normal; a flat one gives
    /// exp(−(s + 1)|h̃|²/2)/Hz³, the same integral as (H·N)^s and its curvature at the peak
    /// that of (H·N)^(s − 2); a spread texel widens and dims, as Toksvig's does.
    ///
    /// Zero where H lies within 10⁻⁴ of the surface or below it (the lobe's tail there is
    /// nothing in f32). det Σ is kept at least 10⁻⁶/(s + 1)² (errata: M − BBᵀ can round below
    /// zero).
    ///
    /// ```
    /// use bumpmap_math::lean::LeanMoments;
    /// use glam::Vec3;
    ///
    /// // A flat texel, H along the normal: the lobe's peak, 1.
    /// assert!((LeanMoments::FLAT.specular(Vec3::Z, 32.0) - 1.0).abs() < 1e-6);
    /// ```
    #[inline(always)]
    pub fn specular(self, h: Vec3, shininess: f32) -> f32 {
        if h.z <= 1e-4 {
            return 0.0;
        }
        let sigma = self.covariance(shininess);
        let floor = 1e-6 / ((shininess + 1.0) * (shininess + 1.0));
        let det = (sigma.x * sigma.z - sigma.y * sigma.y).max(floor);
        let (hx, hy) = (h.x / h.z - self.b.x, h.y / h.z - self.b.y);
        let e = (hx * hx * sigma.z - 2.0 * hx * hy * sigma.y + hy * hy * sigma.x) / det;
        (-0.5 * e).exp() / ((shininess + 1.0) * det.sqrt()) / (h.z * h.z * h.z)
    }
}

/// Moments add as a filter's weighted sum needs them to.
impl std::ops::Add for LeanMoments {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self { b: self.b + o.b, m: self.m + o.m, j: self.j + o.j }
    }
}

/// A filter weight times moments.
impl std::ops::Mul<f32> for LeanMoments {
    type Output = Self;
    #[inline(always)]
    fn mul(self, w: f32) -> Self {
        Self { b: self.b * w, m: self.m * w, j: self.j * w }
    }
}

/// The moments of every level of a normal map: level k's texel the mean of the level-0 moments
/// it covers.
#[derive(Clone, Debug, PartialEq)]
pub struct LeanMips {
    /// Level 0 first, as many levels as the normal map has.
    pub levels: Vec<Image<LeanMoments>>,
}

impl LeanMips {
    /// The moments of `normal_map`'s level 0 (its texels range-compressed by `encoding`; the
    /// stored smaller levels are not read, so a chain another tool renormalized loses nothing),
    /// filtered down to as many levels as `normal_map` has. Errors with the size needed when
    /// memory runs out.
    pub fn from_normal_map(normal_map: &Rgba8Mips, encoding: Encoding) -> Result<Self, OutOfMemory> {
        Self::from_level0(&normal_map.levels()[0], normal_map.levels().len(), encoding)
    }

    /// [`LeanMips::from_normal_map`] from a normal map's level 0 alone, `count` levels (at most
    /// down to 1×1).
    pub fn from_level0(base: &Rgba8Image, count: usize, encoding: Encoding) -> Result<Self, OutOfMemory> {
        let level0 = moments_of_level(base, encoding)?;
        let mut levels = Vec::with_capacity(count);
        levels.push(level0);
        // How many level-0 columns and rows each texel of the newest level covers.
        let mut cols = vec![1u32; base.width];
        let mut rows = vec![1u32; base.height];
        while levels.len() < count && {
            let last = levels.last().expect("level 0 is there");
            last.width > 1 || last.height > 1
        } {
            let prev = levels.last().expect("level 0 is there");
            let (w, h) = (next_size(prev.width), next_size(prev.height));
            let next_cols: Vec<u32> = (0..w).map(|i| footprint(i, prev.width).map(|x| cols[x]).sum()).collect();
            let next_rows: Vec<u32> = (0..h).map(|j| footprint(j, prev.height).map(|y| rows[y]).sum()).collect();
            let mut texels = Vec::new();
            texels.try_reserve_exact(w * h).map_err(|_| OutOfMemory::of::<LeanMoments>("LEAN moments", w * h))?;
            for j in 0..h {
                for i in 0..w {
                    let total = (next_cols[i] * next_rows[j]) as f32;
                    let mut sum = LeanMoments::ZERO;
                    for y in footprint(j, prev.height) {
                        for x in footprint(i, prev.width) {
                            let weight = (cols[x] * rows[y]) as f32 / total;
                            sum = sum + prev.texel(x, y) * weight;
                        }
                    }
                    texels.push(sum);
                }
            }
            levels.push(Image::new(w, h, texels));
            (cols, rows) = (next_cols, next_rows);
        }
        Ok(Self { levels })
    }
}

fn moments_of_level(level: &Rgba8Image, encoding: Encoding) -> Result<Image<LeanMoments>, OutOfMemory> {
    let n = level.width * level.height;
    let mut texels = Vec::new();
    texels.try_reserve_exact(n).map_err(|_| OutOfMemory::of::<LeanMoments>("LEAN moments", n))?;
    for y in 0..level.height {
        for x in 0..level.width {
            let (d, _) = level.decode(x, y, encoding);
            texels.push(LeanMoments::of_normal(d.normalize_or(Vec3::Z)));
        }
    }
    Ok(Image::new(level.width, level.height, texels))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mip::{MipChain, MipMode};
    use proptest::prelude::*;

    fn chain(w: usize, h: usize, seed: u64) -> Rgba8Mips {
        let mut rng = seed;
        let normals: Vec<Vec3> = (0..w * h)
            .map(|_| {
                let mut next = || {
                    rng = rng.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
                    ((rng >> 40) as f32) / (1u64 << 24) as f32 * 1.6 - 0.8
                };
                Vec3::new(next(), next(), 1.0).normalize()
            })
            .collect();
        MipChain::<[u8; 4]>::from_normals(w, h, &normals, Encoding::Unorm, MipMode::LengthInAlpha).into_mips()
    }

    proptest! {
        /// Every level's texel is the mean of the level-0 moments it covers, whatever the size,
        /// and its covariance is positive semi-definite (the moments of one distribution).
        #[test]
        fn each_level_is_the_mean_of_level_0_and_its_covariance_a_covariance(w in 1usize..23, h in 1usize..23, seed in any::<u64>()) {
            let mips = chain(w, h, seed);
            let lean = LeanMips::from_normal_map(&mips, Encoding::Unorm).unwrap();
            prop_assert_eq!(lean.levels.len(), mips.levels().len());
            let last = lean.levels.last().unwrap();
            prop_assert_eq!((last.width, last.height), (1, 1));
            let l0 = &lean.levels[0];
            let n = l0.texels.len() as f32;
            let mean_b: Vec2 = l0.texels.iter().map(|t| t.b).sum::<Vec2>() / n;
            let mean_m: Vec3 = l0.texels.iter().map(|t| t.m).sum::<Vec3>() / n;
            let mean_j: f32 = l0.texels.iter().map(|t| t.j).sum::<f32>() / n;
            let top = last.texel(0, 0);
            prop_assert!((top.j - mean_j).abs() < 1e-4 * mean_j, "{} vs {}", top.j, mean_j);
            prop_assert!((top.b - mean_b).abs().max_element() < 1e-4, "{} vs {}", top.b, mean_b);
            prop_assert!((top.m - mean_m).abs().max_element() < 1e-4, "{} vs {}", top.m, mean_m);
            for level in &lean.levels {
                for t in &level.texels {
                    let c = t.covariance(f32::INFINITY);
                    prop_assert!(c.x >= -1e-5 && c.z >= -1e-5 && c.x * c.z - c.y * c.y >= -1e-5, "{:?}", c);
                }
            }
        }
    }

    proptest! {
        /// CLEAN keeps the mean slope, J and the spread's total, loses its direction, and
        /// draws LEAN's lobe wherever the spread was round already.
        #[test]
        fn clean_is_lean_with_the_spread_shared_out(
            b in (-2.0f32..2.0, -2.0f32..2.0),
            spread in (0.0f32..1.0, -0.3f32..0.3, 0.0f32..1.0),
            j in 1.0f32..10.0,
            h in (-0.6f32..0.6, -0.6f32..0.6),
        ) {
            let b = Vec2::new(b.0, b.1);
            let lean = LeanMoments { b, m: Vec3::new(b.x * b.x + spread.0, b.x * b.y + spread.1, b.y * b.y + spread.2), j };
            let clean = lean.isotropic();
            let (cl, cc) = (lean.covariance(f32::INFINITY), clean.covariance(f32::INFINITY));
            prop_assert_eq!((clean.b, clean.j), (lean.b, lean.j));
            prop_assert!(((cl.x + cl.z) - (cc.x + cc.z)).abs() < 1e-4, "{cl} vs {cc}");
            prop_assert!((cc.x - cc.z).abs() < 1e-4 && cc.y.abs() < 1e-4, "{cc}");
            let twice = clean.isotropic();
            prop_assert!((twice.m - clean.m).abs().max_element() < 1e-5, "idempotent: {:?} vs {:?}", twice, clean);
            let round = LeanMoments { m: Vec3::new(b.x * b.x + spread.0, b.x * b.y, b.y * b.y + spread.0), ..lean };
            let h = Vec3::new(h.0, h.1, 1.0).normalize();
            let (a, c) = (round.specular(h, 16.0), round.isotropic().specular(h, 16.0));
            prop_assert!((a - c).abs() <= 1e-4 * a.max(1.0), "{a} vs {c}");
        }
    }

    #[test]
    fn a_flat_texel_is_close_to_blinn_phong_and_spread_widens_and_dims_it() {
        let s = 32.0;
        for deg in [0.0f32, 2.0, 5.0, 10.0] {
            let h = Vec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
            let lean = LeanMoments::FLAT.specular(h, s);
            let phong = h.z.powf(s);
            assert!((lean - phong).abs() < 0.03, "{deg}°: {lean} vs {phong}");
        }
        // Two texels tilted ±0.3 in x: the mean is flat, the spread is 0.09 in x only.
        let (a, b) = (
            LeanMoments::of_normal(Vec3::new(0.3, 0.0, 1.0).normalize()),
            LeanMoments::of_normal(Vec3::new(-0.3, 0.0, 1.0).normalize()),
        );
        let mean = (a + b) * 0.5;
        assert!(mean.b.length() < 1e-6);
        // J = (1 + 0.3²)^{3/2} for both; Σ = diag(0.3² + J/(s + 1), J/(s + 1)); at H = +z the
        // peak 1/((s + 1)·√det Σ).
        let j = 1.09f32.powf(1.5);
        assert!((mean.j - j).abs() < 1e-5, "{} vs {j}", mean.j);
        let peak = mean.specular(Vec3::Z, s);
        let v = j / (s + 1.0);
        let want = 1.0 / ((s + 1.0) * ((0.09 + v) * v).sqrt());
        assert!((peak - want).abs() < 1e-4, "the spread dims the peak: {peak} vs {want}");
        let off_x = Vec3::new(0.35, 0.0, 1.0).normalize();
        let off_y = Vec3::new(0.0, 0.35, 1.0).normalize();
        assert!(mean.specular(off_x, s) > LeanMoments::FLAT.specular(off_x, s), "wider along the spread");
        assert!(mean.specular(off_x, s) > mean.specular(off_y, s), "anisotropic: wider in x than in y");
        assert_eq!(mean.specular(-Vec3::Z, s), 0.0);
    }

    proptest! {
        /// One texel, however tilted, peaks at 1 where H lies along its normal, as (H·N)^s does.
        #[test]
        fn a_single_texel_peaks_at_one_along_its_normal(x in -0.95f32..0.95, y in -0.95f32..0.95, s in 1.0f32..200.0) {
            let z = (1.0 - x * x - y * y).max(0.0).sqrt();
            prop_assume!(z > 0.2);
            let n = Vec3::new(x, y, z);
            let peak = LeanMoments::of_normal(n).specular(n, s);
            prop_assert!((peak - 1.0).abs() < 1e-3, "{}: {}", n, peak);
        }
    }

    #[test]
    fn a_flat_texels_lobe_holds_what_blinn_phongs_does_over_directions() {
        // ∫ (H·N)^s dΩ = 2π/(s + 1); the lobe's integral, by the midpoint rule over θ.
        for s in [1.0f32, 8.0, 32.0, 100.0] {
            let steps = 200_000;
            let d = std::f64::consts::FRAC_PI_2 / steps as f64;
            let total: f64 = (0..steps)
                .map(|i| {
                    let theta = (i as f64 + 0.5) * d;
                    let h = Vec3::new(theta.sin() as f32, 0.0, theta.cos() as f32);
                    LeanMoments::FLAT.specular(h, s) as f64 * 2.0 * std::f64::consts::PI * theta.sin() * d
                })
                .sum();
            let want = 2.0 * std::f64::consts::PI / (s as f64 + 1.0);
            assert!((total / want - 1.0).abs() < 2e-3, "s {s}: {total} vs {want}");
        }
    }

    #[test]
    fn steep_normals_are_read_at_the_steepest_slope_kept() {
        let m = LeanMoments::of_normal(Vec3::X);
        assert_eq!(m.b, Vec2::new(1.0 / MIN_NZ, 0.0));
        assert!(m.m.is_finite());
    }
}
