//! The paper's technique (Kilgard §5.4–5.6) as passes for a GeForce 256:
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
//!
//! A material's occlusion map multiplies the ambient term in pass 2 from a third texture unit
//! (`setups::with_ambient_occlusion`).

use glam::{Vec3, Vec4};

use bumpmap_math::Encoding;

use crate::combiners::{
    CombinerSetup,
    ComponentUsage::*,
    FinalInput, Input,
    InputMapping::{UnsignedIdentity, UnsignedInvert},
    Precision,
    Register::*,
};
use crate::error::{CoreError, Feature};
use crate::scene::{Attenuation, NormalSpace, Scene};
use crate::setups;
use crate::state::{Blend, BlendFactor, PassState, Sampler};
use crate::technique::{Binding, CombinerProgram, Pass, Program, TextureUnit};
use crate::vertex::var;

/// The technique's name.
pub const NAME: &str = "kilgard";

/// Which specular setup pass 3 uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SpecularMode {
    /// `max(0, H·N')^8` by repeated squaring (Appendix H).
    #[default]
    EighthPower,
    /// `max(0, 4·(H·N' − ¾))²` (§5.5).
    Ramp,
}

bumpmap_math::named!(SpecularMode {
    EighthPower => "power8": "max(0, H·N')^8 by repeated squaring (Appendix H)",
    Ramp => "ramp": "max(0, 4·(H·N' − ¾))² (§5.5), a tighter highlight",
});

/// Options of the three-pass technique.
#[derive(Clone, Debug, PartialEq)]
pub struct KilgardOptions {
    /// The normal map's and decal's filtering (the paper: LINEAR_MIPMAP_LINEAR).
    pub sampler: Sampler,
    /// Eq. 12's self-shadowing term (Figure 14 right); off gives Figure 14 left.
    pub self_shadow: bool,
    /// Appendix H's eighth power or §5.5's ramp.
    pub specular: SpecularMode,
    /// The combiners' datapath.
    pub precision: Precision,
    /// Face size of the normalization cube map.
    pub cube_size: usize,
    /// How the cube map stores its vectors.
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

/// Names of the first light's passes, for the `--passes` images (Figure 12).
pub const PASS_NAMES: [&str; 3] = ["decal", "diffuse", "specular"];

/// Refuses what the paper's combiners have no room for.
pub fn validate(scene: &Scene) -> Result<(), CoreError> {
    let unsupported = |feature| Err(CoreError::Unsupported { technique: NAME, feature });
    for object in &scene.objects {
        let m = &object.material;
        match m.normal_space {
            NormalSpace::Tangent => {}
            NormalSpace::SurfaceTangent { .. } => return unsupported(Feature::SurfaceMap),
            NormalSpace::Object { .. } => return unsupported(Feature::ObjectSpace),
            NormalSpace::TangentPerPixel => return unsupported(Feature::PerPixelDecode),
        }
        if m.normal_texels != crate::scene::NormalTexels::UnitVector {
            return unsupported(Feature::OffsetMap);
        }
        if m.shininess != 8.0 {
            return unsupported(Feature::Shininess(m.shininess));
        }
        if m.specular.max_element() > 0.0 && m.specular != Vec3::ONE {
            return unsupported(Feature::SpecularColor);
        }
    }
    for light in &scene.lights {
        if light.attenuation != Attenuation::None {
            return unsupported(Feature::Attenuation);
        }
        if light.spot.is_some() {
            return unsupported(Feature::Spotlight);
        }
    }
    Ok(())
}

/// The passes of `scene`, every object in turn, every light of each object in turn.
pub fn passes(scene: &Scene, options: &KilgardOptions) -> Result<Vec<Pass>, CoreError> {
    validate(scene)?;
    let cube = |r| TextureUnit {
        binding: Binding::NormalizationCube { size: options.cube_size, encoding: options.cube_encoding, r },
        sampler: Sampler::LINEAR_CLAMP,
    };
    let mut passes = Vec::new();
    for (o, object) in scene.objects.iter().enumerate() {
        let m = &object.material;
        let unit_2d = |texture| TextureUnit {
            binding: Binding::TwoD { texture, s: var::S, t: var::T },
            sampler: options.sampler.for_material(&m.sampler),
        };
        let normal_unit = unit_2d(m.normal_map.clone());
        let decal_unit = m.decal.clone().map(unit_2d);
        let has_specular = m.specular.max_element() > 0.0;
        let colored = object.mesh.has_colors();
        let equal = |blend| PassState::equal(blend);
        for (l, light) in scene.lights.iter().enumerate() {
            let mut pass = |snapshot, state, units, setup: CombinerSetup| {
                setup.validate()?;
                let vertex_color = colored && setup.reads(PrimaryColor);
                let program =
                    Program::Combiners(CombinerProgram { units, setup, precision: options.precision, vertex_color });
                passes.push(Pass { object: o, light: l, snapshot, state, program });
                Ok::<_, CoreError>(())
            };
            let first = l == 0;
            let named = |k: usize| first.then_some(PASS_NAMES[k]);
            let kd = (m.diffuse * light.color).extend(0.0);
            let ambient = m.ambient.extend(0.0);
            if first {
                // Pass 1: the decal (times the vertex colours, where the mesh has them).
                let units: Vec<TextureUnit> = decal_unit.iter().cloned().collect();
                if colored {
                    pass(named(0), PassState::OPAQUE, units, setups::vertex_colored_decal(decal_unit.is_some()))?;
                } else if !units.is_empty() {
                    pass(named(0), PassState::OPAQUE, units, setups::decal())?;
                }
                // Pass 2: ambient + diffuse, s_self to alpha.
                let state = if decal_unit.is_some() || colored { equal(Blend::MODULATE) } else { PassState::OPAQUE };
                let setup = diffuse_setup(options.self_shadow, ambient, kd);
                let mut units = vec![normal_unit.clone(), cube(var::L)];
                // An occlusion map multiplies the ambient term only, from a third unit.
                let setup = match &m.occlusion {
                    Some(occlusion) => {
                        units.push(unit_2d(occlusion.clone()));
                        setups::with_ambient_occlusion(setup)
                    }
                    None => setup,
                };
                pass(named(1), state, units, setup)?;
            } else {
                // Extra light, pass a: decal · s_self · k_d · max(0, L·N') · |N'|, added.
                let setup = decal_times_diffuse(options.self_shadow, decal_unit.is_some(), colored);
                let mut units = vec![normal_unit.clone(), cube(var::L)];
                units.extend(decal_unit.clone());
                let blend = Blend {
                    color: [kd.x, kd.y, kd.z, 0.0],
                    ..Blend::new(BlendFactor::ConstantColor, BlendFactor::One)
                };
                pass(None, equal(blend), units, setup)?;
                // Pass b: this light's s_self into alpha only.
                if has_specular {
                    let state = PassState { color_mask: [false, false, false, true], ..equal(Blend::REPLACE) };
                    let setup = diffuse_setup(options.self_shadow, ambient, kd);
                    pass(None, state, vec![normal_unit.clone(), cube(var::L)], setup)?;
                }
            }
            // Pass 3: specular, modulated by s_self in destination alpha.
            if has_specular {
                let setup = match options.specular {
                    SpecularMode::EighthPower => setups::specular(),
                    SpecularMode::Ramp => setups::specular_ramp(),
                };
                pass(named(2), equal(Blend::ADD_BY_DST_ALPHA), vec![normal_unit.clone(), cube(var::H)], setup)?;
            }
        }
    }
    Ok(passes)
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
/// `s_self · spare0 · decal` (texture 2) with alpha 0. With `vertex_color` the decal is
/// multiplied by `PRIMARY_COLOR` first, in stage 1's free C·D (`spare1`).
pub fn decal_times_diffuse(self_shadow: bool, has_decal: bool, vertex_color: bool) -> CombinerSetup {
    let mut setup = diffuse_setup(self_shadow, Vec4::ZERO, Vec4::ONE);
    let decal = if has_decal {
        FinalInput::reg(Texture2, Rgb)
    } else {
        FinalInput { mapping: UnsignedInvert, ..FinalInput::ZERO }
    };
    let f = if vertex_color {
        let rgb = &mut setup.stages[1].rgb;
        rgb.c = if has_decal { Input::new(Texture2, UnsignedIdentity, Rgb) } else { Input::one(Rgb) };
        rgb.d = Input::new(PrimaryColor, UnsignedIdentity, Rgb);
        rgb.outputs.cd = Some(Spare1);
        FinalInput::reg(Spare1, Rgb)
    } else {
        decal
    };
    let fc = &mut setup.final_combiner;
    fc.a = FinalInput::reg(Spare0, Alpha);
    fc.b = FinalInput::E_TIMES_F;
    fc.c = FinalInput::ZERO;
    fc.d = FinalInput::ZERO;
    fc.e = FinalInput::reg(Spare0, Rgb);
    fc.f = f;
    fc.g = FinalInput::reg(Zero, Alpha);
    setup
}
