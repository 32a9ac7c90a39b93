//! Embossing (Kilgard §3.1, Eq. 29–30), the technique the paper's replaces: the height field
//! fetched twice, once shifted toward the light by about one texel, the two subtracted and L_z
//! added — on the GeForce pipeline with its 8-bit framebuffer and clamping.
//!
//! 1. the decal, depth LESS (when there is one);
//! 2. `I_ambient + k_diffuse · max(0, L_z + scale·(F − F_shifted))` ([`setups::emboss`]),
//!    `glBlendFunc(GL_DST_COLOR, GL_ZERO)`, depth EQUAL.
//!
//! Diffuse only, one light: embossing has no normal to take a half-angle vector to, and the
//! paper's point is what it gets wrong even so. [`BackFacing::Unforced`] leaves the shift on
//! where `L_z ≤ 0`, which lights faces turned away from the light (§3.1).

use glam::Vec3;

use crate::combiners::{Precision, Register, Scale};
use crate::error::{CoreError, Feature};
use crate::scene::{Attenuation, Scene};
use crate::setups;
use crate::state::{Blend, PassState, Sampler};
use crate::technique::{Binding, CombinerProgram, Pass, Program, TextureUnit};
use crate::vertex::var;

/// The technique's name.
pub const NAME: &str = "emboss";

/// What the shift does where the light is behind the surface (`L_z ≤ 0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BackFacing {
    /// L_x, L_y forced to 0 there, as §3.1 says: the difference vanishes and L_z ≤ 0 leaves
    /// only the ambient term.
    #[default]
    Forced,
    /// The shift left on: bumps stay lit on the side turned away from the light.
    Unforced,
}

/// Options of embossing.
#[derive(Clone, Debug, PartialEq)]
pub struct EmbossOptions {
    /// The height map's and decal's filtering.
    pub sampler: Sampler,
    /// Where `L_z ≤ 0`.
    pub back_facing: BackFacing,
    /// Face size of the normalization cube map that gives L_z.
    pub cube_size: usize,
}

impl Default for EmbossOptions {
    fn default() -> Self {
        Self { sampler: Sampler::TRILINEAR_REPEAT, back_facing: BackFacing::Forced, cube_size: 32 }
    }
}

/// The combiners' output scale for a bump scale, if they have one.
fn scale_of(bump_scale: f32) -> Option<Scale> {
    match bump_scale {
        1.0 => Some(Scale::None),
        2.0 => Some(Scale::ByTwo),
        4.0 => Some(Scale::ByFour),
        _ => None,
    }
}

/// The passes of `scene`: one light, every object.
pub fn passes(scene: &Scene, options: &EmbossOptions) -> Result<Vec<Pass>, CoreError> {
    let unsupported = |feature| Err(CoreError::Unsupported { technique: NAME, feature });
    if scene.lights.len() > 1 {
        return unsupported(Feature::MultipleLights);
    }
    if scene.lights.iter().any(|l| l.attenuation != Attenuation::None || l.spot.is_some()) {
        return unsupported(Feature::Attenuation);
    }
    let mut passes = Vec::new();
    for (o, object) in scene.objects.iter().enumerate() {
        let m = &object.material;
        // Embossing reads the height map, which repeats with the texture; only the lighting
        // space matters.
        if m.normal_space.is_object() {
            return unsupported(Feature::ObjectSpace);
        }
        if m.normal_space == crate::scene::NormalSpace::TangentPerPixel {
            return unsupported(Feature::PerPixelDecode);
        }
        let Some(scale) = scale_of(m.bump_scale) else {
            return unsupported(Feature::BumpScale(m.bump_scale));
        };
        let Some(heights) = m.height_map.clone() else {
            return unsupported(Feature::HeightMap);
        };
        let shifted = match options.back_facing {
            BackFacing::Forced => var::EMBOSS,
            BackFacing::Unforced => var::EMBOSS_UNFORCED,
        };
        let unit = |texture, s, t| TextureUnit {
            binding: Binding::TwoD { texture, s, t },
            sampler: options.sampler.for_material(&m.sampler),
        };
        let cube = TextureUnit {
            binding: Binding::NormalizationCube {
                size: options.cube_size,
                encoding: bumpmap_math::Encoding::Unorm,
                r: var::L,
            },
            sampler: Sampler::LINEAR_CLAMP,
        };
        let color = scene.lights.first().map_or(Vec3::ONE, |l| l.color);
        let colored = object.mesh.has_colors();
        let mut push = |state, units, setup: crate::combiners::CombinerSetup| {
            setup.validate()?;
            let vertex_color = colored && setup.reads(Register::PrimaryColor);
            let program =
                Program::Combiners(CombinerProgram { units, setup, precision: Precision::Float, vertex_color });
            passes.push(Pass { object: o, light: 0, snapshot: None, state, program });
            Ok::<_, CoreError>(())
        };
        // The decal, times the vertex colours where the mesh has them.
        let units: Vec<TextureUnit> = m.decal.iter().map(|decal| unit(decal.clone(), var::S, var::T)).collect();
        if colored {
            push(PassState::OPAQUE, units, setups::vertex_colored_decal(m.decal.is_some()))?;
        } else if !units.is_empty() {
            push(PassState::OPAQUE, units, setups::decal())?;
        }
        let state = if m.decal.is_some() || colored { PassState::equal(Blend::MODULATE) } else { PassState::OPAQUE };
        let units = vec![unit(heights.clone(), var::S, var::T), unit(heights, shifted, shifted + 1), cube];
        push(state, units, setups::emboss(scale, m.ambient.extend(0.0), (m.diffuse * color).extend(0.0)))?;
    }
    Ok(passes)
}
