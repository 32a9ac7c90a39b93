//! Techniques as lists of passes: each pass is GL state plus a program, drawn over one object
//! for one light. A backend executes the list in order; it never decides what a technique is.
//!
//! - [`kilgard`]: the paper's three passes, register-combiner programs (Kilgard §5.4–5.6);
//! - [`single_pass`]: the same lighting model in one float pass per light ([`crate::shading`]);
//! - [`emboss`]: the technique the paper replaces (§3.1), register-combiner programs;
//! - [`reference`](mod@reference): ground truth's options (drawn by `bumpmap-reference`, not as passes).
//!
//! Which named technique (`peercy-blinn`, `mip-renormalized`, …) becomes which of these, with
//! which maps, is the catalogue's ([`crate::catalogue`]).
//!
//! Capability checks live here: [`Technique::passes`] refuses what a technique cannot do with
//! a typed [`CoreError`], so every backend refuses the same things.

pub mod emboss;
pub mod kilgard;
mod materials;
pub mod reference;
pub mod single_pass;

use std::sync::Arc;

use bumpmap_math::{Encoding, HeightMips, Rgba8Mips};

use crate::combiners::{CombinerSetup, Precision};
use crate::error::CoreError;
use crate::parallax::Parallax;
use crate::scene::{NormalSpace, Scene, SceneLight};
use crate::state::{PassState, Sampler};
use crate::vertex::var;

pub use emboss::{BackFacing, EmbossOptions};
pub use kilgard::{KilgardOptions, SpecularMode};
pub use reference::ReferenceOptions;
pub use single_pass::{Gloss, HalfAngle, Normalize, SelfShadow, SinglePassOptions, SpecularFilter, SpecularShadow};

/// A technique with its options.
#[derive(Clone, Debug, PartialEq)]
pub enum Technique {
    /// Kilgard's three passes on a GeForce 256 (register combiners, 8-bit framebuffer).
    Kilgard(KilgardOptions),
    /// One float pass per light.
    SinglePass(SinglePassOptions),
    /// Embossing (Kilgard §3.1): two height fetches subtracted, plus L_z.
    Emboss(EmbossOptions),
    /// Ground truth: Blinn's normal on the exact surface, many samples per pixel. Not a pass
    /// list: `bumpmap-reference` draws it.
    Reference(ReferenceOptions),
}

impl Technique {
    /// The technique's name as the papers and the CLI spell it.
    pub fn name(&self) -> &'static str {
        match self {
            Technique::Kilgard(_) => kilgard::NAME,
            Technique::SinglePass(_) => single_pass::NAME,
            Technique::Emboss(_) => emboss::NAME,
            Technique::Reference(_) => reference::NAME,
        }
    }

    /// The passes that render `scene`, in order; the first clears nothing (backends clear to
    /// black, alpha 0, depth 1 before the first pass). Fails when the technique cannot render
    /// the scene as asked, and for [`Technique::Reference`], which is not a pass list.
    ///
    /// Each material's alpha, emission and place in the order are applied here for every
    /// technique alike (`materials`): a cut-out material's depth is laid by its decal's alpha
    /// first, emission is added after its lit passes, and blended materials are drawn last,
    /// the farthest first.
    pub fn passes(&self, scene: &Scene) -> Result<Vec<Pass>, CoreError> {
        let (passes, sampler) = match self {
            Technique::Kilgard(o) => (kilgard::passes(scene, o)?, o.sampler),
            Technique::SinglePass(o) => (single_pass::passes(scene, o)?, o.sampler),
            Technique::Emboss(o) => (emboss::passes(scene, o)?, o.sampler),
            Technique::Reference(_) => return Err(CoreError::NotPasses),
        };
        materials::finish(self.name(), scene, passes, sampler, self.blends())
    }

    /// Whether the technique draws a blended material ([`crate::scene::AlphaMode::Blend`]) over
    /// what is behind it. Only the single pass can: the multipass techniques build each pixel's
    /// colour in the framebuffer itself (the decal, then the lighting multiplied onto it), so
    /// there is no surface colour apart from what is behind to blend; they draw it opaque.
    pub fn blends(&self) -> bool {
        matches!(self, Technique::SinglePass(_))
    }
}

/// One draw of one object for one light.
#[derive(Clone, Debug)]
pub struct Pass {
    /// Index into `Scene::objects`.
    pub object: usize,
    /// Index into `Scene::lights`: whose vertex stage (L, H, …) the pass reads.
    pub light: usize,
    /// A name for the framebuffer after this pass, where a figure shows it (Kilgard Figure 12).
    pub snapshot: Option<&'static str>,
    /// Depth, blend, colour mask, culling.
    pub state: PassState,
    /// What computes each fragment's colour.
    pub program: Program,
}

/// A pass's fragment computation.
#[derive(Clone, Debug)]
pub enum Program {
    /// Texture units feeding NV_register_combiners.
    Combiners(CombinerProgram),
    /// The float lighting model of [`crate::shading`].
    Lit(Box<LitProgram>),
}

impl Program {
    /// How many varyings (from slot 0) the program reads: a backend need not interpolate more.
    pub fn varyings_read(&self) -> usize {
        match self {
            Program::Combiners(c) => {
                let units = c.units.iter().map(|u| u.binding.varyings_read()).max().unwrap_or(0);
                if c.vertex_color { units.max(var::COLOR + 4) } else { units }
            }
            Program::Lit(l) => l.varyings_read(),
        }
    }
}

/// Up to four texture units and the combiner setup they feed.
#[derive(Clone, Debug, PartialEq)]
pub struct CombinerProgram {
    /// Unit i loads register `TEXTURE<i>`.
    pub units: Vec<TextureUnit>,
    /// A setup that [`CombinerSetup::validate`] accepts.
    pub setup: CombinerSetup,
    /// The datapath's precision.
    pub precision: Precision,
    /// Whether `PRIMARY_COLOR` is the interpolated vertex colour ([`var::COLOR`], as
    /// `glColorPointer` feeds it); otherwise white.
    pub vertex_color: bool,
}

/// What a texture unit has bound, and its sampler state.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureUnit {
    /// The texture and the varyings that address it.
    pub binding: Binding,
    /// Filter and wrap modes.
    pub sampler: Sampler,
}

/// A texture and its coordinates.
#[derive(Clone, Debug, PartialEq)]
pub enum Binding {
    /// A 2D texture addressed by (s, t) = varyings `[s, t]`.
    TwoD {
        /// The texture.
        texture: Arc<Rgba8Mips>,
        /// Varying slot of s.
        s: usize,
        /// Varying slot of t.
        t: usize,
    },
    /// The normalization cube map (Kilgard Appendix D) addressed by varyings `[r, r+1, r+2]`.
    NormalizationCube {
        /// Face size in texels.
        size: usize,
        /// How the unit vectors are stored.
        encoding: Encoding,
        /// First varying slot of the direction.
        r: usize,
    },
}

impl Binding {
    /// One past the last varying slot this binding reads.
    pub fn varyings_read(&self) -> usize {
        match self {
            Binding::TwoD { s, t, .. } => s.max(t) + 1,
            Binding::NormalizationCube { r, .. } => r + 3,
        }
    }
}

/// The single pass's program for one object and one light: its material with the light's
/// colour folded in, and the options that shape the model.
#[derive(Clone, Debug, PartialEq)]
pub struct LitProgram {
    /// RGB range-compressed normal (unorm), A = |N'|.
    pub normal_map: Arc<Rgba8Mips>,
    /// Tangent or object space, and the object-space map's coordinate scale.
    pub normal_space: NormalSpace,
    /// Unit normals, or an offset map.
    pub normal_texels: crate::scene::NormalTexels,
    /// The decal; white where `None`.
    pub decal: Option<Arc<Rgba8Mips>>,
    /// Where the gloss comes from.
    pub gloss: Gloss,
    /// The roughness map given for [`SpecularFilter::RoughnessMap`]; `None` with that filter:
    /// the backend samples [`crate::shading::roughness_texture`] of the normal map and the
    /// terms' shininess. Read with the normal map's coordinates and sampler.
    pub roughness_map: Option<Arc<Rgba8Mips>>,
    /// The filtering of the normal map, decal, gloss and occlusion maps (and the detail map's).
    pub sampler: Sampler,
    /// A detail normal map laid over the normal map per fragment, read with the normal map's
    /// coordinates times its repeat ([`crate::detail`]); `None`: none.
    pub detail: Option<crate::detail::DetailLayer>,
    /// What multiplies the ambient term, in red, read with the decal's coordinates
    /// ([`crate::scene::Material::occlusion`]); `None`: 1.
    pub occlusion: Option<Arc<Rgba8Mips>>,
    /// Whether the fragment's alpha is the decal's (a blended material's pass), else 1.
    pub decal_alpha: bool,
    /// Whether the decal (colour and alpha) is multiplied by the interpolated vertex colour
    /// ([`var::COLOR`]); the gloss read from the decal's alpha is the texture's alone.
    pub vertex_color: bool,
    /// The lighting coefficients and switches, per pass.
    pub terms: crate::shading::LitTerms,
    /// How L and H are renormalized per fragment.
    pub normalize: Normalize,
    /// The cube map's face size for [`Normalize::Cube`].
    pub cube_size: usize,
    /// Per-vertex or per-fragment H.
    pub half_angle: HalfAngle,
    /// The light: attenuation, spotlight (its colour is already in `terms`).
    pub light: SceneLight,
    /// Heights as geometry: where the maps are read is where the view ray meets the heights
    /// (`crate::parallax`), or `None` for the entry point itself.
    pub parallax: Option<ParallaxProgram>,
}

/// What a single pass with heights as geometry reads besides the lit program's maps.
#[derive(Clone, Debug, PartialEq)]
pub struct ParallaxProgram {
    /// The march and its options.
    pub parallax: Parallax,
    /// The heights, the normal map's size (with their min–max levels for the exact walk).
    pub heights: Arc<HeightMips>,
    /// The heights' horizon map, for [`crate::parallax::ParallaxShadow::Horizon`].
    pub horizons: Option<Arc<bumpmap_math::HorizonMap>>,
    /// Object units per unit of height.
    pub depth: f32,
    /// The camera's `far / (far − near)`: what a hit's window depth is computed with
    /// ([`crate::parallax::displaced_depth`]).
    pub depth_range: f32,
}

impl LitProgram {
    /// How many varyings (from slot 0) the program reads.
    pub fn varyings_read(&self) -> usize {
        let read = self.varyings_read_uncoloured();
        if self.vertex_color { read.max(var::COLOR + 4) } else { read }
    }

    fn varyings_read_uncoloured(&self) -> usize {
        if self.normal_space == NormalSpace::TangentPerPixel {
            var::TANGENT + 4
        } else if self.parallax.is_some() {
            var::CURVATURE + 2
        } else if matches!(self.normal_texels, crate::scene::NormalTexels::Derivatives { .. }) {
            var::PARAM_FRAME + 3
        } else if self.normal_space.lit_in_object_space() {
            var::N + 3
        } else if self.light.spot.is_some() {
            var::PROJ + 3
        } else if self.light.attenuation != crate::scene::Attenuation::None {
            var::LIGHT_DISTANCE + 1
        } else if self.half_angle == HalfAngle::Fragment {
            var::V + 3
        } else {
            var::H + 3
        }
    }
}
