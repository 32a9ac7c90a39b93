//! The reference (ground truth) as a technique: what it is asked for. It is not a pass list —
//! `bumpmap-reference` samples the exact surface many times per pixel — so it has options and a
//! name here, and [`crate::Technique::passes`] refuses it.

use crate::shading::{SelfShadow, SpecularShadow};

/// The technique's name.
pub const NAME: &str = "reference";

/// The most samples per pixel a reference takes.
pub const MAX_SAMPLES_PER_PIXEL: usize = 4096;

/// What the reference is asked for; the lighting switches should be those of the techniques it
/// is compared with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceOptions {
    /// Samples per pixel, in 1..=[`MAX_SAMPLES_PER_PIXEL`].
    pub samples_per_pixel: usize,
    /// Which sample pattern (each pixel's rotation of the sequence): another seed gives an
    /// independent estimate of the same image; 0 is the default pattern.
    pub seed: u32,
    /// The self-shadowing factor of Eq. 11.
    pub self_shadow: SelfShadow,
    /// The specular term's gating.
    pub specular_shadow: SpecularShadow,
    /// Heights as geometry: the surface displaced by the material's heights and depth, rays
    /// traced to it, instead of the base surface shaded with Blinn's normal.
    pub displaced: bool,
    /// With `displaced`: a shadow ray from every sample toward each light, against the same
    /// displaced surface.
    pub shadow_rays: bool,
}

impl Default for ReferenceOptions {
    /// 64 samples per pixel; the paper's Eq. 12 ramp and specular gating; the base surface.
    fn default() -> Self {
        Self {
            samples_per_pixel: 64,
            seed: 0,
            self_shadow: SelfShadow::Ramp,
            specular_shadow: SpecularShadow::Kilgard,
            displaced: false,
            shadow_rays: false,
        }
    }
}
