//! The single pass (Kilgard §6's prediction; the Cg Tutorial's fragment programs): one float
//! pass per light evaluating [`crate::shading`] per fragment.
//!
//! The first light's pass draws with depth LESS and adds the ambient term; each further light
//! adds its own pass with `glBlendFunc(GL_ONE, GL_ONE)` and depth EQUAL, so the framebuffer is
//! 8-bit between lights as on the hardware. Attenuation is the per-vertex distance
//! interpolated, not the per-fragment distance.

use std::sync::Arc;

use bumpmap_math::Rgba8Mips;

use crate::detail::{DetailLayer, MAX_DETAIL_REPEAT};
use crate::error::{CoreError, Feature};
use crate::parallax::{MAX_LAYERS, Parallax, ParallaxMethod};
use crate::scene::{AlphaMode, Attenuation, Scene, SceneLight};
use crate::shading::LitTerms;
pub use crate::shading::{SelfShadow, SpecularFilter, SpecularShadow};
use crate::state::{Blend, BlendFactor, PassState, Sampler};
use crate::technique::{LitProgram, ParallaxProgram, Pass, Program};

/// The technique's name.
pub const NAME: &str = "single-pass";

/// How the interpolated L and H are renormalized per fragment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Normalize {
    /// `normalize()` in float.
    #[default]
    Math,
    /// A lookup in the normalization cube map, expanded as `2x − 1` (the paper's way).
    Cube,
}

/// Where the half-angle vector comes from (Cg Tutorial §8.1.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum HalfAngle {
    /// Computed per vertex (Appendix C) and interpolated.
    #[default]
    Vertex,
    /// `normalize(L̂ + V̂)` from the interpolated L and V.
    Fragment,
}

bumpmap_math::named!(Normalize {
    Math => "math": "normalize() in float",
    Cube => "cube": "the normalization cube map, as the paper does",
});

bumpmap_math::named!(HalfAngle {
    Vertex => "vertex": "per vertex, interpolated (Appendix C)",
    Fragment => "fragment": "normalize(L̂ + V̂) per fragment (Cg Tutorial §8.1.4)",
});

/// Where the gloss (specular scale) comes from (Cg Tutorial §8.5.2).
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Gloss {
    /// No gloss: the specular term at full strength.
    #[default]
    None,
    /// The decal's alpha channel.
    DecalAlpha,
    /// The red channel of a gloss map with the decal's texture coordinates.
    Map(Arc<Rgba8Mips>),
}

/// Options of the single-pass technique. The defaults are the paper's settings except for the
/// math normalization.
#[derive(Clone, Debug, PartialEq)]
pub struct SinglePassOptions {
    /// The normal map's, decal's and gloss map's filtering.
    pub sampler: Sampler,
    /// Per-fragment renormalization of L and H.
    pub normalize: Normalize,
    /// The self-shadowing factor.
    pub self_shadow: SelfShadow,
    /// Per-vertex or per-fragment H.
    pub half_angle: HalfAngle,
    /// The specular term's gating.
    pub specular_shadow: SpecularShadow,
    /// The gloss source.
    pub gloss: Gloss,
    /// The cube map's face size for [`Normalize::Cube`].
    pub cube_size: usize,
    /// How the specular exponent answers the filtered normal's length (Toksvig, or none).
    pub specular_filter: SpecularFilter,
    /// The roughness map [`SpecularFilter::RoughnessMap`] reads: perceptual roughness in red,
    /// at the normal map's size, every level its own (a file `bumpmap normalmap --roughness-out`
    /// wrote, say). `None`: the renderers make it from each normal map's levels and the
    /// material's shininess as that command does ([`crate::shading::roughness_texture`]).
    pub roughness_map: Option<Arc<Rgba8Mips>>,
    /// Heights as geometry: the march that finds where each pixel's ray meets the material's
    /// heights, or `None` to read the maps where the ray enters the polygon.
    pub parallax: Option<Parallax>,
    /// A detail normal map laid over every material's normal map per fragment
    /// ([`crate::detail`]), or `None`.
    pub detail: Option<DetailLayer>,
}

impl Default for SinglePassOptions {
    fn default() -> Self {
        Self {
            sampler: Sampler::TRILINEAR_REPEAT,
            normalize: Normalize::Math,
            self_shadow: SelfShadow::Ramp,
            half_angle: HalfAngle::Vertex,
            specular_shadow: SpecularShadow::Kilgard,
            gloss: Gloss::None,
            cube_size: 32,
            specular_filter: SpecularFilter::None,
            roughness_map: None,
            parallax: None,
            detail: None,
        }
    }
}

/// Checks what the options and the scene's lights and materials allow.
pub fn validate(scene: &Scene, options: &SinglePassOptions) -> Result<(), CoreError> {
    for object in &scene.objects {
        let m = &object.material;
        if !(m.shininess > 0.0 && m.shininess.is_finite()) {
            return Err(CoreError::out_of_range("shininess", m.shininess, "a positive number"));
        }
        if let Gloss::Map(g) = &options.gloss {
            match &m.decal {
                Some(d) if (d.width(), d.height()) != (g.width(), g.height()) => {
                    return Err(CoreError::GlossSize {
                        gloss: (g.width(), g.height()),
                        decal: (d.width(), d.height()),
                    });
                }
                _ => {}
            }
        }
        if options.gloss == Gloss::DecalAlpha && m.decal.is_none() {
            return Err(CoreError::GlossNeedsDecal);
        }
        // The slopes' moments, the march, the detail's blend and Peercy's derivatives are
        // tangent-space work that the per-vertex frame's L and H meet; decoded per pixel, L and
        // H are in object space.
        let tangent_work = matches!(options.specular_filter, SpecularFilter::Lean | SpecularFilter::Clean)
            || options.parallax.is_some()
            || options.detail.is_some()
            || matches!(m.normal_texels, crate::scene::NormalTexels::Derivatives { .. });
        if m.normal_space == crate::scene::NormalSpace::TangentPerPixel && tangent_work {
            return Err(CoreError::Unsupported { technique: NAME, feature: Feature::PerPixelDecode });
        }
        if matches!(options.specular_filter, SpecularFilter::Lean | SpecularFilter::Clean)
            && (m.normal_space.is_object() || m.normal_texels != crate::scene::NormalTexels::UnitVector)
        {
            return Err(CoreError::Unsupported { technique: "single-pass", feature: Feature::LeanFilter });
        }
        if options.specular_filter == SpecularFilter::RoughnessMap {
            if m.normal_texels != crate::scene::NormalTexels::UnitVector {
                return Err(CoreError::Unsupported { technique: "single-pass", feature: Feature::RoughnessFilter });
            }
            let size = |t: &Rgba8Mips| (t.width(), t.height());
            if let Some(r) = options.roughness_map.as_ref().or(m.roughness_map.as_ref())
                && size(r) != size(&m.normal_map)
            {
                return Err(CoreError::RoughnessSize { roughness: size(r), normal_map: size(&m.normal_map) });
            }
        }
    }
    if let Some(p) = &options.parallax {
        validate_parallax(scene, p)?;
    }
    if let Some(d) = &options.detail {
        validate_detail(scene, d)?;
    }
    validate_lights(&scene.lights)
}

/// The most lights a scene may have: each is one more pass over the frame (Kilgard §5.4's
/// multipass, one per light) or one more term per pixel, so the time grows with the count;
/// 64 is eight times what OpenGL 1.2 guarantees (`GL_MAX_LIGHTS` ≥ 8).
pub const MAX_LIGHTS: usize = 64;

/// Checks the number of lights against [`MAX_LIGHTS`] (before looking at any of them), then
/// each light.
pub fn validate_lights(lights: &[SceneLight]) -> Result<(), CoreError> {
    if lights.len() > MAX_LIGHTS {
        return Err(CoreError::out_of_range(
            "the number of lights",
            lights.len(),
            "at most 64 (each light is one more pass over the frame)",
        ));
    }
    lights.iter().try_for_each(validate_light)
}

/// Checks heights as geometry: every material has heights (with min–max levels for the exact
/// walk) under a tangent-space map of unit normals, and the layer count is in range.
pub fn validate_parallax(scene: &Scene, p: &Parallax) -> Result<(), CoreError> {
    if !(1..=MAX_LAYERS).contains(&p.options.layers) {
        return Err(CoreError::out_of_range("the layer count", p.options.layers, "in 1..=256"));
    }
    for object in &scene.objects {
        let m = &object.material;
        if m.normal_space != crate::scene::NormalSpace::Tangent
            || m.normal_texels != crate::scene::NormalTexels::UnitVector
        {
            return Err(CoreError::Unsupported { technique: NAME, feature: Feature::Parallax });
        }
        let Some(heights) = &m.heights else {
            return Err(CoreError::Needs { technique: NAME, requirement: crate::Requirement::Heights });
        };
        if p.method == ParallaxMethod::Exact && heights.minmax().is_none() {
            return Err(CoreError::NoMinMax { technique: "height-exact" });
        }
    }
    Ok(())
}

/// Checks a detail map: its repeat and strength, and that every material's normal map is a
/// tangent-space map of unit normals (the blends compose two tangent-space normals).
pub fn validate_detail(scene: &Scene, d: &DetailLayer) -> Result<(), CoreError> {
    if !(d.repeat > 0.0 && d.repeat <= MAX_DETAIL_REPEAT) {
        return Err(CoreError::out_of_range("the detail's repeat", d.repeat, "in (0, 1024]"));
    }
    if !(d.strength.is_finite() && d.strength >= 0.0) {
        return Err(CoreError::out_of_range("the detail's strength", d.strength, "finite and not negative"));
    }
    for object in &scene.objects {
        let m = &object.material;
        if m.normal_space != crate::scene::NormalSpace::Tangent
            || m.normal_texels != crate::scene::NormalTexels::UnitVector
        {
            return Err(CoreError::Unsupported { technique: NAME, feature: Feature::DetailMap });
        }
    }
    Ok(())
}

const _: () = assert!(MAX_DETAIL_REPEAT == 1024.0, "the message of validate_detail says 1024");

const _: () = assert!(MAX_LIGHTS == 64, "the message of validate_lights says 64");

/// Checks one light's parameters.
pub fn validate_light(light: &SceneLight) -> Result<(), CoreError> {
    let bad = |what, value: String, expected| Err(CoreError::OutOfRange { what, value, expected });
    if !light.color.is_finite() || light.color.min_element() < 0.0 {
        return bad("a light colour", light.color.to_string(), "finite and not negative");
    }
    match light.attenuation {
        Attenuation::Polynomial { constant, linear, quadratic } => {
            if [constant, linear, quadratic].iter().any(|c| !(c.is_finite() && *c >= 0.0))
                || constant + linear + quadratic == 0.0
            {
                return bad(
                    "attenuation coefficients",
                    format!("{constant},{linear},{quadratic}"),
                    "≥ 0 and not all zero",
                );
            }
        }
        Attenuation::Exponential { density } | Attenuation::ExponentialSquared { density } => {
            if !(density.is_finite() && density >= 0.0) {
                return bad("attenuation density", density.to_string(), "≥ 0");
            }
        }
        Attenuation::None => {}
    }
    if let Some(spot) = &light.spot {
        if !(spot.cutoff_degrees > 0.0 && spot.cutoff_degrees < 90.0) {
            return bad("a spotlight cutoff", spot.cutoff_degrees.to_string(), "in (0, 90) degrees");
        }
        if !(spot.exponent.is_finite() && spot.exponent >= 0.0) {
            return bad("a spotlight exponent", spot.exponent.to_string(), "≥ 0");
        }
        if !(spot.direction.length() > 0.0 && spot.direction.is_finite()) {
            return bad("a spotlight direction", spot.direction.to_string(), "a finite non-zero vector");
        }
        if matches!(light.light, bumpmap_math::lighting::Light::Directional(_)) {
            return bad("a spotlight's light", "directional".into(), "positional");
        }
    }
    Ok(())
}

/// The passes of `scene`: per object, one per light.
pub fn passes(scene: &Scene, options: &SinglePassOptions) -> Result<Vec<Pass>, CoreError> {
    validate(scene, options)?;
    let mut passes = Vec::new();
    for (o, object) in scene.objects.iter().enumerate() {
        let m = &object.material;
        let blended = m.alpha == AlphaMode::Blend;
        for (l, light) in scene.lights.iter().enumerate() {
            let terms =
                LitTerms::of(m, light, l == 0, options.self_shadow, options.specular_shadow, options.specular_filter);
            let program = LitProgram {
                normal_map: m.normal_map.clone(),
                normal_space: m.normal_space,
                normal_texels: m.normal_texels,
                decal: m.decal.clone(),
                gloss: options.gloss.clone(),
                // A map given explicitly, else the material's own (a glTF's roughness), else none:
                // the backend makes one from the normal map.
                roughness_map: match options.specular_filter {
                    SpecularFilter::RoughnessMap => options.roughness_map.clone().or_else(|| m.roughness_map.clone()),
                    _ => None,
                },
                sampler: options.sampler.for_material(&m.sampler),
                detail: options.detail.clone(),
                occlusion: m.occlusion.clone(),
                decal_alpha: blended,
                vertex_color: object.mesh.has_colors(),
                terms,
                normalize: options.normalize,
                cube_size: options.cube_size,
                half_angle: options.half_angle,
                light: light.clone(),
                parallax: match options.parallax {
                    Some(parallax) => {
                        let heights = m.heights.clone().expect("validated: every material has heights");
                        let horizons = if parallax.reads_horizons() { Some(heights.horizons()?) } else { None };
                        Some(ParallaxProgram {
                            parallax,
                            heights,
                            horizons,
                            depth: m.depth,
                            depth_range: scene.camera.far / (scene.camera.far - scene.camera.near),
                        })
                    }
                    None => None,
                },
            };
            let state = match (l == 0, blended) {
                (true, false) => PassState::OPAQUE,
                (false, false) => PassState::equal(Blend::ADD),
                // α·surface + (1 − α)·behind, each further light's terms added times α.
                (true, true) => PassState {
                    blend: Blend::new(BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha),
                    ..PassState::OPAQUE
                },
                (false, true) => PassState::equal(Blend::new(BlendFactor::SrcAlpha, BlendFactor::One)),
            };
            passes.push(Pass { object: o, light: l, snapshot: None, state, program: Program::Lit(Box::new(program)) });
        }
    }
    Ok(passes)
}
