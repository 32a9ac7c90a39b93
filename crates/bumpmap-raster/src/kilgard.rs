//! The paper's technique (Kilgard §5.4–5.6): three passes on the emulated GeForce 256.
//!
//! 1. the decal, depth LESS;
//! 2. ambient + diffuse with the normal map's length factor and the self-shadowing ramp
//!    (Appendix G), `glBlendFunc(GL_DST_COLOR, GL_ZERO)`, depth EQUAL, s_self into alpha;
//! 3. the specular `(H·N')^8` (Appendix H) or §5.5's ramp, `glBlendFunc(GL_DST_ALPHA, GL_ONE)`.
//!
//! Without a decal, pass 2 draws first with depth LESS; with a black specular colour, pass 3 is
//! dropped. Each further light (§5.6, "multiple passes") adds three passes on a GeForce3-class
//! setup with three texture units: its decal-modulated diffuse added with a constant blend colour
//! (`k_diffuse · light colour`), its s_self into alpha alone (colour mask), and its specular by
//! destination alpha. The first light's colour scales `k_diffuse` (constant colour 1); specular
//! is white, as the paper's combiners leave no multiplier for a specular colour.

use std::sync::Arc;

use glam::Vec4;

use bumpmap_math::{Encoding, NormalizationCubeMap};

use crate::combiners::{
    CombinerSetup, Combiners, ComponentUsage::*, FinalInput, InputMapping::UnsignedInvert, Precision, Register::*,
};
use crate::error::RasterError;
use crate::fixed_function::{Binding, FixedFunction, TextureUnit};
use crate::framebuffer::{Blend, BlendFactor, DepthFunc, Framebuffer};
use crate::raster::{DrawState, Vertex, draw};
use crate::scene::{Scene, SceneObject, var};
use crate::setups;
use crate::texture::{Sampler, TextureCube};

/// Which specular setup pass 3 uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SpecularMode {
    /// `max(0, H·N')^8` by repeated squaring (Appendix H).
    #[default]
    EighthPower,
    /// `max(0, 4·(H·N' − ¾))²` (§5.5).
    Ramp,
}

/// Options of the three-pass technique.
#[derive(Clone, Debug, PartialEq)]
pub struct KilgardOptions {
    /// The normal map's and decal's filtering (the paper: LINEAR_MIPMAP_LINEAR).
    pub sampler: Sampler,
    /// Eq. 12's self-shadowing term (Figure 14 right); off gives Figure 14 left.
    pub self_shadow: bool,
    pub specular: SpecularMode,
    pub precision: Precision,
    /// Face size of the normalization cube map.
    pub cube_size: usize,
    pub cube_encoding: Encoding,
}

impl Default for KilgardOptions {
    fn default() -> Self {
        Self {
            sampler: Sampler::TRILINEAR_REPEAT,
            self_shadow: true,
            specular: SpecularMode::EighthPower,
            precision: Precision::Float,
            cube_size: 32,
            cube_encoding: Encoding::Unorm,
        }
    }
}

/// Names of the passes, for the `--passes` images (Figure 12).
pub const PASS_NAMES: [&str; 3] = ["decal", "diffuse", "specular"];

/// Renders `scene` into `fb` (cleared first). `on_pass` sees the framebuffer after each pass of
/// the first light, named by [`PASS_NAMES`].
pub fn render(
    scene: &Scene,
    options: &KilgardOptions,
    fb: &mut Framebuffer,
    mut on_pass: impl FnMut(&str, &Framebuffer),
) -> Result<(), RasterError> {
    fb.clear([0, 0, 0, 0], 1.0);
    let cube =
        Arc::new(TextureCube::from_normalization(&NormalizationCubeMap::new(options.cube_size, options.cube_encoding)));
    let aspect = fb.width as f32 / fb.height as f32;
    let combiners = |setup: CombinerSetup| Combiners::new(setup, options.precision);
    for object in &scene.objects {
        let m = &object.material;
        if m.normal_space != crate::scene::NormalSpace::Tangent {
            return Err(RasterError::Scene(
                "the three-pass technique lights in tangent space (its self-shadowing reads L_z); use --technique single-pass for object space".into(),
            ));
        }
        let normal_unit = TextureUnit {
            binding: Binding::TwoD { texture: m.normal_map.clone(), s: var::S, t: var::T },
            sampler: options.sampler,
        };
        let cube_unit =
            |r| TextureUnit { binding: Binding::Cube { texture: cube.clone(), r }, sampler: Sampler::LINEAR_CLAMP };
        let decal_unit = m.decal.as_ref().map(|d| TextureUnit {
            binding: Binding::TwoD { texture: d.clone(), s: var::S, t: var::T },
            sampler: options.sampler,
        });
        let has_specular = m.specular.max_element() > 0.0;
        // Each draw interpolates only the varyings its texture units read (`draw_object`).
        let opaque = DrawState::OPAQUE;
        let equal = DrawState { depth_func: DepthFunc::Equal, depth_write: false, ..opaque };
        for (i, light) in scene.lights.iter().enumerate() {
            let vertices = scene.vertices(object, light, aspect);
            let kd = (m.diffuse * light.color).extend(0.0);
            let ambient = m.ambient.extend(0.0);
            let spec = match options.specular {
                SpecularMode::EighthPower => setups::specular(),
                SpecularMode::Ramp => setups::specular_ramp(),
            };
            if i == 0 {
                // Pass 1: the decal.
                if let Some(decal) = &decal_unit {
                    let shader = FixedFunction { units: vec![decal.clone()], combiners: combiners(setups::decal())? };
                    draw_object(fb, &vertices, object, &opaque, &shader);
                    on_pass(PASS_NAMES[0], fb);
                }
                // Pass 2: ambient + diffuse, s_self to alpha.
                let diffuse = diffuse_setup(options.self_shadow, ambient, kd);
                let state = if decal_unit.is_some() { DrawState { blend: Blend::MODULATE, ..equal } } else { opaque };
                let shader = FixedFunction {
                    units: vec![normal_unit.clone(), cube_unit(var::L)],
                    combiners: combiners(diffuse)?,
                };
                draw_object(fb, &vertices, object, &state, &shader);
                on_pass(PASS_NAMES[1], fb);
            } else {
                // Extra light, pass a: decal · s_self · k_d · max(0, L·N') · |N'|, added.
                let setup = decal_times_diffuse(options.self_shadow, decal_unit.is_some());
                let mut units = vec![normal_unit.clone(), cube_unit(var::L)];
                units.extend(decal_unit.clone());
                let blend = Blend {
                    color: [kd.x, kd.y, kd.z, 0.0],
                    ..Blend::new(BlendFactor::ConstantColor, BlendFactor::One)
                };
                let shader = FixedFunction { units, combiners: combiners(setup)? };
                draw_object(fb, &vertices, object, &DrawState { blend, ..equal }, &shader);
                // Pass b: this light's s_self into alpha only.
                if has_specular {
                    let diffuse = diffuse_setup(options.self_shadow, ambient, kd);
                    let shader = FixedFunction {
                        units: vec![normal_unit.clone(), cube_unit(var::L)],
                        combiners: combiners(diffuse)?,
                    };
                    let state = DrawState { color_mask: [false, false, false, true], ..equal };
                    draw_object(fb, &vertices, object, &state, &shader);
                }
            }
            // Pass 3: specular, modulated by s_self in destination alpha.
            if has_specular {
                let shader =
                    FixedFunction { units: vec![normal_unit.clone(), cube_unit(var::H)], combiners: combiners(spec)? };
                draw_object(fb, &vertices, object, &DrawState { blend: Blend::ADD_BY_DST_ALPHA, ..equal }, &shader);
                if i == 0 {
                    on_pass(PASS_NAMES[2], fb);
                }
            }
        }
    }
    Ok(())
}

fn draw_object(
    fb: &mut Framebuffer,
    vertices: &[Vertex],
    object: &SceneObject,
    state: &DrawState,
    shader: &FixedFunction,
) {
    let state = DrawState { varyings: shader.varyings_read(), ..*state };
    draw(fb, vertices, &object.mesh.indices, &state, shader);
}

/// Appendix G, with or without Eq. 12's self-shadowing term (Figure 14).
fn diffuse_setup(self_shadow: bool, ambient: Vec4, diffuse: Vec4) -> CombinerSetup {
    if self_shadow {
        setups::ambient_and_diffuse(ambient, diffuse)
    } else {
        setups::ambient_and_diffuse_unshadowed(ambient, diffuse)
    }
}

/// Appendix G's first stage, then `spare0 = max(0, L·N')·|N'|`, and in the final combiner
/// `s_self · spare0 · decal` (texture 2) with alpha 0.
fn decal_times_diffuse(self_shadow: bool, has_decal: bool) -> CombinerSetup {
    let mut setup = diffuse_setup(self_shadow, Vec4::ZERO, Vec4::ONE);
    let f = &mut setup.final_combiner;
    f.a = FinalInput::reg(Spare0, Alpha);
    f.b = FinalInput::E_TIMES_F;
    f.c = FinalInput::ZERO;
    f.d = FinalInput::ZERO;
    f.e = FinalInput::reg(Spare0, Rgb);
    f.f = if has_decal {
        FinalInput::reg(Texture2, Rgb)
    } else {
        FinalInput { mapping: UnsignedInvert, ..FinalInput::ZERO }
    };
    f.g = FinalInput::reg(Zero, Alpha);
    setup
}
