//! What the reference renderer refuses, as values.

/// Why a reference image could not be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// An object with no analytic surface behind it (a loaded mesh).
    #[error(
        "object {object} is a loaded mesh: the reference needs an analytic surface (torus, wall, floor, patch, sphere)"
    )]
    NoSurface {
        /// Index into the scene's objects.
        object: usize,
    },
    /// An object whose normal map was given as it is, with no heights to differentiate.
    #[error(
        "object {object}'s normal map was given as it is: the reference differentiates a height field, and it has none"
    )]
    NoHeights {
        /// Index into the scene's objects.
        object: usize,
    },
    /// The displaced reference of an object without heights as geometry.
    #[error("object {object} has no heights as geometry: the displaced reference carves the surface by them")]
    NoDisplacement {
        /// Index into the scene's objects.
        object: usize,
    },
    /// Heights whose min–max levels could not be made.
    #[error("object {object}'s heights: {error}")]
    Heights {
        /// Index into the scene's objects.
        object: usize,
        /// Why.
        error: bumpmap_math::HeightMipsError,
    },
    /// A curved surface whose tessellation (a vertex per texel corner) would not fit.
    #[error(
        "object {object}'s carved surface is {texels} texels, {}: the displaced reference tessellates curved surfaces a vertex per texel, at most {max} texels (use a smaller height field or fewer repeats)",
        bumpmap_math::buffer::Bytes(*bytes)
    )]
    Tessellation {
        /// Index into the scene's objects.
        object: usize,
        /// Texels it would have.
        texels: u64,
        /// Bytes they would need.
        bytes: u64,
        /// The most allowed.
        max: usize,
    },
    /// A spotlight that projects a pattern.
    #[error("light {light} projects a spotlight pattern, which the reference does not sample")]
    SpotPattern {
        /// Index into the scene's lights.
        light: usize,
    },
    /// Zero samples per pixel, or more than the limit.
    #[error("samples per pixel must be in 1..={max}, got {got}")]
    SamplesPerPixel {
        /// What was asked.
        got: usize,
        /// The most allowed.
        max: usize,
    },
    /// An empty image, or one larger than the limit.
    #[error("image size {width}x{height} is outside 1..={max} a side")]
    Size {
        /// Width asked.
        width: usize,
        /// Height asked.
        height: usize,
        /// The largest side.
        max: usize,
    },
}
