//! Texture sampling for a whole batch of fragments at once: coordinates in, RGBA out, both as
//! structure-of-arrays lanes, which is what the register combiners and the single-pass shader
//! consume.
//!
//! The results are those of [`sample_2d`] and [`sample_cube`] lane by lane, bit for bit: the
//! 8-wide path (AVX2 builds) performs the same float operations in the same order, only eight
//! lanes at a time, with the four bilinear taps fetched by gathers. It covers what the
//! techniques bind: LINEAR and LINEAR_MIPMAP_LINEAR 2D textures, and single-level square cube
//! maps with a LINEAR magnification filter. Everything else, and any group of eight lanes whose
//! λ selects different mip levels, takes the scalar path.

use glam::Vec3;

use super::{Sampler, Texture2d, TextureCube, sample_2d, sample_cube};
use crate::combiners::{LANES, Lanes};

/// Samples `tex` at lanes `0..n` of (s, t) with the per-lane level of detail `lambda`, writing
/// R, G, B, A into `out[0..4][0..n]`. Lanes from `n` up to the next multiple of eight may be
/// overwritten with anything.
pub fn sample_2d_lanes(
    tex: &Texture2d,
    sampler: &Sampler,
    s: &Lanes,
    t: &Lanes,
    lambda: &Lanes,
    n: usize,
    out: &mut [Lanes; 4],
) {
    debug_assert!(n <= LANES);
    // SAFETY: AVX2 and FMA are enabled at compile time (the cfg).
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma"))]
    let first_scalar = unsafe { avx2::sample_2d(tex, sampler, s, t, lambda, n, out) };
    #[cfg(not(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma")))]
    let first_scalar = 0;
    for lane in first_scalar..n {
        put(out, lane, sample_2d(tex, sampler, s[lane], t[lane], lambda[lane]));
    }
}

/// Stores one RGBA sample at `lane`.
#[inline(always)]
fn put(out: &mut [Lanes; 4], lane: usize, c: glam::Vec4) {
    for ch in 0..4 {
        out[ch][lane] = c[ch];
    }
}

/// Samples the cube map `tex` (level of detail 0) in the directions (x, y, z) of lanes `0..n`,
/// writing R, G, B, A into `out[0..4][0..n]`. Lanes from `n` up to the next multiple of eight
/// may be overwritten with anything.
pub fn sample_cube_lanes(tex: &TextureCube, sampler: &Sampler, dir: [&Lanes; 3], n: usize, out: &mut [Lanes; 4]) {
    debug_assert!(n <= LANES);
    // SAFETY: AVX2 and FMA are enabled at compile time (the cfg).
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma"))]
    let first_scalar = unsafe { avx2::sample_cube(tex, sampler, dir, n, out) };
    #[cfg(not(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma")))]
    let first_scalar = 0;
    let [x, y, z] = dir;
    for lane in first_scalar..n {
        put(out, lane, sample_cube(tex, sampler, Vec3::new(x[lane], y[lane], z[lane]), 0.0));
    }
}

#[cfg(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma"))]
mod avx2 {
    // Every function here runs only in AVX2 builds; the unsafe operations are the intrinsics,
    // the loads and stores within `Lanes`, and gathers whose indices are clamped in range.
    #![allow(unsafe_op_in_unsafe_fn)]
    use std::arch::x86_64::*;

    use super::super::{Level, MagFilter, MinFilter, WrapMode};
    use super::*;

    /// Whether the 8-wide path reproduces `sampler` on a 2D texture.
    fn fast_2d(sampler: &Sampler) -> bool {
        sampler.mag == MagFilter::Linear && matches!(sampler.min, MinFilter::Linear | MinFilter::LinearMipmapLinear)
    }

    /// Whether the 8-wide path reproduces `sampler` on a cube map: its faces are sampled at λ = 0,
    /// which is magnification, so only the magnification filter matters, and the wrap mode in s
    /// that the packed faces were padded for (CLAMP_TO_EDGE).
    fn fast_cube(tex: &TextureCube, sampler: &Sampler) -> bool {
        sampler.mag == MagFilter::Linear && sampler.wrap_s == WrapMode::ClampToEdge && tex.packed.is_some()
    }

    /// What `Level` exposes to the 8-wide path.
    impl Level {
        fn texel_words(&self) -> *const i32 {
            self.texels.as_ptr().cast()
        }

        fn repeat_row_words(&self) -> *const i32 {
            self.repeat_rows.as_ptr().cast()
        }
    }

    /// One axis of a LINEAR lookup for eight lanes: the two texel indices and the weight of the
    /// second, exactly as `linear_indices` computes them.
    #[inline(always)]
    unsafe fn axis(coord: __m256, size: usize, wrap: WrapMode) -> (__m256i, __m256i, __m256) {
        let nf = _mm256_set1_ps(size as f32);
        let half = _mm256_set1_ps(0.5);
        let u = match wrap {
            WrapMode::Repeat => _mm256_sub_ps(_mm256_mul_ps(_mm256_sub_ps(coord, _mm256_floor_ps(coord)), nf), half),
            WrapMode::ClampToEdge => {
                let c = _mm256_min_ps(_mm256_max_ps(_mm256_mul_ps(coord, nf), half), _mm256_sub_ps(nf, half));
                _mm256_sub_ps(c, half)
            }
            WrapMode::MirroredRepeat => {
                // WrapMode::mirror, then CLAMP_TO_EDGE: 1 − |s − 2·floor(s/2) − 1|.
                let one = _mm256_set1_ps(1.0);
                let t = _mm256_sub_ps(
                    coord,
                    _mm256_mul_ps(_mm256_set1_ps(2.0), _mm256_floor_ps(_mm256_mul_ps(coord, half))),
                );
                let d = _mm256_sub_ps(t, one);
                let folded = _mm256_sub_ps(one, _mm256_andnot_ps(_mm256_set1_ps(-0.0), d));
                let c = _mm256_min_ps(_mm256_max_ps(_mm256_mul_ps(folded, nf), half), _mm256_sub_ps(nf, half));
                _mm256_sub_ps(c, half)
            }
        };
        let f = _mm256_floor_ps(u);
        let a = _mm256_sub_ps(u, f);
        let i = _mm256_cvttps_epi32(f);
        let last = _mm256_set1_epi32(size as i32 - 1);
        let one = _mm256_set1_epi32(1);
        match wrap {
            WrapMode::Repeat => {
                // i < 0 (or a NaN's 0x80000000) wraps to the last texel; the next one wraps to 0.
                let i0 =
                    _mm256_blendv_epi8(_mm256_min_epi32(i, last), last, _mm256_cmpgt_epi32(_mm256_setzero_si256(), i));
                let i1 = _mm256_andnot_si256(_mm256_cmpeq_epi32(i0, last), _mm256_add_epi32(i0, one));
                (i0, i1, a)
            }
            WrapMode::ClampToEdge | WrapMode::MirroredRepeat => {
                let i0 = _mm256_min_epi32(_mm256_max_epi32(i, _mm256_setzero_si256()), last);
                (i0, _mm256_min_epi32(_mm256_add_epi32(i0, one), last), a)
            }
        }
    }

    /// The four channels of eight texels, as floats in [0, 255]: one byte shuffle per channel
    /// moves byte c of each texel to the bottom of its 32-bit lane.
    #[inline(always)]
    unsafe fn unpack(words: __m256i) -> [__m256; 4] {
        let z = -1i8; // a shuffle index with the top bit set writes 0
        let pick = |c: i8| {
            _mm256_setr_epi8(
                c,
                z,
                z,
                z,
                c + 4,
                z,
                z,
                z,
                c + 8,
                z,
                z,
                z,
                c + 12,
                z,
                z,
                z, //
                c,
                z,
                z,
                z,
                c + 4,
                z,
                z,
                z,
                c + 8,
                z,
                z,
                z,
                c + 12,
                z,
                z,
                z,
            )
        };
        let ch = |c: i8| _mm256_cvtepi32_ps(_mm256_shuffle_epi8(words, pick(c)));
        [ch(0), ch(1), ch(2), _mm256_cvtepi32_ps(_mm256_srli_epi32(words, 24))]
    }

    /// Where a bilinear lookup's texels come from: `words`, with texel (0, 0) of the image at
    /// word `base` (per lane) and rows either as stored or padded by [`pad_rows`] for the
    /// sampler's wrap mode in s.
    #[derive(Clone, Copy)]
    struct Image {
        words: *const i32,
        base: __m256i,
        width: usize,
        height: usize,
        padded: bool,
    }

    impl Image {
        /// A level for `sampler`: padded rows when they were made for its wrap mode in s.
        unsafe fn level(l: &Level, sampler: &Sampler) -> Self {
            let padded = sampler.wrap_s == WrapMode::Repeat;
            let words = if padded { l.repeat_row_words() } else { l.texel_words() };
            Image { words, base: _mm256_setzero_si256(), width: l.width, height: l.height, padded }
        }
    }

    /// The texels at word offsets `index` and `index + 1` of `words` for eight lanes: two
    /// 64-bit gathers instead of two 32-bit ones, which halves the loads.
    #[inline(always)]
    unsafe fn texel_pairs(words: *const i32, index: __m256i) -> (__m256i, __m256i) {
        let pairs = |idx: __m128i| _mm256_castsi256_ps(_mm256_i32gather_epi64::<4>(words.cast(), idx));
        let (lo, hi) = (pairs(_mm256_castsi256_si128(index)), pairs(_mm256_extracti128_si256::<1>(index)));
        // Even words are the first texels, odd words the second, in the 64-bit order 0 2 1 3.
        let order = |v: __m256| _mm256_permute4x64_epi64::<0b11_01_10_00>(_mm256_castps_si256(v));
        (order(_mm256_shuffle_ps::<0b10_00_10_00>(lo, hi)), order(_mm256_shuffle_ps::<0b11_01_11_01>(lo, hi)))
    }

    /// The four texels of eight lanes' bilinear lookups, as fetched (RGBA8 words), and the
    /// weights of the second column and row: what [`filter`] needs. Fetching is split from
    /// filtering so that a trilinear lookup's eight gathers are all issued before either
    /// level's arithmetic waits on them.
    #[derive(Clone, Copy)]
    struct Taps {
        t00: __m256i,
        t10: __m256i,
        t01: __m256i,
        t11: __m256i,
        a: __m256,
        b: __m256,
    }

    /// The gathers of a bilinear lookup of eight lanes on `image`.
    #[inline(always)]
    unsafe fn fetch(image: Image, sampler: &Sampler, s: __m256, t: __m256) -> Taps {
        let (i0, i1, a) = axis(s, image.width, sampler.wrap_s);
        let (j0, j1, b) = axis(t, image.height, sampler.wrap_t);
        let stride = _mm256_set1_epi32((image.width + image.padded as usize) as i32);
        let r0 = _mm256_add_epi32(image.base, _mm256_mullo_epi32(j0, stride));
        let r1 = _mm256_add_epi32(image.base, _mm256_mullo_epi32(j1, stride));
        let words = image.words;
        if image.padded {
            // Padded rows hold texel i1 right after i0.
            let (t00, t10) = texel_pairs(words, _mm256_add_epi32(r0, i0));
            let (t01, t11) = texel_pairs(words, _mm256_add_epi32(r1, i0));
            Taps { t00, t10, t01, t11, a, b }
        } else {
            let tap = |row: __m256i, col: __m256i| _mm256_i32gather_epi32::<4>(words, _mm256_add_epi32(row, col));
            Taps { t00: tap(r0, i0), t10: tap(r0, i1), t01: tap(r1, i0), t11: tap(r1, i1), a, b }
        }
    }

    /// `Level::linear`'s arithmetic on fetched taps: the weighted sum by fused multiply-adds in
    /// byte units, then 1/255.
    #[inline(always)]
    unsafe fn filter(taps: Taps) -> [__m256; 4] {
        let Taps { t00, t10, t01, t11, a, b } = taps;
        let (t00, t10, t01, t11) = (unpack(t00), unpack(t10), unpack(t01), unpack(t11));
        let one = _mm256_set1_ps(1.0);
        let (ca, cb) = (_mm256_sub_ps(one, a), _mm256_sub_ps(one, b));
        let w = [_mm256_mul_ps(ca, cb), _mm256_mul_ps(a, cb), _mm256_mul_ps(ca, b), _mm256_mul_ps(a, b)];
        let k = _mm256_set1_ps(1.0 / 255.0);
        let mut out = [_mm256_setzero_ps(); 4];
        for c in 0..4 {
            let v = _mm256_mul_ps(t00[c], w[0]);
            let v = _mm256_fmadd_ps(t10[c], w[1], v);
            let v = _mm256_fmadd_ps(t01[c], w[2], v);
            let v = _mm256_fmadd_ps(t11[c], w[3], v);
            out[c] = _mm256_mul_ps(v, k);
        }
        out
    }

    /// Bilinear filtering of eight lanes on `image`: `Level::linear`'s arithmetic, eight lanes at
    /// a time.
    #[inline(always)]
    unsafe fn bilinear(image: Image, sampler: &Sampler, s: __m256, t: __m256) -> [__m256; 4] {
        filter(fetch(image, sampler, s, t))
    }

    #[inline(always)]
    unsafe fn store(out: &mut [Lanes; 4], lane: usize, v: [__m256; 4]) {
        for c in 0..4 {
            _mm256_storeu_ps(out[c].as_mut_ptr().add(lane), v[c]);
        }
    }

    #[inline(always)]
    unsafe fn load(v: &Lanes, lane: usize) -> __m256 {
        _mm256_loadu_ps(v.as_ptr().add(lane))
    }

    /// Eight lanes at a time; returns the first lane left to the scalar path (groups whose
    /// levels differ are done here lane by lane).
    pub(super) unsafe fn sample_2d(
        tex: &Texture2d,
        sampler: &Sampler,
        s: &Lanes,
        t: &Lanes,
        lambda: &Lanes,
        n: usize,
        out: &mut [Lanes; 4],
    ) -> usize {
        if !fast_2d(sampler) {
            return 0;
        }
        let q = tex.levels.len() - 1;
        let mipmapped = sampler.min == MinFilter::LinearMipmapLinear && q > 0;
        let qf = _mm256_set1_ps(q as f32);
        let zero = _mm256_setzero_ps();
        for lane in (0..n).step_by(8) {
            let (sv, tv) = (load(s, lane), load(t, lane));
            if !mipmapped {
                // LINEAR (or a single level): level 0, bilinear, whatever λ is.
                store(out, lane, bilinear(Image::level(&tex.levels[0], sampler), sampler, sv, tv));
                continue;
            }
            // GL 1.2 §3.8.8: λ ≤ 0 magnifies (level 0); λ ≥ q uses level q; in between, levels
            // ⌊λ⌋ and ⌊λ⌋ + 1 blended by the fraction.
            let lam = load(lambda, lane);
            let minify = _mm256_cmp_ps::<_CMP_GT_OQ>(lam, zero);
            let below_last = _mm256_cmp_ps::<_CMP_LT_OQ>(lam, qf);
            let d = _mm256_and_ps(_mm256_floor_ps(_mm256_min_ps(lam, qf)), minify);
            let f = _mm256_and_ps(_mm256_sub_ps(lam, _mm256_floor_ps(lam)), _mm256_and_ps(minify, below_last));
            let d0 = _mm256_cvtss_f32(d);
            let ordered = _mm256_cmp_ps::<_CMP_ORD_Q>(lam, lam);
            let same = _mm256_movemask_ps(_mm256_and_ps(_mm256_cmp_ps::<_CMP_EQ_OQ>(d, _mm256_set1_ps(d0)), ordered));
            let live = if n - lane >= 8 { 0xff } else { (1 << (n - lane)) - 1 };
            if same & live != live {
                // Levels differ (or λ is NaN): lane by lane.
                for k in lane..(lane + 8).min(n) {
                    put(out, k, super::sample_2d(tex, sampler, s[k], t[k], lambda[k]));
                }
                continue;
            }
            let d = d0 as usize;
            let taps1 = fetch(Image::level(&tex.levels[d], sampler), sampler, sv, tv);
            if _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(f, zero)) & live == 0 {
                store(out, lane, filter(taps1));
                continue;
            }
            // Both levels' gathers before either level's arithmetic.
            let taps2 = fetch(Image::level(&tex.levels[(d + 1).min(q)], sampler), sampler, sv, tv);
            let (t1, t2) = (filter(taps1), filter(taps2));
            let g = _mm256_sub_ps(_mm256_set1_ps(1.0), f);
            let mut v = [zero; 4];
            for c in 0..4 {
                v[c] = _mm256_add_ps(_mm256_mul_ps(t1[c], g), _mm256_mul_ps(t2[c], f));
            }
            store(out, lane, v);
        }
        n
    }

    /// Table 1 face selection and bilinear filtering within the face, eight lanes at a time.
    pub(super) unsafe fn sample_cube(
        tex: &TextureCube,
        sampler: &Sampler,
        dir: [&Lanes; 3],
        n: usize,
        out: &mut [Lanes; 4],
    ) -> usize {
        if !fast_cube(tex, sampler) {
            return 0;
        }
        let packed = tex.packed.as_deref().expect("checked by fast_cube");
        let size = tex.faces[0].width();
        let words: *const i32 = packed.as_ptr().cast();
        let sign = _mm256_set1_ps(-0.0);
        let face_words = _mm256_set1_epi32((size * (size + 1)) as i32);
        let (half, one) = (_mm256_set1_ps(0.5), _mm256_set1_ps(1.0));
        for lane in (0..n).step_by(8) {
            let (x, y, z) = (load(dir[0], lane), load(dir[1], lane), load(dir[2], lane));
            let (ax, ay, az) = (_mm256_andnot_ps(sign, x), _mm256_andnot_ps(sign, y), _mm256_andnot_ps(sign, z));
            let ge = |p: __m256, q: __m256| _mm256_cmp_ps::<_CMP_GE_OQ>(p, q);
            let sel = |m: __m256, p: __m256, q: __m256| _mm256_blendv_ps(q, p, m);
            let neg = |v: __m256| _mm256_xor_ps(v, sign);
            // CubeFace::select's branches as masks: x-major, else y-major, else z-major.
            let x_major = _mm256_and_ps(ge(ax, ay), ge(ax, az));
            let y_major = _mm256_andnot_ps(x_major, ge(ay, az));
            let z_major = _mm256_andnot_ps(_mm256_or_ps(x_major, y_major), _mm256_castsi256_ps(_mm256_set1_epi32(-1)));
            let zero = _mm256_setzero_ps();
            let (px, py, pz) = (ge(x, zero), ge(y, zero), ge(z, zero));
            let sc_x = sel(px, neg(z), z);
            let sc_y = x;
            let sc_z = sel(pz, x, neg(x));
            let tc_x = neg(y);
            let tc_y = sel(py, z, neg(z));
            let tc_z = neg(y);
            let sc = sel(x_major, sc_x, sel(y_major, sc_y, sc_z));
            let tc = sel(x_major, tc_x, sel(y_major, tc_y, tc_z));
            let ma = sel(x_major, ax, sel(y_major, ay, az));
            // Faces in GL order: +X −X +Y −Y +Z −Z.
            let face_of = |m: __m256, pos: __m256, first: i32| {
                let f = _mm256_blendv_epi8(
                    _mm256_set1_epi32(first + 1),
                    _mm256_set1_epi32(first),
                    _mm256_castps_si256(pos),
                );
                _mm256_and_si256(f, _mm256_castps_si256(m))
            };
            let face = _mm256_or_si256(
                _mm256_or_si256(face_of(x_major, px, 0), face_of(y_major, py, 2)),
                face_of(z_major, pz, 4),
            );
            let valid = _mm256_and_ps(
                _mm256_cmp_ps::<_CMP_GT_OQ>(ma, zero),
                _mm256_cmp_ps::<_CMP_LT_OQ>(ma, _mm256_set1_ps(f32::INFINITY)),
            );
            let s = _mm256_mul_ps(half, _mm256_add_ps(_mm256_div_ps(sc, ma), one));
            let t = _mm256_mul_ps(half, _mm256_add_ps(_mm256_div_ps(tc, ma), one));
            let base = _mm256_mullo_epi32(face, face_words);
            let v = bilinear(Image { words, base, width: size, height: size, padded: true }, sampler, s, t);
            store(out, lane, v.map(|c| _mm256_and_ps(c, valid)));
        }
        n
    }
}

#[cfg(test)]
mod tests {
    use bumpmap_math::{Encoding, NormalizationCubeMap};
    use proptest::prelude::*;

    use super::super::{MagFilter, MinFilter, WrapMode};
    use super::*;

    /// A texture with a full box-filtered mip chain whose texels differ in every channel.
    fn noisy(w: usize, h: usize) -> Texture2d {
        let texels = (0..w * h)
            .map(|i| {
                let x = (i as u32).wrapping_mul(2_654_435_761);
                x.to_le_bytes()
            })
            .collect();
        Texture2d::from_mips(&bumpmap_math::Rgba8Mips::with_box_mipmaps(bumpmap_math::Rgba8Image::new(w, h, texels)))
    }

    fn same_bits(batch: &[Lanes; 4], lane: usize, scalar: glam::Vec4) -> bool {
        (0..4).all(|c| batch[c][lane].to_bits() == scalar[c].to_bits())
    }

    const SAMPLERS: [Sampler; 5] = [
        Sampler::TRILINEAR_REPEAT,
        Sampler::LINEAR_REPEAT,
        Sampler {
            min: MinFilter::LinearMipmapLinear,
            mag: MagFilter::Linear,
            wrap_s: WrapMode::ClampToEdge,
            wrap_t: WrapMode::Repeat,
        },
        Sampler {
            min: MinFilter::LinearMipmapLinear,
            mag: MagFilter::Linear,
            wrap_s: WrapMode::MirroredRepeat,
            wrap_t: WrapMode::MirroredRepeat,
        },
        Sampler {
            min: MinFilter::Linear,
            mag: MagFilter::Linear,
            wrap_s: WrapMode::Repeat,
            wrap_t: WrapMode::MirroredRepeat,
        },
    ];

    proptest! {
        /// The batch path must be the scalar path, bit for bit: both do the same float
        /// operations in the same order, so no tolerance.
        #[test]
        fn batch_2d_equals_scalar(
            coords in prop::collection::vec((-3.0f32..3.0, -3.0f32..3.0), LANES),
            lambda_base in -2.0f32..12.0,
            spread in prop::sample::select(vec![0.0f32, 0.3, 4.0]),
            n in 0usize..=LANES,
            which in 0usize..SAMPLERS.len(),
            size in prop::sample::select(vec![(64usize, 64usize), (37, 5), (1, 1)]),
        ) {
            let tex = noisy(size.0, size.1);
            let sampler = SAMPLERS[which];
            let mut s = [0.0; LANES];
            let mut t = [0.0; LANES];
            let mut lambda = [0.0; LANES];
            for (i, &(a, b)) in coords.iter().enumerate() {
                s[i] = a;
                t[i] = b;
                lambda[i] = lambda_base + spread * ((i % 7) as f32 / 7.0);
            }
            // Exact level boundaries and the special values take their own branches.
            lambda[0] = lambda_base.floor();
            lambda[1] = f32::NEG_INFINITY;
            lambda[2] = f32::INFINITY;
            let mut out = [[0.0; LANES]; 4];
            sample_2d_lanes(&tex, &sampler, &s, &t, &lambda, n, &mut out);
            for lane in 0..n {
                let scalar = sample_2d(&tex, &sampler, s[lane], t[lane], lambda[lane]);
                prop_assert!(same_bits(&out, lane, scalar), "lane {lane}: {:?} vs {scalar}", out.map(|c| c[lane]));
            }
        }

        #[test]
        fn batch_cube_equals_scalar(dirs in prop::collection::vec((-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0), LANES)) {
            let cube = TextureCube::from_normalization(&NormalizationCubeMap::new(32, Encoding::Kilgard));
            let mut d = [[0.0; LANES]; 3];
            for (i, &(x, y, z)) in dirs.iter().enumerate() {
                d[0][i] = x;
                d[1][i] = y;
                d[2][i] = z;
            }
            // The zero vector (transparent black) and exact ties between axes.
            d[0][0] = 0.0;
            d[1][0] = 0.0;
            d[2][0] = 0.0;
            d[0][1] = 1.0;
            d[1][1] = -1.0;
            d[2][1] = 1.0;
            let mut out = [[0.0; LANES]; 4];
            sample_cube_lanes(&cube, &Sampler::LINEAR_CLAMP, [&d[0], &d[1], &d[2]], LANES, &mut out);
            for lane in 0..LANES {
                let scalar = sample_cube(&cube, &Sampler::LINEAR_CLAMP, Vec3::new(d[0][lane], d[1][lane], d[2][lane]), 0.0);
                prop_assert!(same_bits(&out, lane, scalar), "lane {lane}: {:?} vs {scalar}", out.map(|c| c[lane]));
            }
        }
    }
}
