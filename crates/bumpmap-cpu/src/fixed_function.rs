//! The GeForce pixel path as a fragment shader: up to four texture units feeding the register
//! combiners.
//!
//! Each unit reads its coordinates from named varyings, samples a 2D texture (λ from the quad's
//! derivatives, once per quad) or a cube map, and loads `TEXTURE<i>`; SPARE0's alpha starts as
//! texture 0's alpha, PRIMARY_COLOR is the interpolated vertex colour where the pass asks for
//! it and white otherwise, SECONDARY_COLOR black; then the combiners run over the whole batch.

use std::sync::Arc;

use crate::combiners::{Combiners, LANES, Lanes, Register, RegisterFile};
use crate::raster::{FragmentBatch, FragmentShader};
use crate::texture::{Sampler, Texture2d, TextureCube, lambda_from_rho2, sample_2d_lanes, sample_cube_lanes};

/// What a texture unit has bound.
#[derive(Clone, Debug)]
pub enum Binding {
    /// A 2D texture addressed by (s, t) = varyings `[s, t]`.
    TwoD { texture: Arc<Texture2d>, s: usize, t: usize },
    /// A cube map addressed by the direction in varyings `[r, r+1, r+2]`.
    Cube { texture: Arc<TextureCube>, r: usize },
}

/// One enabled texture unit.
#[derive(Clone, Debug)]
pub struct TextureUnit {
    pub binding: Binding,
    pub sampler: Sampler,
}

/// Texture units 0..n (at most four) and the combiner setup of one pass.
#[derive(Clone, Debug)]
pub struct FixedFunction {
    pub units: Vec<TextureUnit>,
    pub combiners: Combiners,
    /// The first of four varying slots holding PRIMARY_COLOR (RGBA), or `None`: white.
    pub primary_color: Option<usize>,
}

/// Per-thread working memory: the register file and packed texture coordinates.
pub struct Scratch {
    regs: Box<RegisterFile>,
    coords: Box<[Lanes; 3]>,
}

/// PRIMARY_COLOR white and SECONDARY_COLOR black in lanes `0..n`.
fn load_colors(regs: &mut RegisterFile, n: usize) {
    for c in 0..4 {
        regs.reg_mut(Register::PrimaryColor)[c][..n].fill(1.0);
        regs.reg_mut(Register::SecondaryColor)[c][..n].fill(0.0);
    }
}

/// Packs the coordinates of a 2D lookup for a batch's live lanes: `scale ⊙ (s, t)` from
/// varyings `slots` into `out[0]`, `out[1]`, and λ (from each quad's derivatives, GL 1.2
/// Eq. 3.14) into `out[2]`.
pub(crate) fn pack_2d_coords(
    tex: &Texture2d,
    batch: &FragmentBatch,
    slots: [usize; 2],
    scale: [f32; 2],
    out: &mut [Lanes; 3],
) {
    let (s, t) = (&batch.varyings[slots[0]], &batch.varyings[slots[1]]);
    let [ps, pt, pl] = out;
    // ρ² of each quad on its four lanes, packed like a varying; λ only for the live lanes.
    let mut rho2 = [0f32; LANES];
    quad_rho2(tex, s, t, scale, batch.lanes(), &mut rho2);
    batch.pack_lanes(&rho2, pl);
    batch.pack(slots[0], ps);
    batch.pack(slots[1], pt);
    let n = batch.live().len().next_multiple_of(8).min(LANES);
    let [ks, kt] = scale;
    for j in 0..n {
        ps[j] *= ks;
        pt[j] *= kt;
        pl[j] = lambda_from_rho2(pl[j]);
    }
}

/// [`rho2_2d`] of each quad of `scale ⊙ (s, t)` in lanes `0..lanes`, on all four of its lanes.
/// The AVX2 path takes two quads per vector (one per 128-bit half, where in-lane shuffles pick
/// the quad's pixels 0, 1 and 2) with the scalar function's operations in its order, so both
/// give the same bits.
fn quad_rho2(tex: &Texture2d, s: &Lanes, t: &Lanes, [ks, kt]: [f32; 2], lanes: usize, out: &mut Lanes) {
    debug_assert!(lanes <= LANES && lanes.is_multiple_of(4));
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
    {
        use std::arch::x86_64::*;
        let (w, h) = (tex.width() as f32, tex.height() as f32);
        for i in (0..lanes).step_by(8) {
            // SAFETY: AVX2 is enabled at compile time (the cfg); i + 8 ≤ LANES because i < lanes ≤
            // LANES and LANES is a multiple of 8, so the loads and the store stay in the arrays.
            unsafe {
                let sv = _mm256_mul_ps(_mm256_set1_ps(ks), _mm256_loadu_ps(s.as_ptr().add(i)));
                let tv = _mm256_mul_ps(_mm256_set1_ps(kt), _mm256_loadu_ps(t.as_ptr().add(i)));
                let (s0, s1, s2) =
                    (_mm256_permute_ps::<0x00>(sv), _mm256_permute_ps::<0x55>(sv), _mm256_permute_ps::<0xaa>(sv));
                let (t0, t1, t2) =
                    (_mm256_permute_ps::<0x00>(tv), _mm256_permute_ps::<0x55>(tv), _mm256_permute_ps::<0xaa>(tv));
                let (wv, hv) = (_mm256_set1_ps(w), _mm256_set1_ps(h));
                let (dudx, dvdx) = (_mm256_mul_ps(_mm256_sub_ps(s1, s0), wv), _mm256_mul_ps(_mm256_sub_ps(t1, t0), hv));
                let (dudy, dvdy) = (_mm256_mul_ps(_mm256_sub_ps(s2, s0), wv), _mm256_mul_ps(_mm256_sub_ps(t2, t0), hv));
                let x = _mm256_add_ps(_mm256_mul_ps(dudx, dudx), _mm256_mul_ps(dvdx, dvdx));
                let y = _mm256_add_ps(_mm256_mul_ps(dudy, dudy), _mm256_mul_ps(dvdy, dvdy));
                _mm256_storeu_ps(out.as_mut_ptr().add(i), _mm256_max_ps(x, y));
            }
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "avx2")))]
    for b in (0..lanes).step_by(4) {
        let rho2 = crate::texture::rho2_2d(
            tex,
            [ks * s[b], ks * s[b + 1], ks * s[b + 2]],
            [kt * t[b], kt * t[b + 1], kt * t[b + 2]],
        );
        out[b..b + 4].fill(rho2);
    }
}

impl FragmentShader for FixedFunction {
    type Scratch = Scratch;

    fn scratch(&self) -> Scratch {
        // Registers the combiners only read are loaded once here, for every lane.
        let mut regs = RegisterFile::new();
        self.combiners.load_constants(&mut regs, LANES);
        load_colors(&mut regs, LANES);
        Scratch { regs, coords: Box::new([[0.0; LANES]; 3]) }
    }

    fn shade(&self, batch: &FragmentBatch, scratch: &mut Scratch, out: &mut [Lanes; 4]) {
        debug_assert!(self.units.len() <= 4);
        let Scratch { regs, coords } = scratch;
        // λ needs the whole quad; everything after it runs on the live lanes only, packed.
        let n = batch.live().len();
        for (i, unit) in self.units.iter().enumerate() {
            let reg = regs.reg_mut(Register::texture(i));
            match &unit.binding {
                Binding::TwoD { texture, s, t } => {
                    pack_2d_coords(texture, batch, [*s, *t], [1.0, 1.0], coords);
                    let [s, t, lambda] = &**coords;
                    sample_2d_lanes(texture, &unit.sampler, s, t, lambda, n, reg);
                }
                Binding::Cube { texture, r } => {
                    for (k, c) in coords.iter_mut().enumerate() {
                        batch.pack(r + k, c);
                    }
                    // A normalization cube map has one level: λ does not matter.
                    let [x, y, z] = &**coords;
                    sample_cube_lanes(texture, &unit.sampler, [x, y, z], n, reg);
                }
            }
        }
        let n8 = n.next_multiple_of(8);
        let (below, textures) = regs.regs.split_at_mut(Register::Texture0 as usize);
        let spare0_alpha = &mut below[Register::Spare0 as usize][3][..n8];
        match self.units.is_empty() {
            true => spare0_alpha.fill(0.0),
            false => spare0_alpha.copy_from_slice(&textures[0][3][..n8]),
        }
        if self.combiners.writes(Register::PrimaryColor) || self.combiners.writes(Register::SecondaryColor) {
            load_colors(regs, n8);
        }
        if let Some(first) = self.primary_color {
            let primary = regs.reg_mut(Register::PrimaryColor);
            for (c, lanes) in primary.iter_mut().enumerate() {
                batch.pack(first + c, lanes);
            }
        }
        self.combiners.run(regs, n, out);
    }
}
