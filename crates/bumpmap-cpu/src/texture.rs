//! Texture units with OpenGL 1.2 rules: 2D mipmapped textures and cube maps, NEAREST, LINEAR and
//! the mipmap filters with λ from screen-space derivatives, REPEAT and CLAMP_TO_EDGE
//! (SPECS.md §2–3, GL 1.2 §3.8).
//!
//! Texels stay 8-bit; a sample is returned as floats in [0, 1], which is what the register
//! combiners receive. There is no border colour (CLAMP, not CLAMP_TO_EDGE, is not emulated), no
//! LOD bias (not core in 1.2), no anisotropy, and cube maps do not filter across faces.

use glam::{Vec3, Vec4};

use bumpmap_math::buffer::OutOfMemory;
use bumpmap_math::{CubeFace, NormalizationCubeMap, Rgba8Image, Rgba8Mips};

pub use bumpmap_core::state::{MagFilter, MinFilter, Sampler, WrapMode};

mod lanes;
mod moments;
pub use lanes::{sample_2d_lanes, sample_cube_lanes};
pub(crate) use moments::MomentTexture;

/// One mip level: `width`×`height` RGBA8 texels, row 0 = t = 0.
///
/// Builds without SSE4.1, where converting bytes on the fly is slow, also keep each texel as
/// four floats (0–255); SSE4.1 builds keep only the bytes. AVX2 builds add the rows padded for
/// REPEAT (`pad_rows`), from which the batch sampler fetches both texels of a bilinear row
/// with one 64-bit load.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    pub width: usize,
    pub height: usize,
    texels: Vec<[u8; 4]>,
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse4.1")))]
    values: Vec<Vec4>,
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma"))]
    repeat_rows: Vec<[u8; 4]>,
}

/// The bytes a texture unit holds for a texture of `texels` RGBA8 texels (all levels): the
/// bytes, plus the rows padded for REPEAT in AVX2 builds or the texels as floats in builds
/// without SSE4.1 (see `texture::Level`). What a command counts before it draws a large map.
pub fn texture_unit_bytes(texels: u64) -> u64 {
    let extra = if cfg!(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma")) {
        4
    } else if cfg!(all(target_arch = "x86_64", target_feature = "sse4.1")) {
        0
    } else {
        16
    };
    texels.saturating_mul(4 + extra)
}

/// `texels` (`width`×`height`, row-major) with one more column per row: the texel a LINEAR
/// lookup under `wrap` pairs with the row's last one (column 0 for REPEAT, the last column again
/// for CLAMP_TO_EDGE). Then the two texels of every bilinear row, (i, i + 1) after wrapping, are
/// adjacent.
#[cfg_attr(not(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma")), allow(dead_code))]
pub(crate) fn pad_rows(texels: &[[u8; 4]], width: usize, wrap: WrapMode) -> Result<Vec<[u8; 4]>, OutOfMemory> {
    let n = texels.len() + texels.len() / width;
    let mut out = try_vec(n, "a texture unit's padded rows")?;
    out.extend(texels.chunks_exact(width).flat_map(|row| {
        let extra = match wrap {
            WrapMode::Repeat => row[0],
            WrapMode::ClampToEdge | WrapMode::MirroredRepeat => row[width - 1],
        };
        row.iter().copied().chain(std::iter::once(extra))
    }));
    Ok(out)
}

/// An empty vector with room for `n` items, or the error naming `what` and its size.
fn try_vec<T>(n: usize, what: &'static str) -> Result<Vec<T>, OutOfMemory> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| OutOfMemory::of::<T>(what, n))?;
    Ok(v)
}

/// A 2D texture: level 0 and optionally every smaller level. RGB textures are stored with
/// A = 255, which is what the GL's RGB → register mapping gives (R, G, B, 1).
#[derive(Clone, Debug, PartialEq)]
pub struct Texture2d {
    pub levels: Vec<Level>,
}

impl Texture2d {
    /// The texture unit's copy of `mips`: every level, with the sampler's padded rows. Aborts
    /// when memory runs out: for textures whose size no input chooses ([`Texture2d::try_from_mips`]
    /// otherwise).
    pub fn from_mips(mips: &Rgba8Mips) -> Self {
        Self::try_from_mips(mips).expect("memory for a texture unit's copy")
    }

    /// [`Texture2d::from_mips`], or the error saying how much memory a copy needs (a texture
    /// unit holds two or more copies of each level: the bytes, and rows padded or floats
    /// depending on the build).
    pub fn try_from_mips(mips: &Rgba8Mips) -> Result<Self, OutOfMemory> {
        let mut levels = Vec::with_capacity(mips.levels().len());
        for l in mips.levels() {
            let mut texels = try_vec(l.texels.len(), "a texture unit's copy of a level")?;
            texels.extend_from_slice(&l.texels);
            levels.push(Level::try_new(l.width, l.height, texels)?);
        }
        Ok(Self { levels })
    }

    /// A single-level texture. Panics if the sizes disagree.
    pub fn from_rgba8(width: usize, height: usize, texels: Vec<[u8; 4]>) -> Self {
        Self::from_mips(&Rgba8Mips::single(Rgba8Image::new(width, height, texels)))
    }

    /// Level 0's width.
    pub fn width(&self) -> usize {
        self.levels[0].width
    }

    /// Level 0's height.
    pub fn height(&self) -> usize {
        self.levels[0].height
    }
}

/// Integer texel index along one axis for NEAREST.
#[inline(always)]
fn nearest_index(s: f32, n: usize, wrap: WrapMode) -> usize {
    let nf = n as f32;
    let i = match wrap {
        WrapMode::Repeat => ((s - s.floor()) * nf) as usize,
        WrapMode::ClampToEdge => (s * nf).max(0.0) as usize,
        WrapMode::MirroredRepeat => (WrapMode::mirror(s) * nf).max(0.0) as usize,
    };
    i.min(n - 1)
}

/// The two texel indices and the weight of the second for LINEAR along one axis.
#[inline(always)]
fn linear_indices(s: f32, n: usize, wrap: WrapMode) -> (usize, usize, f32) {
    let nf = n as f32;
    let u = match wrap {
        WrapMode::Repeat => (s - s.floor()) * nf - 0.5,
        // s ∈ [1/2N, 1 − 1/2N] at every level, so the filter never leaves the image.
        WrapMode::ClampToEdge => (s * nf).clamp(0.5, nf - 0.5) - 0.5,
        WrapMode::MirroredRepeat => (WrapMode::mirror(s) * nf).clamp(0.5, nf - 0.5) - 0.5,
    };
    let f = u.floor();
    let a = u - f;
    // u ∈ [−½, N − ½), so floor(u) ∈ [−1, N − 1]: one comparison wraps or clamps it.
    let i = f as i64;
    match wrap {
        WrapMode::Repeat => {
            let i0 = if i < 0 { n - 1 } else { (i as usize).min(n - 1) };
            (i0, if i0 + 1 == n { 0 } else { i0 + 1 }, a)
        }
        WrapMode::ClampToEdge | WrapMode::MirroredRepeat => {
            let i0 = (i.max(0) as usize).min(n - 1);
            (i0, (i0 + 1).min(n - 1), a)
        }
    }
}

/// The weights of texels (i0, j0), (i1, j0), (i0, j1), (i1, j1) for fractions α, β.
#[inline(always)]
fn bilinear_weights(a: f32, b: f32) -> [f32; 4] {
    let (ca, cb) = (1.0 - a, 1.0 - b);
    [ca * cb, a * cb, ca * b, a * b]
}

impl Level {
    /// A level from its texels, or the error saying how much memory its float or padded copy
    /// needs. Panics if the count is not `width·height`.
    pub fn try_new(width: usize, height: usize, texels: Vec<[u8; 4]>) -> Result<Self, OutOfMemory> {
        assert_eq!(texels.len(), width * height, "texel count of a {width}x{height} level");
        #[cfg(not(all(target_arch = "x86_64", target_feature = "sse4.1")))]
        let values = {
            let mut v = try_vec(texels.len(), "a texture unit's texels as floats")?;
            v.extend(texels.iter().map(|t| Vec4::new(t[0] as f32, t[1] as f32, t[2] as f32, t[3] as f32)));
            v
        };
        Ok(Self {
            width,
            height,
            #[cfg(not(all(target_arch = "x86_64", target_feature = "sse4.1")))]
            values,
            #[cfg(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma"))]
            repeat_rows: pad_rows(&texels, width, WrapMode::Repeat)?,
            texels,
        })
    }

    #[inline(always)]
    fn value(&self, x: usize, y: usize) -> Vec4 {
        self.value_at(y * self.width + x)
    }

    /// Texel `i` as floats in [0, 1].
    #[inline(always)]
    fn value_at(&self, i: usize) -> Vec4 {
        self.bytes_at(i) * (1.0 / 255.0)
    }

    /// Texel `i` as floats in [0, 255]. With SSE4.1 (any x86-64-v2 or later build) straight from
    /// the bytes, which keeps the working set 4× smaller than the float copy.
    #[inline(always)]
    fn bytes_at(&self, i: usize) -> Vec4 {
        #[cfg(all(target_arch = "x86_64", target_feature = "sse4.1"))]
        {
            crate::pixel::rgba8_bytes(self.texels[i])
        }
        #[cfg(not(all(target_arch = "x86_64", target_feature = "sse4.1")))]
        {
            self.values[i]
        }
    }

    #[inline(always)]
    fn nearest(&self, s: f32, t: f32, sampler: &Sampler) -> Vec4 {
        self.value(nearest_index(s, self.width, sampler.wrap_s), nearest_index(t, self.height, sampler.wrap_t))
    }

    #[inline(always)]
    fn linear(&self, s: f32, t: f32, sampler: &Sampler) -> Vec4 {
        let (i0, i1, a) = linear_indices(s, self.width, sampler.wrap_s);
        let (j0, j1, b) = linear_indices(t, self.height, sampler.wrap_t);
        let (r0, r1) = (j0 * self.width, j1 * self.width);
        // GL 1.2 Eq. 3.18's weighted sum of the four texels, accumulated with fused
        // multiply-adds in byte units and scaled to [0, 1] once (the batch sampler does the
        // same operations in the same order).
        let w = bilinear_weights(a, b);
        let v = self.bytes_at(r0 + i0) * w[0];
        let v = self.bytes_at(r0 + i1).mul_add(Vec4::splat(w[1]), v);
        let v = self.bytes_at(r1 + i0).mul_add(Vec4::splat(w[2]), v);
        let v = self.bytes_at(r1 + i1).mul_add(Vec4::splat(w[3]), v);
        v * (1.0 / 255.0)
    }
}

/// Samples a 2D texture at (s, t) with level of detail λ (GL 1.2 §3.8.8–3.8.9).
#[inline(always)]
pub fn sample_2d(tex: &Texture2d, sampler: &Sampler, s: f32, t: f32, lambda: f32) -> Vec4 {
    sample_levels(&tex.levels, sampler, s, t, lambda)
}

/// One level's NEAREST and LINEAR lookups, for [`sample_levels`]'s mipmap rules.
pub(crate) trait Filter {
    /// What a lookup returns; mipmap levels blend as `a·(1 − f) + b·f`.
    type Value: Copy + std::ops::Mul<f32, Output = Self::Value> + std::ops::Add<Output = Self::Value>;
    fn nearest(&self, s: f32, t: f32, sampler: &Sampler) -> Self::Value;
    fn linear(&self, s: f32, t: f32, sampler: &Sampler) -> Self::Value;
    #[inline(always)]
    fn filter(&self, s: f32, t: f32, linear: bool, sampler: &Sampler) -> Self::Value {
        if linear { self.linear(s, t, sampler) } else { self.nearest(s, t, sampler) }
    }
}

impl Filter for Level {
    type Value = Vec4;
    #[inline(always)]
    fn nearest(&self, s: f32, t: f32, sampler: &Sampler) -> Vec4 {
        Level::nearest(self, s, t, sampler)
    }
    #[inline(always)]
    fn linear(&self, s: f32, t: f32, sampler: &Sampler) -> Vec4 {
        Level::linear(self, s, t, sampler)
    }
}

/// GL 1.2's choice of level and filter for λ over `levels` (level 0 first), whatever a texel
/// holds: the one home of the mipmap rules for the 8-bit texture units and the float moments.
#[inline(always)]
pub(crate) fn sample_levels<L: Filter>(levels: &[L], sampler: &Sampler, s: f32, t: f32, lambda: f32) -> L::Value {
    let base = &levels[0];
    if lambda <= sampler.switch_over() || !lambda.is_finite() && lambda < 0.0 {
        return base.filter(s, t, sampler.mag == MagFilter::Linear, sampler);
    }
    let q = (levels.len() - 1) as f32;
    let pick = |d: f32| &levels[d.min(q) as usize];
    match sampler.min {
        MinFilter::Nearest => base.nearest(s, t, sampler),
        MinFilter::Linear => base.linear(s, t, sampler),
        MinFilter::NearestMipmapNearest | MinFilter::LinearMipmapNearest => {
            let d = Sampler::nearest_level(lambda, levels.len() - 1);
            levels[d].filter(s, t, sampler.min == MinFilter::LinearMipmapNearest, sampler)
        }
        MinFilter::NearestMipmapLinear | MinFilter::LinearMipmapLinear => {
            let linear = sampler.min == MinFilter::LinearMipmapLinear;
            if lambda >= q {
                return pick(q).filter(s, t, linear, sampler);
            }
            let d1 = lambda.floor();
            let f = lambda - d1;
            let t1 = pick(d1).filter(s, t, linear, sampler);
            if f == 0.0 {
                return t1;
            }
            t1 * (1.0 - f) + pick(d1 + 1.0).filter(s, t, linear, sampler) * f
        }
    }
}

/// λ = log2 ρ for one 2×2 quad, ρ the larger screen-space footprint length in texels (GL 1.2
/// Eq. 3.14), from the texture coordinates of the quad's pixels (0,0), (1,0) and (0,1).
#[cfg(test)]
pub fn lambda_2d(tex: &Texture2d, s: [f32; 3], t: [f32; 3]) -> f32 {
    lambda_from_rho2(rho2_2d(tex, s, t))
}

/// ρ² of one quad's footprint (GL 1.2 Eq. 3.14): the scalar twin of the AVX2 batch path.
#[cfg(any(test, not(all(target_arch = "x86_64", target_feature = "avx2"))))]
#[inline(always)]
pub(crate) fn rho2_2d(tex: &Texture2d, s: [f32; 3], t: [f32; 3]) -> f32 {
    let (w, h) = (tex.width() as f32, tex.height() as f32);
    let (dudx, dvdx) = ((s[1] - s[0]) * w, (t[1] - t[0]) * h);
    let (dudy, dvdy) = ((s[2] - s[0]) * w, (t[2] - t[0]) * h);
    // `max_lo` rather than `f32::max`: the batch path's `maxps` treats NaN the same way.
    bumpmap_core::lane_math::max_lo(dudx * dudx + dvdx * dvdx, dudy * dudy + dvdy * dvdy)
}

/// λ = ½·log2 ρ². The logarithm is a short series (GL lets λ be approximated) that agrees with
/// `f32::log2` to about 1e-7 and, unlike a libm call, vectorizes over a batch's quads. ρ² = 0
/// gives −∞ (magnification); ∞ and NaN pass through.
#[inline(always)]
pub(crate) fn lambda_from_rho2(rho2: f32) -> f32 {
    // rho2 = m·2^e with m in [√½, √2); ln m = 2·atanh(u), u = (m − 1)/(m + 1), |u| < 0.172.
    let bits = rho2.to_bits();
    let high = (bits & 0x007f_ffff) > 0x0035_04f3; // mantissa above √2: use m/2, e + 1
    let e = ((bits >> 23) & 0xff) as i32 - 127 + high as i32;
    let m = f32::from_bits((bits & 0x007f_ffff) | if high { 0x3f00_0000 } else { 0x3f80_0000 });
    let u = (m - 1.0) / (m + 1.0);
    let u2 = u * u;
    let atanh = u * (1.0 + u2 * (1.0 / 3.0 + u2 * (1.0 / 5.0 + u2 * (1.0 / 7.0 + u2 * (1.0 / 9.0)))));
    let log2 = e as f32 + atanh * (2.0 * std::f32::consts::LOG2_E);
    let log2 = if rho2 == 0.0 {
        f32::NEG_INFINITY
    } else if rho2.is_finite() {
        log2
    } else {
        rho2
    };
    0.5 * log2
}

/// A cube map: six square faces in GL order, each a 2D texture.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureCube {
    faces: [Texture2d; 6],
    /// Level 0 of the six faces back to back with rows padded for CLAMP_TO_EDGE ([`pad_rows`]),
    /// when they are square, of one size and have one level: the layout the batch sampler
    /// fetches from (AVX2 builds).
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma"))]
    packed: Option<Vec<[u8; 4]>>,
}

impl TextureCube {
    /// A cube map from its faces in GL order (+X, −X, +Y, −Y, +Z, −Z).
    pub fn new(faces: [Texture2d; 6]) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma"))]
        let packed = {
            let n = faces[0].width();
            let uniform = faces.iter().all(|f| f.levels.len() == 1 && f.width() == n && f.height() == n);
            uniform.then(|| {
                faces
                    .iter()
                    .flat_map(|f| {
                        pad_rows(&f.levels[0].texels, n, WrapMode::ClampToEdge)
                            .expect("memory for a cube map's padded faces (six of a cube face's size)")
                    })
                    .collect()
            })
        };
        Self {
            faces,
            #[cfg(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma"))]
            packed,
        }
    }

    /// The normalization cube map as a texture (A = 255: an RGB texture).
    pub fn from_normalization(map: &NormalizationCubeMap) -> Self {
        let n = map.size;
        Self::new(
            map.faces
                .clone()
                .map(|f| Texture2d::from_rgba8(n, n, f.into_iter().map(|[r, g, b]| [r, g, b, 255]).collect())),
        )
    }
}

/// Samples a cube map with the direction (s, t, r): face and face coordinates per Kilgard
/// Table 1, then ordinary 2D filtering on that face. A zero or non-finite direction returns
/// transparent black.
#[inline]
pub fn sample_cube(tex: &TextureCube, sampler: &Sampler, r: Vec3, lambda: f32) -> Vec4 {
    match CubeFace::select(r) {
        Some((face, s, t)) => sample_2d(&tex.faces[face as usize], sampler, s, t, lambda),
        None => Vec4::ZERO,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp(w: usize, h: usize) -> Texture2d {
        Texture2d::from_rgba8(w, h, (0..w * h).map(|i| [(i % w * 10) as u8, (i / w * 10) as u8, 0, 255]).collect())
    }

    #[test]
    fn linear_at_texel_centres_returns_texels_and_blends_between() {
        let tex = ramp(4, 4);
        let s = Sampler::LINEAR_REPEAT;
        let c = sample_2d(&tex, &s, 1.5 / 4.0, 2.5 / 4.0, 0.0) * 255.0;
        assert!((c.x - 10.0).abs() < 1e-3 && (c.y - 20.0).abs() < 1e-3, "{c}");
        let mid = sample_2d(&tex, &s, 2.0 / 4.0, 2.5 / 4.0, 0.0) * 255.0;
        assert!((mid.x - 15.0).abs() < 1e-3, "{mid}");
        // REPEAT: s = 0 sits between the last and first columns.
        let wrap = sample_2d(&tex, &s, 0.0, 0.5 / 4.0, 0.0) * 255.0;
        assert!((wrap.x - 15.0).abs() < 1e-3, "{wrap}");
        // CLAMP_TO_EDGE: s = 0 is the first column exactly.
        let clamp = sample_2d(&tex, &Sampler::LINEAR_CLAMP, 0.0, 0.5 / 4.0, 0.0) * 255.0;
        assert!(clamp.x.abs() < 1e-3, "{clamp}");
    }

    #[test]
    fn nearest_picks_the_texel_containing_s() {
        let tex = ramp(4, 1);
        let s = Sampler::NEAREST_REPEAT;
        assert_eq!((sample_2d(&tex, &s, 0.26, 0.5, 0.0).x * 255.0).round(), 10.0);
        assert_eq!((sample_2d(&tex, &s, 0.99, 0.5, 0.0).x * 255.0).round(), 30.0);
        assert_eq!((sample_2d(&tex, &s, 1.01, 0.5, 0.0).x * 255.0).round(), 0.0, "REPEAT uses frac(s)");
    }

    #[test]
    fn lambda_series_matches_log2() {
        let mut x = 1e-30f32;
        while x < 1e30 {
            let (fast, exact) = (lambda_from_rho2(x), 0.5 * x.log2());
            // A five-term atanh series (truncation < 1e-9) and a few roundings in f32.
            assert!((fast - exact).abs() < 1e-6, "ρ² = {x}: {fast} vs {exact}");
            x *= 1.37;
        }
        for x in [1.0f32, 2.0, 4.0, 0.25, std::f32::consts::SQRT_2] {
            assert!((lambda_from_rho2(x) - 0.5 * x.log2()).abs() < 1e-7, "{x}");
        }
        assert_eq!(lambda_from_rho2(0.0), f32::NEG_INFINITY);
        assert_eq!(lambda_from_rho2(f32::INFINITY), f32::INFINITY);
        assert!(lambda_from_rho2(f32::NAN).is_nan());
    }

    #[test]
    fn trilinear_blends_levels_by_frac_lambda() {
        let mut tex = Texture2d::from_rgba8(2, 2, vec![[200, 0, 0, 255]; 4]);
        tex.levels.push(Level::try_new(1, 1, vec![[100, 0, 0, 255]]).unwrap());
        let s = Sampler::TRILINEAR_REPEAT;
        let at = |l| (sample_2d(&tex, &s, 0.3, 0.3, l).x * 255.0).round();
        assert_eq!(at(-1.0), 200.0, "magnification uses level 0");
        assert_eq!(at(0.25), 175.0);
        assert_eq!(at(0.5), 150.0);
        assert_eq!(at(7.0), 100.0, "λ beyond the last level clamps to it");
        // λ from a quad whose s grows by one texel per pixel is 0; two texels, 1.
        assert_eq!(lambda_2d(&tex, [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]), 0.0);
        assert_eq!(lambda_2d(&tex, [0.0, 1.0, 0.0], [0.0, 0.0, 0.25]), 1.0);
    }

    #[test]
    fn mirrored_repeat_is_repeat_over_the_texture_and_its_mirror_image() {
        // GL's MIRRORED_REPEAT of T at s is REPEAT of [T | T flipped] (twice as wide) at s/2,
        // at level 0 with either filter: an independent model of the definition.
        let (w, h) = (5, 3);
        let tex = ramp(w, h);
        let texels: Vec<[u8; 4]> = (0..h)
            .flat_map(|y| (0..2 * w).map(move |x| if x < w { (x, y) } else { (2 * w - 1 - x, y) }))
            .map(|(x, y)| [(x * 10) as u8, (y * 10) as u8, 0, 255])
            .collect();
        let doubled = Texture2d::from_rgba8(2 * w, h, texels);
        for (mirror, repeat) in [
            (Sampler { wrap_s: WrapMode::MirroredRepeat, ..Sampler::LINEAR_REPEAT }, Sampler::LINEAR_REPEAT),
            (Sampler { wrap_s: WrapMode::MirroredRepeat, ..Sampler::NEAREST_REPEAT }, Sampler::NEAREST_REPEAT),
        ] {
            for i in -70..70 {
                let s = i as f32 * 0.061 + 0.013;
                let a = sample_2d(&tex, &mirror, s, 0.5, 0.0) * 255.0;
                let b = sample_2d(&doubled, &repeat, s / 2.0, 0.5, 0.0) * 255.0;
                assert!((a - b).abs().max_element() < 1e-3, "{:?} at s = {s}: {a} vs {b}", mirror.min);
            }
        }
    }
}
