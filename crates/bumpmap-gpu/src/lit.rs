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

use bumpmap_core::detail::BlendMethod;
use bumpmap_core::parallax::{HitNormal, ParallaxMethod, ParallaxShadow};
use bumpmap_core::scene::{Attenuation, NormalTexels};
use bumpmap_core::shading::LitTerms;
use bumpmap_core::technique::{Gloss, HalfAngle, LitProgram, Normalize, SelfShadow, SpecularFilter, SpecularShadow};

/// One switch of the lit program: its override constant and the WGSL names of its values, in
/// code order (a value's code is its index here).
struct Switch {
    name: &'static str,
    values: &'static [&'static str],
}

impl Switch {
    /// The code of the value named `value`. Panics when the value is not listed: a new variant
    /// of a switch's enum must be named here (every parity test would fail first).
    fn code(&self, value: &str) -> u32 {
        self.values
            .iter()
            .position(|&v| v == value)
            .unwrap_or_else(|| panic!("{value} is not a value of {}", self.name)) as u32
    }
}

const SELF_SHADOW: Switch =
    Switch { name: "SELF_SHADOW", values: &["SELF_SHADOW_RAMP", "SELF_SHADOW_STEP", "SELF_SHADOW_OFF"] };
const SPECULAR_SHADOW: Switch = Switch {
    name: "SPECULAR_SHADOW",
    values: &["SPECULAR_SHADOW_KILGARD", "SPECULAR_SHADOW_CG_TUTORIAL", "SPECULAR_SHADOW_OFF"],
};
const SPECULAR_FILTER: Switch = Switch {
    name: "SPECULAR_FILTER",
    values: &[
        "SPECULAR_FILTER_NONE",
        "SPECULAR_FILTER_TOKSVIG",
        "SPECULAR_FILTER_ROUGHNESS_MAP",
        "SPECULAR_FILTER_LEAN",
        "SPECULAR_FILTER_CLEAN",
    ],
};
const GLOSS: Switch = Switch { name: "GLOSS", values: &["GLOSS_NONE", "GLOSS_DECAL_ALPHA", "GLOSS_MAP"] };
const ATTENUATION: Switch = Switch {
    name: "ATTENUATION",
    values: &["ATTENUATION_NONE", "ATTENUATION_POLYNOMIAL", "ATTENUATION_EXP", "ATTENUATION_EXP2"],
};
const NORMAL_TEXELS: Switch = Switch {
    name: "NORMAL_TEXELS",
    values: &["NORMAL_TEXELS_UNIT_VECTOR", "NORMAL_TEXELS_OFFSET", "NORMAL_TEXELS_DERIVATIVES"],
};
const PARALLAX: Switch = Switch {
    name: "PARALLAX",
    values: &[
        "PARALLAX_NONE",
        "PARALLAX_OFFSET",
        "PARALLAX_STEEP",
        "PARALLAX_OCCLUSION",
        "PARALLAX_RELIEF",
        "PARALLAX_EXACT",
        "PARALLAX_FLAT",
    ],
};
const PARALLAX_SHADOW: Switch = Switch {
    name: "PARALLAX_SHADOW",
    values: &["PARALLAX_SHADOW_OFF", "PARALLAX_SHADOW_HARD", "PARALLAX_SHADOW_SOFT", "PARALLAX_SHADOW_HORIZON"],
};

const DETAIL: Switch = Switch {
    name: "DETAIL",
    values: &[
        "DETAIL_NONE",
        "DETAIL_RNM",
        "DETAIL_PARTIAL_DERIVATIVE",
        "DETAIL_WHITEOUT",
        "DETAIL_UDN",
        "DETAIL_LINEAR",
        "DETAIL_OVERLAY",
    ],
};

/// The WGSL name of a detail blend's constant (`DETAIL_NONE` for no detail map).
pub fn detail_name(method: Option<BlendMethod>) -> &'static str {
    match method {
        None => "DETAIL_NONE",
        Some(BlendMethod::Rnm) => "DETAIL_RNM",
        Some(BlendMethod::PartialDerivative) => "DETAIL_PARTIAL_DERIVATIVE",
        Some(BlendMethod::Whiteout) => "DETAIL_WHITEOUT",
        Some(BlendMethod::Udn) => "DETAIL_UDN",
        Some(BlendMethod::Linear) => "DETAIL_LINEAR",
        Some(BlendMethod::Overlay) => "DETAIL_OVERLAY",
    }
}

/// The WGSL name of a parallax method's constant (`PARALLAX_NONE` for none).
pub fn parallax_name(method: Option<ParallaxMethod>) -> &'static str {
    match method {
        None => "PARALLAX_NONE",
        Some(ParallaxMethod::Offset) => "PARALLAX_OFFSET",
        Some(ParallaxMethod::Steep) => "PARALLAX_STEEP",
        Some(ParallaxMethod::Occlusion) => "PARALLAX_OCCLUSION",
        Some(ParallaxMethod::Relief) => "PARALLAX_RELIEF",
        Some(ParallaxMethod::Exact) => "PARALLAX_EXACT",
        Some(ParallaxMethod::Flat) => "PARALLAX_FLAT",
    }
}

/// The WGSL name of a parallax shadow's constant (`PARALLAX_SHADOW_OFF`, …).
pub fn parallax_shadow_name(shadow: ParallaxShadow) -> &'static str {
    match shadow {
        ParallaxShadow::Off => "PARALLAX_SHADOW_OFF",
        ParallaxShadow::Hard => "PARALLAX_SHADOW_HARD",
        ParallaxShadow::Soft => "PARALLAX_SHADOW_SOFT",
        ParallaxShadow::Horizon => "PARALLAX_SHADOW_HORIZON",
    }
}

/// The WGSL name of a self-shadowing mode's constant (`SELF_SHADOW_RAMP`, …).
pub fn self_shadow_name(mode: SelfShadow) -> &'static str {
    match mode {
        SelfShadow::Ramp => "SELF_SHADOW_RAMP",
        SelfShadow::Step => "SELF_SHADOW_STEP",
        SelfShadow::Off => "SELF_SHADOW_OFF",
    }
}

/// The WGSL name of a specular gate's constant (`SPECULAR_SHADOW_KILGARD`, …).
pub fn specular_shadow_name(mode: SpecularShadow) -> &'static str {
    match mode {
        SpecularShadow::Kilgard => "SPECULAR_SHADOW_KILGARD",
        SpecularShadow::CgTutorial => "SPECULAR_SHADOW_CG_TUTORIAL",
        SpecularShadow::Off => "SPECULAR_SHADOW_OFF",
    }
}

/// The WGSL name of a specular filter's constant (`SPECULAR_FILTER_NONE`, …).
pub fn specular_filter_name(filter: SpecularFilter) -> &'static str {
    match filter {
        SpecularFilter::None => "SPECULAR_FILTER_NONE",
        SpecularFilter::Toksvig => "SPECULAR_FILTER_TOKSVIG",
        SpecularFilter::RoughnessMap => "SPECULAR_FILTER_ROUGHNESS_MAP",
        SpecularFilter::Lean => "SPECULAR_FILTER_LEAN",
        SpecularFilter::Clean => "SPECULAR_FILTER_CLEAN",
    }
}

fn gloss_name(gloss: &Gloss) -> &'static str {
    match gloss {
        Gloss::None => "GLOSS_NONE",
        Gloss::DecalAlpha => "GLOSS_DECAL_ALPHA",
        Gloss::Map(_) => "GLOSS_MAP",
    }
}

fn attenuation_name(a: &Attenuation) -> &'static str {
    match a {
        Attenuation::None => "ATTENUATION_NONE",
        Attenuation::Polynomial { .. } => "ATTENUATION_POLYNOMIAL",
        Attenuation::Exponential { .. } => "ATTENUATION_EXP",
        Attenuation::ExponentialSquared { .. } => "ATTENUATION_EXP2",
    }
}

fn normal_texels_name(t: &NormalTexels) -> &'static str {
    match t {
        NormalTexels::UnitVector => "NORMAL_TEXELS_UNIT_VECTOR",
        NormalTexels::Offset { .. } => "NORMAL_TEXELS_OFFSET",
        NormalTexels::Derivatives { .. } => "NORMAL_TEXELS_DERIVATIVES",
    }
}

/// Every named value of every switch with its code: the prelude's constants.
pub(crate) fn named_values() -> impl Iterator<Item = (&'static str, u32)> {
    [
        SELF_SHADOW,
        SPECULAR_SHADOW,
        SPECULAR_FILTER,
        GLOSS,
        ATTENUATION,
        NORMAL_TEXELS,
        PARALLAX,
        PARALLAX_SHADOW,
        DETAIL,
    ]
    .into_iter()
    .flat_map(|s| s.values.iter().enumerate().map(|(i, &v)| (v, i as u32)))
}

/// The switches of one lit program, as `lit.wgsl`'s override constants.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LitVariant {
    self_shadow: u32,
    specular_shadow: u32,
    specular_filter: u32,
    normalize_cube: bool,
    fragment_half_angle: bool,
    gloss: u32,
    object_space: bool,
    /// The tangent-space normal decoded per pixel (MikkTSpace's decode).
    per_pixel_decode: bool,
    attenuation: u32,
    spot: bool,
    spot_pattern: bool,
    /// The shininess's bits (a constant, so whole exponents become a fixed product).
    shininess: u32,
    normal_texels: u32,
    parallax: u32,
    parallax_shadow: u32,
    silhouettes: bool,
    write_depth: bool,
    ambient_occlusion: bool,
    /// The hit shaded with the heights' normal, not the normal map's.
    hit_normal_heights: bool,
    height_mipmaps: bool,
    positional_light: bool,
    occlusion_map: bool,
    decal_alpha: bool,
    vertex_color: bool,
    detail: u32,
}

impl Default for LitVariant {
    /// Every switch at its first value; shininess 8.
    fn default() -> Self {
        Self {
            self_shadow: 0,
            specular_shadow: 0,
            specular_filter: 0,
            normalize_cube: false,
            fragment_half_angle: false,
            gloss: 0,
            object_space: false,
            per_pixel_decode: false,
            attenuation: 0,
            spot: false,
            spot_pattern: false,
            shininess: 8.0f32.to_bits(),
            normal_texels: 0,
            parallax: 0,
            parallax_shadow: 0,
            silhouettes: false,
            write_depth: false,
            ambient_occlusion: false,
            hit_normal_heights: false,
            height_mipmaps: false,
            positional_light: false,
            occlusion_map: false,
            decal_alpha: false,
            vertex_color: false,
            detail: 0,
        }
    }
}

impl LitVariant {
    /// The variant `p` needs.
    pub fn of(p: &LitProgram) -> Self {
        Self {
            self_shadow: SELF_SHADOW.code(self_shadow_name(p.terms.self_shadow)),
            specular_shadow: SPECULAR_SHADOW.code(specular_shadow_name(p.terms.specular_shadow)),
            specular_filter: SPECULAR_FILTER.code(specular_filter_name(p.terms.specular_filter)),
            normalize_cube: p.normalize == Normalize::Cube,
            fragment_half_angle: p.half_angle == HalfAngle::Fragment,
            gloss: GLOSS.code(gloss_name(&p.gloss)),
            object_space: p.normal_space.lit_in_object_space(),
            per_pixel_decode: p.normal_space == bumpmap_core::scene::NormalSpace::TangentPerPixel,
            attenuation: ATTENUATION.code(attenuation_name(&p.light.attenuation)),
            spot: p.light.spot.is_some(),
            spot_pattern: p.light.spot.as_ref().is_some_and(|s| s.pattern.is_some()),
            shininess: p.terms.shininess.to_bits(),
            normal_texels: NORMAL_TEXELS.code(normal_texels_name(&p.normal_texels)),
            parallax: PARALLAX.code(parallax_name(p.parallax.as_ref().map(|x| x.parallax.method))),
            parallax_shadow: PARALLAX_SHADOW.code(parallax_shadow_name(
                p.parallax.as_ref().map_or(ParallaxShadow::Off, |x| x.parallax.options.shadow),
            )),
            silhouettes: p.parallax.as_ref().is_some_and(|x| x.parallax.options.silhouettes),
            write_depth: p.parallax.as_ref().is_some_and(|x| x.parallax.options.write_depth),
            ambient_occlusion: p.parallax.as_ref().is_some_and(|x| x.parallax.options.ambient_occlusion),
            hit_normal_heights: p.parallax.as_ref().is_some_and(|x| x.parallax.hit_normal() == HitNormal::Heights),
            height_mipmaps: p.parallax.is_some() && p.sampler.has_mipmaps(),
            positional_light: matches!(p.light.light, bumpmap_math::lighting::Light::Positional(_)),
            occlusion_map: p.occlusion.is_some(),
            decal_alpha: p.decal_alpha,
            vertex_color: p.vertex_color,
            detail: DETAIL.code(detail_name(p.detail.as_ref().map(|d| d.method))),
        }
    }

    /// The fragment entry point: `fs_lit_depth` where the program writes its depth.
    pub fn entry_point(&self) -> &'static str {
        if self.write_depth { "fs_lit_depth" } else { "fs_lit" }
    }

    /// The override constants by their names in `lit.wgsl`, with their values: the one list
    /// the pipeline's constants and the prelude's declarations are made from.
    pub(crate) fn overrides(&self) -> [(&'static str, Override); 25] {
        use Override::{Code, Flag, Float};
        [
            (SELF_SHADOW.name, Code(self.self_shadow)),
            (SPECULAR_SHADOW.name, Code(self.specular_shadow)),
            (SPECULAR_FILTER.name, Code(self.specular_filter)),
            ("NORMALIZE_CUBE", Flag(self.normalize_cube)),
            ("FRAGMENT_HALF_ANGLE", Flag(self.fragment_half_angle)),
            (GLOSS.name, Code(self.gloss)),
            ("OBJECT_SPACE", Flag(self.object_space)),
            ("PER_PIXEL_DECODE", Flag(self.per_pixel_decode)),
            (ATTENUATION.name, Code(self.attenuation)),
            ("SPOTLIGHT", Flag(self.spot)),
            ("SPOT_PATTERN", Flag(self.spot_pattern)),
            ("SHININESS", Float(f32::from_bits(self.shininess))),
            (NORMAL_TEXELS.name, Code(self.normal_texels)),
            (PARALLAX.name, Code(self.parallax)),
            (PARALLAX_SHADOW.name, Code(self.parallax_shadow)),
            ("SILHOUETTES", Flag(self.silhouettes)),
            ("WRITE_DEPTH", Flag(self.write_depth)),
            ("AMBIENT_OCCLUSION", Flag(self.ambient_occlusion)),
            ("HIT_NORMAL_HEIGHTS", Flag(self.hit_normal_heights)),
            ("HEIGHT_MIPMAPS", Flag(self.height_mipmaps)),
            ("POSITIONAL_LIGHT", Flag(self.positional_light)),
            ("OCCLUSION_MAP", Flag(self.occlusion_map)),
            ("DECAL_ALPHA", Flag(self.decal_alpha)),
            ("VERTEX_COLOR", Flag(self.vertex_color)),
            (DETAIL.name, Code(self.detail)),
        ]
    }

    /// The override constants as the pipeline takes them.
    pub fn constants(&self) -> Vec<(&'static str, f64)> {
        self.overrides()
            .into_iter()
            .map(|(name, value)| {
                let v = match value {
                    Override::Flag(b) => b as u32 as f64,
                    Override::Code(c) => c as f64,
                    Override::Float(x) => x as f64,
                };
                (name, v)
            })
            .collect()
    }
}

/// An override constant's value, typed as `lit.wgsl` declares it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Override {
    /// A `bool` switch.
    Flag(bool),
    /// A `u32` switch, one of its named values' codes.
    Code(u32),
    /// An `f32`.
    Float(f32),
}

/// A member of `lit.wgsl`'s `Lit` uniform block, each a `vec4<f32>`: the one list the WGSL
/// struct is generated from (`crate::prelude::lit_block`) and [`uniforms`] packs by, so the two
/// cannot disagree on the order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LitMember {
    Ambient,
    Diffuse,
    Specular,
    Attenuation,
    Spot,
    NormalScale,
    Texels,
    Parallax,
    Detail,
}

impl LitMember {
    /// Every member, in the block's order.
    pub(crate) const ALL: [LitMember; 9] = [
        LitMember::Ambient,
        LitMember::Diffuse,
        LitMember::Specular,
        LitMember::Attenuation,
        LitMember::Spot,
        LitMember::NormalScale,
        LitMember::Texels,
        LitMember::Parallax,
        LitMember::Detail,
    ];

    /// Its name in WGSL.
    pub(crate) fn name(self) -> &'static str {
        match self {
            LitMember::Ambient => "ambient",
            LitMember::Diffuse => "diffuse",
            LitMember::Specular => "specular",
            LitMember::Attenuation => "attenuation",
            LitMember::Spot => "spot",
            LitMember::NormalScale => "normal_scale",
            LitMember::Texels => "texels",
            LitMember::Parallax => "parallax",
            LitMember::Detail => "detail",
        }
    }

    /// What its components hold (the WGSL struct's comment).
    pub(crate) fn holds(self) -> &'static str {
        match self {
            LitMember::Ambient => "xyz: k_ambient · the ambient light.",
            LitMember::Diffuse => "xyz: k_diffuse · the light's colour.",
            LitMember::Specular => "xyz: k_specular · the light's colour.",
            LitMember::Attenuation => "Polynomial: constant, linear, quadratic; exponential: density in x.",
            LitMember::Spot => "x: cos(cutoff); y: exponent.",
            LitMember::NormalScale => {
                "xy: the texture-coordinate scale of a map made for the surface (1, 1 for one that repeats with the texture)."
            }
            LitMember::Texels => "x: an offset map's range; yz: the derivatives' scale (NormalTexels::Derivatives).",
            LitMember::Parallax => {
                "Heights as geometry: x the layers, y the depth (object units per unit of height), z far / (far - near)."
            }
            LitMember::Detail => "The detail map: x its repeat over the normal map's coordinates, y its strength.",
        }
    }

    /// Its value for `p`.
    fn value(self, p: &LitProgram) -> [f32; 4] {
        let LitTerms { ambient, diffuse, specular, .. } = p.terms;
        match self {
            LitMember::Ambient => ambient.extend(0.0).to_array(),
            LitMember::Diffuse => diffuse.extend(0.0).to_array(),
            LitMember::Specular => specular.extend(0.0).to_array(),
            LitMember::Attenuation => match p.light.attenuation {
                Attenuation::None => [0.0; 4],
                Attenuation::Polynomial { constant, linear, quadratic } => [constant, linear, quadratic, 0.0],
                Attenuation::Exponential { density } | Attenuation::ExponentialSquared { density } => {
                    [density, 0.0, 0.0, 0.0]
                }
            },
            LitMember::Spot => match &p.light.spot {
                Some(s) => [s.cutoff_degrees.to_radians().cos(), s.exponent, 0.0, 0.0],
                None => [0.0; 4],
            },
            LitMember::NormalScale => {
                let scale = p.normal_space.texcoord_scale().to_array();
                [scale[0], scale[1], 0.0, 0.0]
            }
            LitMember::Texels => match p.normal_texels {
                NormalTexels::UnitVector => [0.0; 4],
                NormalTexels::Offset { range } => [range, 0.0, 0.0, 0.0],
                NormalTexels::Derivatives { range, scale } => [range, scale.x, scale.y, 0.0],
            },
            LitMember::Parallax => match &p.parallax {
                Some(x) => [x.parallax.options.layers as f32, x.depth, x.depth_range, 0.0],
                None => [0.0; 4],
            },
            LitMember::Detail => match &p.detail {
                Some(d) => [d.repeat, d.strength, 0.0, 0.0],
                None => [0.0; 4],
            },
        }
    }
}

/// `lit.wgsl`'s `Lit` uniform block for `p`: each [`LitMember`] in order, 16 bytes each.
pub fn uniforms(p: &LitProgram) -> Vec<u8> {
    LitMember::ALL.iter().flat_map(|m| m.value(p)).flat_map(f32::to_le_bytes).collect()
}
