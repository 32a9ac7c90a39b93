//! A float texture of LEAN moments (`bumpmap_math::lean`), sampled with the 8-bit texture
//! units' wrap, filter and mipmap rules (`sample_levels`): a GL 1.2 pipeline had no float
//! textures, so this is the single pass's extra unit, as a GPU's `Rgba16Float` pair is.
//!
//! Not vectorized: lanes are looked up one at a time (the LEAN filter's cost in BENCHMARKS.md
//! says what that costs).

use bumpmap_math::buffer::OutOfMemory;
use bumpmap_math::lean::{LeanMips, LeanMoments};

use super::{Filter, Sampler, bilinear_weights, linear_indices, nearest_index, sample_levels};
use crate::combiners::Lanes;

/// One level of moments, row 0 = t = 0.
#[derive(Clone, Debug, PartialEq)]
struct MomentLevel {
    width: usize,
    height: usize,
    texels: Vec<LeanMoments>,
}

/// Every level of a normal map's LEAN moments.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct MomentTexture {
    levels: Vec<MomentLevel>,
}

impl MomentTexture {
    /// The texture unit's copy of `mips`.
    pub fn try_from_mips(mips: &LeanMips) -> Result<Self, OutOfMemory> {
        let mut levels = Vec::with_capacity(mips.levels.len());
        for l in &mips.levels {
            let mut texels = Vec::new();
            texels
                .try_reserve_exact(l.texels.len())
                .map_err(|_| OutOfMemory::of::<LeanMoments>("a texture unit's LEAN moments", l.texels.len()))?;
            texels.extend_from_slice(&l.texels);
            levels.push(MomentLevel { width: l.width, height: l.height, texels });
        }
        Ok(Self { levels })
    }

    /// The filtered moments at lanes `0..n` of (s, t, λ), into `out[0..6]` in
    /// [`LeanMoments::to_array`]'s order.
    pub fn sample_lanes(&self, sampler: &Sampler, coords: &[Lanes; 3], n: usize, out: &mut [Lanes; 6]) {
        let [s, t, lambda] = coords;
        for j in 0..n {
            let m = sample_levels(&self.levels, sampler, s[j], t[j], lambda[j]).to_array();
            for (c, v) in m.into_iter().enumerate() {
                out[c][j] = v;
            }
        }
    }
}

impl Filter for MomentLevel {
    type Value = LeanMoments;

    #[inline(always)]
    fn nearest(&self, s: f32, t: f32, sampler: &Sampler) -> LeanMoments {
        let (i, j) = (nearest_index(s, self.width, sampler.wrap_s), nearest_index(t, self.height, sampler.wrap_t));
        self.texels[j * self.width + i]
    }

    #[inline(always)]
    fn linear(&self, s: f32, t: f32, sampler: &Sampler) -> LeanMoments {
        let (i0, i1, a) = linear_indices(s, self.width, sampler.wrap_s);
        let (j0, j1, b) = linear_indices(t, self.height, sampler.wrap_t);
        let (r0, r1) = (j0 * self.width, j1 * self.width);
        let w = bilinear_weights(a, b);
        self.texels[r0 + i0] * w[0]
            + self.texels[r0 + i1] * w[1]
            + self.texels[r1 + i0] * w[2]
            + self.texels[r1 + i1] * w[3]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpmap_math::{Encoding, Rgba8Mips};
    use glam::{Vec2, Vec3};

    /// A 4×1 moment texture whose texel i has Bx = i, and its 2×1 and 1×1 levels.
    fn ramp() -> MomentTexture {
        let level = |w: usize, xs: &[f32]| MomentLevel {
            width: w,
            height: 1,
            texels: xs
                .iter()
                .map(|&x| LeanMoments { b: Vec2::new(x, 0.0), m: Vec3::new(x * x, 0.0, 0.0), j: 1.0 })
                .collect(),
        };
        MomentTexture { levels: vec![level(4, &[0.0, 1.0, 2.0, 3.0]), level(2, &[0.5, 2.5]), level(1, &[1.5])] }
    }

    #[test]
    fn linear_blends_neighbours_and_trilinear_blends_levels_as_the_8_bit_units_do() {
        let tex = ramp();
        let s = Sampler::LINEAR_REPEAT;
        let at = |x: f32, lambda: f32| sample_levels(&tex.levels, &s, x, 0.5, lambda);
        assert_eq!(at(1.5 / 4.0, 0.0).b.x, 1.0);
        assert_eq!(at(2.0 / 4.0, 0.0).b.x, 1.5);
        // REPEAT: s = 0 lies between the last texel and the first.
        assert_eq!(at(0.0, 0.0).b.x, 1.5);
        // Halfway between level 1 (at its texel 0's centre) and level 2.
        let at = |x: f32, lambda: f32| sample_levels(&tex.levels, &Sampler::TRILINEAR_REPEAT, x, 0.5, lambda);
        let mid = at(0.25, 1.5).b.x;
        assert!((mid - (0.5 * 0.5 + 1.5 * 0.5)).abs() < 1e-6, "{mid}");
        // Past the last level: the 1×1 level.
        assert_eq!(at(0.9, 7.0).b.x, 1.5);
    }

    #[test]
    fn a_texture_from_a_normal_map_keeps_its_levels() {
        let level0 = bumpmap_math::Rgba8Image::new(4, 4, vec![[200, 128, 230, 255]; 16]);
        let mips = Rgba8Mips::with_box_mipmaps(level0);
        let lean = LeanMips::from_normal_map(&mips, Encoding::Unorm).unwrap();
        let tex = MomentTexture::try_from_mips(&lean).unwrap();
        assert_eq!(tex.levels.len(), 3);
        let want = lean.levels[2].texel(0, 0);
        let got = sample_levels(&tex.levels, &Sampler::TRILINEAR_REPEAT, 0.3, 0.7, 5.0);
        assert!((got.b - want.b).abs().max_element() < 1e-6 && (got.m - want.m).abs().max_element() < 1e-6);
    }
}
