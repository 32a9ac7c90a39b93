//! The GeForce pixel path as a fragment shader: up to four texture units feeding the register
//! combiners.
//!
//! Each unit reads its coordinates from named varyings, samples a 2D texture (λ from the quad's
//! derivatives, once per quad) or a cube map, and loads `TEXTURE<i>`; SPARE0's alpha starts as
//! texture 0's alpha, PRIMARY_COLOR is white and SECONDARY_COLOR black (the techniques here do
//! not use per-vertex colour); then the combiners run over the whole batch.

use std::sync::Arc;

use glam::Vec3;

use crate::combiners::{Combiners, LANES, Lanes, Register, RegisterFile};
use crate::raster::{FragmentBatch, FragmentShader};
use crate::texture::{Sampler, Texture2d, TextureCube, lambda_2d, sample_2d, sample_cube};

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
}

/// Per-thread working memory: the register file and the compacted output colours.
pub struct Scratch {
    regs: Box<RegisterFile>,
    colors: Box<[Lanes; 4]>,
}

impl FragmentShader for FixedFunction {
    type Scratch = Scratch;

    fn scratch(&self) -> Scratch {
        Scratch { regs: RegisterFile::new(), colors: Box::new([[0.0; LANES]; 4]) }
    }

    fn shade(&self, batch: &FragmentBatch, scratch: &mut Scratch, out: &mut [Lanes; 4]) {
        debug_assert!(self.units.len() <= 4);
        let Scratch { regs, colors } = scratch;
        // λ needs the whole quad; everything after it runs on the live lanes only, packed.
        let mut live = [0u8; LANES];
        let mut n = 0;
        for lane in 0..batch.lanes() {
            if batch.live[lane] {
                live[n] = lane as u8;
                n += 1;
            }
        }
        let live = &live[..n];
        for (i, unit) in self.units.iter().enumerate() {
            let reg = regs.reg_mut(Register::texture(i));
            match &unit.binding {
                Binding::TwoD { texture, s, t } => {
                    let (sv, tv) = (&batch.varyings[*s], &batch.varyings[*t]);
                    let mut lambda = [0f32; LANES / 4];
                    for (q, l) in lambda.iter_mut().enumerate().take(batch.quads) {
                        let b = 4 * q;
                        *l = lambda_2d(texture, [sv[b], sv[b + 1], sv[b + 2]], [tv[b], tv[b + 1], tv[b + 2]]);
                    }
                    for (j, &lane) in live.iter().enumerate() {
                        let lane = lane as usize;
                        let c = sample_2d(texture, &unit.sampler, sv[lane], tv[lane], lambda[lane / 4]);
                        for ch in 0..4 {
                            reg[ch][j] = c[ch];
                        }
                    }
                }
                Binding::Cube { texture, r } => {
                    let (x, y, z) = (&batch.varyings[*r], &batch.varyings[r + 1], &batch.varyings[r + 2]);
                    for (j, &lane) in live.iter().enumerate() {
                        let lane = lane as usize;
                        // A normalization cube map has one level: λ does not matter.
                        let c = sample_cube(texture, &unit.sampler, Vec3::new(x[lane], y[lane], z[lane]), 0.0);
                        for ch in 0..4 {
                            reg[ch][j] = c[ch];
                        }
                    }
                }
            }
        }
        let tex0_alpha: Lanes =
            if self.units.is_empty() { [0.0; LANES] } else { regs.regs[Register::Texture0 as usize][3] };
        regs.reg_mut(Register::Spare0)[3][..n].copy_from_slice(&tex0_alpha[..n]);
        for c in 0..4 {
            regs.reg_mut(Register::PrimaryColor)[c][..n].fill(1.0);
            regs.reg_mut(Register::SecondaryColor)[c][..n].fill(0.0);
        }
        self.combiners.load_constants(regs, n);
        self.combiners.run(regs, n, colors);
        for (j, &lane) in live.iter().enumerate() {
            for c in 0..4 {
                out[c][lane as usize] = colors[c][j];
            }
        }
    }
}
