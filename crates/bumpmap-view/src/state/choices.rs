//! What a viewer's keys choose, apart from the scene they are applied to: the choices that
//! prepare the scene again ([`Choices`]), the view that only redraws ([`View`]), and what the
//! window does next ([`Effect`]). What this module does not do: apply a key (`super::Viewer`).

use bumpmap::bumpmap_core::detail::BlendMethod;
use bumpmap::{ParallaxShadow, SpecularFilter};

/// The mip levels a technique samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mips {
    /// The length of the averaged normal kept in alpha (Kilgard §5.3).
    LengthFactor,
    /// Every level renormalized (alpha 1), as most tools make them.
    Renormalized,
    /// Level 0 only (`GL_LINEAR`, no mipmaps): the shimmer mipmapping removes.
    None,
}

impl Mips {
    pub(super) fn next(self) -> Self {
        match self {
            Mips::LengthFactor => Mips::Renormalized,
            Mips::Renormalized => Mips::None,
            Mips::None => Mips::LengthFactor,
        }
    }

    pub(super) fn name(self) -> &'static str {
        match self {
            Mips::LengthFactor => "length factor",
            Mips::Renormalized => "renormalized",
            Mips::None => "none",
        }
    }
}

/// Everything the user has chosen that changes the maps or the technique: a change here
/// prepares the scene again.
#[derive(Clone, Debug, PartialEq)]
pub struct Choices {
    /// Index into [`TechniqueName::ALL`].
    pub technique: usize,
    /// Index into [`Viewer::scenes`](super::Viewer::scenes).
    pub scene: usize,
    /// The decal pass (Kilgard Figure 12) drawn.
    pub decal: bool,
    /// The diffuse pass drawn.
    pub diffuse: bool,
    /// The specular pass drawn.
    pub specular: bool,
    /// Self-shadowing (Kilgard Eq. 11/12).
    pub self_shadow: bool,
    /// The mip levels sampled.
    pub mips: Mips,
    /// Normalization by the cube map rather than by math (the single pass).
    pub cube: bool,
    /// Nearest texels rather than trilinear filtering.
    pub nearest: bool,
    /// The specular filter (the single pass): none, Toksvig's, the roughness map's, LEAN,
    /// CLEAN.
    pub specular_filter: SpecularFilter,
    /// The bump scale: a height field's step height, or a normal map's slope factor.
    pub bump_scale: f32,
    /// The specular exponent.
    pub shininess: f32,
    /// Heights as geometry: how deep (object units), or `None` for the options' (`--depth`, or
    /// the bump scale's).
    pub depth: Option<f32>,
    /// The marches' layers.
    pub layers: u32,
    /// The marches' self-shadowing.
    pub parallax_shadow: ParallaxShadow,
    /// How the detail map (`--detail-map`) is laid over the normal map, or `None`: not at all.
    pub detail: Option<BlendMethod>,
}

/// Where the light and the camera are, and what is shown over the image: changes here only
/// redraw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The light's orbit stopped.
    pub paused: bool,
    /// How far round its orbit the light is, in turns.
    pub turns: f32,
    /// The light tilted toward the up axis, radians (right-drag).
    pub light_tilt: f32,
    /// The camera turned about its up axis, radians (left-drag).
    pub yaw: f32,
    /// The camera tilted toward its up axis, radians.
    pub pitch: f32,
    /// The camera's distance as a multiple of its starting one (the wheel).
    pub zoom: f32,
    /// The triangles' edges drawn.
    pub wireframe: bool,
    /// The frame rate shown.
    pub frame_rate: bool,
    /// The help overlay shown.
    pub help: bool,
}

impl Default for View {
    fn default() -> Self {
        Self {
            paused: false,
            turns: 0.0,
            light_tilt: 0.0,
            yaw: 0.0,
            pitch: 0.0,
            zoom: 1.0,
            wireframe: false,
            frame_rate: false,
            help: false,
        }
    }
}

/// What the window has to do after an action.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Effect {
    /// Draw again.
    Redraw,
    /// Write a screenshot.
    Screenshot,
    /// Open the other backend.
    SwitchBackend,
    /// Close.
    Quit,
}
