//! Errors of the core: a scene that cannot be built, a technique asked for what it cannot do,
//! a value out of its range. They name values, never command-line flags.

use bumpmap_math::normalmap::NormalMapError;

use crate::combiners::CombinerError;

/// Something a technique cannot do, for [`CoreError::Unsupported`].
#[derive(Clone, Debug, PartialEq)]
pub enum Feature {
    /// A specular exponent other than the combiners' fixed 8.
    Shininess(f32),
    /// A gloss map.
    Gloss,
    /// Attenuation with distance.
    Attenuation,
    /// A spotlight cone or pattern.
    Spotlight,
    /// Normalizing L and H by math rather than by the cube map.
    NormalizeByMath,
    /// A per-fragment half-angle vector.
    FragmentHalfAngle,
    /// A self-shadowing factor other than Eq. 12's ramp or none.
    SelfShadowStep,
    /// An object-space normal map.
    ObjectSpace,
    /// A tangent-space map decoded per pixel (MikkTSpace's decode), which needs the frame at
    /// each fragment.
    PerPixelDecode,
    /// A specular colour other than white.
    SpecularColor,
    /// More than one light.
    MultipleLights,
    /// A bump scale the combiners' output scales cannot make.
    BumpScale(f32),
    /// A material without the height field as a texture.
    HeightMap,
    /// An offset map, whose normal must be renormalized per pixel.
    OffsetMap,
    /// A tangent-space map made for one surface, addressed across the whole surface rather
    /// than with the repeating texture coordinates.
    SurfaceMap,
    /// The LEAN or CLEAN filter on a map that has no tangent-space slopes (object space, or
    /// offsets).
    LeanFilter,
    /// The roughness-map filter made from a map whose alpha is not a normal's length (offsets
    /// or derivatives).
    RoughnessFilter,
    /// Heights as geometry under a map that is not a tangent-space map of unit normals.
    Parallax,
    /// A cut-out material (alpha MASK) with heights as geometry that write their own depth.
    MaskWithDepth,
    /// A detail normal map over a map that is not a tangent-space map of unit normals.
    DetailMap,
}

impl std::fmt::Display for Feature {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Feature::Shininess(s) => write!(f, "a shininess of {s} (its combiners square three times: 8 only)"),
            Feature::Gloss => f.write_str("a gloss map"),
            Feature::Attenuation => f.write_str("attenuation"),
            Feature::Spotlight => f.write_str("spotlights"),
            Feature::NormalizeByMath => f.write_str("normalization by math (it normalizes by the cube map)"),
            Feature::FragmentHalfAngle => f.write_str("a per-fragment half-angle (H is per vertex)"),
            Feature::SelfShadowStep => f.write_str("a step self-shadowing term (Eq. 12's ramp or none)"),
            Feature::ObjectSpace => f.write_str("object-space lighting (its self-shadowing reads tangent-space L_z)"),
            Feature::PerPixelDecode => {
                f.write_str("MikkTSpace's per-pixel decode (this lights in the per-vertex tangent frame)")
            }
            Feature::SpecularColor => f.write_str("a specular colour other than white or black"),
            Feature::MultipleLights => f.write_str("more than one light"),
            Feature::BumpScale(s) => write!(f, "a bump scale of {s} (its combiners scale by 1, 2 or 4)"),
            Feature::HeightMap => f.write_str("a material without its height field (a normal map given as it is)"),
            Feature::OffsetMap => f.write_str("an offset map (its combiners cannot renormalize N + D per pixel)"),
            Feature::LeanFilter => f.write_str(
                "the LEAN or CLEAN specular filter on an object-space or offset map (its moments are the slopes of a tangent-space map of unit normals)",
            ),
            Feature::RoughnessFilter => f.write_str(
                "the roughness-map specular filter on an offset or derivative map (its roughness comes from the lengths a map of unit normals keeps in alpha)",
            ),
            Feature::Parallax => f.write_str(
                "heights as geometry with an object-space, offset or derivative map (the marches read a tangent-space map of unit normals at the hit)",
            ),
            Feature::MaskWithDepth => f.write_str(
                "a cut-out (alpha MASK) material with heights as geometry writing their depth (the cut is a depth pass the march would move)",
            ),
            Feature::DetailMap => f.write_str(
                "a detail normal map over an object-space, offset or derivative map (the blends compose two tangent-space maps of unit normals)",
            ),
            Feature::SurfaceMap => f.write_str(
                "a normal map made for one surface (its passes read every texture with the repeating coordinates)",
            ),
        }
    }
}

/// Why a scene or a technique's passes could not be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CoreError {
    /// The height field could not become a normal map.
    #[error("height field: {0}")]
    HeightField(#[from] NormalMapError),
    /// Heights that cannot be geometry.
    #[error("heights: {0}")]
    HeightMips(#[from] bumpmap_math::HeightMipsError),
    /// The horizon map could not be made or was refused.
    #[error("horizon map: {0}")]
    Horizons(#[from] bumpmap_math::HorizonError),
    /// Heights as geometry are read with the normal map's texture coordinates and levels, so
    /// their sizes must agree.
    #[error("the heights are {}x{} but the normal map is {}x{}: they are read at the same texture coordinates and levels and must be the same size", .heights.0, .heights.1, .normal_map.0, .normal_map.1)]
    HeightsSize {
        /// The heights' size.
        heights: (usize, usize),
        /// The normal map's size.
        normal_map: (usize, usize),
    },
    /// The exact walk without the min–max levels it walks.
    #[error(
        "{technique} walks the heights' min–max levels, and these heights have none (a height map written without them)"
    )]
    NoMinMax {
        /// The technique's name.
        technique: &'static str,
    },
    /// A buffer sized by the scene (the vertex stage's outputs) is more than the machine gives.
    #[error(transparent)]
    OutOfMemory(#[from] bumpmap_math::buffer::OutOfMemory),
    /// Object-space, surface-dependent and derivative maps are made from, or read with, an
    /// analytic surface.
    #[error("{} is made for the built-in surfaces, not for meshes", .0.describe())]
    MapNeedsSurface(crate::spec::BumpMap),
    /// A register-combiner setup broke a rule of the specification.
    #[error("invalid register-combiner setup: {0}")]
    Combiner(#[from] CombinerError),
    /// The technique cannot render what the scene or the options ask for.
    #[error("the {technique} technique cannot do {feature}")]
    Unsupported {
        /// The technique's name.
        technique: &'static str,
        /// What it cannot do.
        feature: Feature,
    },
    /// A value outside its range.
    #[error("{what} must be {expected}, got {value}")]
    OutOfRange {
        /// What the value is.
        what: &'static str,
        /// The value as given.
        value: String,
        /// The accepted range, in words.
        expected: &'static str,
    },
    /// A gloss map and a decal share texture coordinates, so their sizes must agree.
    #[error("the gloss map is {}x{} but the decal is {}x{}: they share texture coordinates and must be the same size", .gloss.0, .gloss.1, .decal.0, .decal.1)]
    GlossSize {
        /// The gloss map's size.
        gloss: (usize, usize),
        /// The decal's size.
        decal: (usize, usize),
    },
    /// A roughness map is read with the normal map's texture coordinates and levels, so their
    /// sizes must agree.
    #[error("the roughness map is {}x{} but the normal map is {}x{}: it is read with the normal map's coordinates and levels and must be the same size", .roughness.0, .roughness.1, .normal_map.0, .normal_map.1)]
    RoughnessSize {
        /// The roughness map's size.
        roughness: (usize, usize),
        /// The normal map's size.
        normal_map: (usize, usize),
    },
    /// Gloss from the decal's alpha without a decal.
    #[error("gloss from the decal's alpha needs a decal")]
    GlossNeedsDecal,
    /// Offset, derivative and surface-dependent maps are made from heights, which a normal map
    /// given as it is does not have.
    #[error("{} is made from a height field, not from a normal map", .0.describe())]
    MapNeedsHeights(crate::spec::BumpMap),
    /// A model's part names a material the model does not have.
    #[error("part {part} draws with material {material}, but the model has {materials}")]
    PartMaterial {
        /// The part's index.
        part: usize,
        /// The material it names.
        material: usize,
        /// How many materials the model has.
        materials: usize,
    },
    /// The reference is not a list of passes.
    #[error("the reference is not drawn as passes: it samples the exact surface (bumpmap-reference draws it)")]
    NotPasses,
    /// A named technique that cannot draw the scene.
    #[error("{technique} needs {requirement}")]
    Needs {
        /// The technique's catalogue name.
        technique: &'static str,
        /// What the scene lacks.
        requirement: crate::requirement::Requirement,
    },
    /// A name the catalogue does not know.
    #[error("unknown technique '{name}': use one of {known}")]
    UnknownTechnique {
        /// The name as given.
        name: String,
        /// Every name the catalogue knows, comma-separated.
        known: String,
    },
    /// The eye at the point looked at: the camera has no direction to look in.
    #[error("the eye {eye} is at the point looked at: the camera needs a direction to look in")]
    EyeAtTarget {
        /// Where both are.
        eye: glam::Vec3,
    },
}

impl CoreError {
    /// An [`CoreError::OutOfRange`] for `value`.
    pub fn out_of_range(what: &'static str, value: impl std::fmt::Display, expected: &'static str) -> Self {
        CoreError::OutOfRange { what, value: value.to_string(), expected }
    }
}
