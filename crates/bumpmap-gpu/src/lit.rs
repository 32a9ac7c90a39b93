//! What `lit.wgsl` is given for one [`LitProgram`]: its uniform block (the material's numbers)
//! and its pipeline-overridable constants (the model's switches).
//!
//! The switches are override constants rather than uniforms so each combination is compiled
//! on its own: the driver folds the untaken branches away, and a software rasterizer such as
//! lavapipe, which runs both sides of a branch under a mask, no longer pays for every mode on
//! every fragment. Pipelines are cached per [`LitVariant`], so a frame compiles none after the
//! first.
//!
//! It does not hold the model itself: that is `shading.wgsl` (tested against
//! `bumpmap_core::shading::shade`).

use bumpmap_core::scene::{Attenuation, NormalTexels};
use bumpmap_core::shading::LitTerms;
use bumpmap_core::technique::{Gloss, HalfAngle, LitProgram, Normalize, SelfShadow, SpecularShadow};

/// The switches of one lit program, as `lit.wgsl`'s override constants.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LitVariant {
    self_shadow: u32,
    specular_shadow: u32,
    normalize_cube: bool,
    fragment_half_angle: bool,
    gloss: u32,
    object_space: bool,
    attenuation: u32,
    spot: bool,
    spot_pattern: bool,
    /// The shininess's bits (a constant, so whole exponents become a fixed product).
    shininess: u32,
    normal_texels: u32,
}

impl LitVariant {
    /// The variant `p` needs.
    pub fn of(p: &LitProgram) -> Self {
        Self {
            self_shadow: match p.terms.self_shadow {
                SelfShadow::Ramp => 0,
                SelfShadow::Step => 1,
                SelfShadow::Off => 2,
            },
            specular_shadow: match p.terms.specular_shadow {
                SpecularShadow::Kilgard => 0,
                SpecularShadow::CgTutorial => 1,
                SpecularShadow::Off => 2,
            },
            normalize_cube: p.normalize == Normalize::Cube,
            fragment_half_angle: p.half_angle == HalfAngle::Fragment,
            gloss: match p.gloss {
                Gloss::None => 0,
                Gloss::DecalAlpha => 1,
                Gloss::Map(_) => 2,
            },
            object_space: p.normal_space.is_object(),
            attenuation: match p.light.attenuation {
                Attenuation::None => 0,
                Attenuation::Polynomial { .. } => 1,
                Attenuation::Exponential { .. } => 2,
                Attenuation::ExponentialSquared { .. } => 3,
            },
            spot: p.light.spot.is_some(),
            spot_pattern: p.light.spot.as_ref().is_some_and(|s| s.pattern.is_some()),
            shininess: p.terms.shininess.to_bits(),
            normal_texels: match p.normal_texels {
                NormalTexels::UnitVector => 0,
                NormalTexels::Offset { .. } => 1,
                NormalTexels::Derivatives { .. } => 2,
            },
        }
    }

    /// The override constants, by their names in `lit.wgsl`.
    pub fn constants(&self) -> [(&'static str, f64); 11] {
        let flag = |b: bool| b as u32 as f64;
        [
            ("SELF_SHADOW", self.self_shadow as f64),
            ("SPECULAR_SHADOW", self.specular_shadow as f64),
            ("NORMALIZE_CUBE", flag(self.normalize_cube)),
            ("FRAGMENT_HALF_ANGLE", flag(self.fragment_half_angle)),
            ("GLOSS", self.gloss as f64),
            ("OBJECT_SPACE", flag(self.object_space)),
            ("ATTENUATION", self.attenuation as f64),
            ("SPOTLIGHT", flag(self.spot)),
            ("SPOT_PATTERN", flag(self.spot_pattern)),
            ("SHININESS", f32::from_bits(self.shininess) as f64),
            ("NORMAL_TEXELS", self.normal_texels as f64),
        ]
    }
}

/// `lit.wgsl`'s `Lit` uniform block for `p`.
pub fn uniforms(p: &LitProgram) -> Vec<u8> {
    let LitTerms { ambient, diffuse, specular, .. } = p.terms;
    let attenuation = match p.light.attenuation {
        Attenuation::None => [0.0; 4],
        Attenuation::Polynomial { constant, linear, quadratic } => [constant, linear, quadratic, 0.0],
        Attenuation::Exponential { density } | Attenuation::ExponentialSquared { density } => [density, 0.0, 0.0, 0.0],
    };
    let spot = match &p.light.spot {
        Some(s) => [s.cutoff_degrees.to_radians().cos(), s.exponent, 0.0, 0.0],
        None => [0.0; 4],
    };
    let scale = p.normal_space.texcoord_scale().to_array();
    let texels = match p.normal_texels {
        NormalTexels::UnitVector => [0.0; 4],
        NormalTexels::Offset { range } => [range, 0.0, 0.0, 0.0],
        NormalTexels::Derivatives { range, scale } => [range, scale.x, scale.y, 0.0],
    };
    let block: [[f32; 4]; 7] = [
        ambient.extend(0.0).to_array(),
        diffuse.extend(0.0).to_array(),
        specular.extend(0.0).to_array(),
        attenuation,
        spot,
        [scale[0], scale[1], 0.0, 0.0],
        texels,
    ];
    block.iter().flatten().flat_map(|x| x.to_le_bytes()).collect()
}
