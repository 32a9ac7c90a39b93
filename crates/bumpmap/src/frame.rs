//! One frame from typed options, as `bumpmap render` draws it and Python's `render` returns it:
//! the options set up (files read, values checked), the technique prepared once, then the frame
//! drawn by a renderer the caller keeps, and refused when it came out black.
//!
//! ```
//! use bumpmap::Renderer;
//! use bumpmap::frame::{FrameRequest, draw_frame, prepare_frame};
//! use bumpmap::options::Given;
//!
//! let request = FrameRequest { size: (32, 32), ..FrameRequest::default() };
//! let prepared = prepare_frame(&request, &Given::default()).unwrap();
//! let mut renderer = Renderer::new(request.backend_for()).unwrap();
//! let frame = draw_frame(&mut renderer, &prepared, request.passes).unwrap();
//! assert_eq!((frame.image.width, frame.image.height), (32, 32));
//! assert!(prepared.depth_notes.is_empty(), "no depth was asked for");
//! ```
//!
//! [`write_frame`] writes a frame as `render -o` does (its own module, `files`).
//!
//! What this module does not do: open a device (the caller chooses the renderer and keeps it
//! between frames) or say anything: what a command would print comes back as
//! data ([`DepthNote`], the set-up's notes, [`FrameError`]) for the command or a script to word.

mod files;

pub use files::{rgb, write_frame};

use bumpmap_core::CoreError;
use bumpmap_cpu::CpuError;
use bumpmap_math::buffer::OutOfMemory;
use bumpmap_math::normalmap::NormalMapError;

use crate::options::{Given, SceneOptions, SetUp, SetupError};
use crate::{
    BackendChoice, BumpSource, Error, Prepared, Renderer, Rgba8Image, Scene, SceneSpec, Technique, TechniqueName,
};

/// The square frame's side when none is given.
pub const DEFAULT_SIZE: usize = 512;

/// The longest side a frame may have, the reference's limit (the CPU framebuffer's limit on the
/// pixel count applies as well: [`Renderer::check_size`]).
pub const MAX_SIDE: usize = bumpmap_reference::MAX_SIDE;

/// A frame to draw, typed: the scene options, the frame's size, the backend, and whether each of
/// kilgard's passes is kept.
#[derive(Clone, Debug)]
pub struct FrameRequest {
    /// What is drawn and how.
    pub options: SceneOptions,
    /// The frame's width and height in pixels.
    pub size: (usize, usize),
    /// What draws it (the reference always draws on the CPU: [`FrameRequest::backend_for`]).
    pub backend: BackendChoice,
    /// Keep the framebuffer after each of kilgard's passes (Kilgard's Figure 12).
    pub passes: bool,
}

impl Default for FrameRequest {
    /// The default scene, 512×512, on the CPU, no passes kept.
    fn default() -> Self {
        FrameRequest {
            options: SceneOptions::default(),
            size: (DEFAULT_SIZE, DEFAULT_SIZE),
            backend: BackendChoice::Cpu,
            passes: false,
        }
    }
}

impl FrameRequest {
    /// The backend that draws it: the one asked for, but the CPU for the reference, which
    /// samples the exact surface there whatever the backend.
    pub fn backend_for(&self) -> BackendChoice {
        if self.options.technique.technique.is_reference() { BackendChoice::Cpu } else { self.backend }
    }
}

/// The sizes that make a scene big, for a message to name when it does not fit: what a user
/// can make smaller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneSize {
    /// The bump texture's width and height.
    pub bumps: (usize, usize),
    /// A decal given by the user (not the bricks' own), its level 0.
    pub decal: Option<(usize, usize)>,
    /// The built-in surface's tessellation.
    pub tessellation: Option<(usize, usize)>,
}

impl SceneSize {
    /// The sizes of `spec`.
    pub fn of(spec: &SceneSpec) -> Self {
        let decal = match &spec.params.decal {
            Some(d) if !spec.params.default_decal => Some((d.levels()[0].width, d.levels()[0].height)),
            _ => None,
        };
        SceneSize { bumps: spec.params.bumps.size(), decal, tessellation: spec.params.tessellation }
    }
}

/// Why a frame was not drawn.
#[derive(Debug, thiserror::Error)]
pub enum FrameError {
    /// Passes asked to be kept of a technique that has not kilgard's three.
    #[error(
        "only kilgard's three passes can be kept; {technique} draws {}",
        if technique.is_reference() { "no passes (it samples the exact surface)" } else { "one pass per light" }
    )]
    Passes {
        /// The technique asked for.
        technique: TechniqueName,
    },
    /// An option or an input the set-up refused.
    #[error(transparent)]
    SetUp(#[from] SetupError),
    /// The scene's maps or its frame would not fit in the memory this process may use.
    #[error("this scene (bumps {}x{}) is too big for the memory this process may use: {source}", size.bumps.0, size.bumps.1)]
    TooBig {
        /// What made it big.
        size: SceneSize,
        /// The buffer that would not fit.
        source: OutOfMemory,
    },
    /// No pixel was drawn or lit: a black image would pass for a result.
    #[error("the image is black (no pixel was drawn or lit)")]
    Black,
    /// What preparing or drawing refused otherwise.
    #[error(transparent)]
    Library(#[from] Error),
}

/// What the depth asked for did, for the caller to say.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthNote {
    /// The depth would carve past the surface's bounds (a quarter of a wall's or floor's
    /// shorter side, half a torus's tube radius or a sphere's radius, a quarter of a patch's
    /// narrower side): drawn at `used`.
    Clamped {
        /// The depth asked for.
        asked: f32,
        /// The depth drawn.
        used: f32,
    },
    /// The depth is `texels` texels of the surface's mean texel side, but the normal map made
    /// from the heights keeps the slopes of its own scale: the bumps' shading and the
    /// geometry's steps disagree.
    Slopes {
        /// The depth drawn, in the scene's units.
        depth: f32,
        /// That depth in texels.
        texels: f32,
        /// The surface's mean texel side.
        side: f32,
        /// The normal map's scale.
        scale: f32,
    },
}

/// A frame's options set up and its technique prepared, ready to draw (and to draw again, the
/// light or the eye moved, with [`draw_frame`]).
pub struct PreparedFrame {
    /// The frame's width and height.
    pub size: (usize, usize),
    /// The scene with the technique's maps.
    pub prepared: Prepared,
    /// What the options set up: the scene, the technique's options, the files read, the notes.
    pub set_up: SetUp,
    /// What the depth asked for did.
    pub depth_notes: Vec<DepthNote>,
}

/// A drawn frame and, when asked for, the framebuffer after each named pass.
pub struct Frame {
    /// The final image.
    pub image: Rgba8Image,
    /// `(pass name, image)` of each of kilgard's passes, when they were kept.
    pub snapshots: Vec<(String, Rgba8Image)>,
}

/// Sets up and prepares what `request` describes, with the inputs `given` in memory in place
/// of their options' files. An impossible frame size and passes asked of a technique without
/// them are refused before any file is read.
pub fn prepare_frame(request: &FrameRequest, given: &Given) -> Result<PreparedFrame, FrameError> {
    prepare_frame_told(request, given, &|_, _| {})
}

/// [`prepare_frame`], telling `progress(rows done, rows)` while a horizon map is made
/// ([`Prepared::new_told`]).
pub fn prepare_frame_told(
    request: &FrameRequest,
    given: &Given,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<PreparedFrame, FrameError> {
    let (width, height) = request.size;
    Renderer::check_size(width, height)?;
    let name = request.options.technique.technique;
    if request.passes && name != TechniqueName::Kilgard {
        return Err(FrameError::Passes { technique: name });
    }
    let set_up = request.options.set_up_given(given)?;
    let prepared =
        Prepared::new_told(&set_up.spec, name, &set_up.options, progress).map_err(|e| too_big(e, &set_up.spec))?;
    let depth_notes = depth_notes(&request.options, &set_up.spec, &prepared);
    Ok(PreparedFrame { size: request.size, prepared, set_up, depth_notes })
}

/// The renderer `request` draws on: its backend ([`FrameRequest::backend_for`]: the CPU for the
/// reference, so no device opens for it), the reference's tiles told to `progress`. For `auto`,
/// [`Renderer::fallback_reason`] says why it drew on the CPU, if it did.
pub fn renderer_for(request: &FrameRequest, progress: Option<crate::renderer::Progress>) -> Result<Renderer, Error> {
    let mut renderer = Renderer::new(request.backend_for())?;
    if request.options.technique.technique.is_reference() {
        renderer.set_reference_progress(progress);
    }
    Ok(renderer)
}

/// Draws `frame` with `renderer`, keeping each of kilgard's passes with `passes`; refuses a
/// black image ([`FrameError::Black`]), judged from the pixels so that it holds for every
/// backend and the reference alike.
pub fn draw_frame(renderer: &mut Renderer, frame: &PreparedFrame, passes: bool) -> Result<Frame, FrameError> {
    let (width, height) = frame.size;
    let (scene, technique) = (&frame.prepared.scene, &frame.prepared.technique);
    let drawn =
        draw_passes(renderer, scene, technique, width, height, passes).map_err(|e| too_big(e, &frame.set_up.spec))?;
    if is_black(&drawn.image) {
        return Err(FrameError::Black);
    }
    Ok(drawn)
}

/// Draws `technique`'s passes of `scene` at `width`×`height`, keeping the framebuffer after each
/// named pass with `passes`. Nothing is refused here that [`Renderer::draw_scene`] draws (a
/// black image too: [`draw_frame`] refuses it).
pub fn draw_passes(
    renderer: &mut Renderer,
    scene: &Scene,
    technique: &Technique,
    width: usize,
    height: usize,
    passes: bool,
) -> Result<Frame, Error> {
    let mut snapshots = Vec::new();
    let mut keep = |name: &str, image: &Rgba8Image| snapshots.push((name.to_string(), image.clone()));
    let on_pass: Option<crate::renderer::OnPass> = if passes { Some(&mut keep) } else { None };
    let image = renderer.draw_scene(scene, technique, width, height, on_pass)?;
    Ok(Frame { image, snapshots })
}

/// Whether no pixel of `image` has any colour (its alpha is not looked at).
pub fn is_black(image: &Rgba8Image) -> bool {
    image.texels.iter().all(|&[r, g, b, _]| r == 0 && g == 0 && b == 0)
}

/// `e`, or [`FrameError::TooBig`] with `spec`'s sizes where a buffer would not fit.
fn too_big(e: Error, spec: &SceneSpec) -> FrameError {
    match e {
        Error::OutOfMemory { source, .. }
        | Error::Cpu(CpuError::OutOfMemory(source))
        | Error::Core(CoreError::OutOfMemory(source))
        | Error::Core(CoreError::HeightField(NormalMapError::OutOfMemory(source))) => {
            FrameError::TooBig { size: SceneSize::of(spec), source }
        }
        other => FrameError::Library(other),
    }
}

/// What the depth asked for did: clamped to what the surface allows, or a depth whose slopes
/// the normal map `spec` makes from heights does not share.
fn depth_notes(options: &SceneOptions, spec: &SceneSpec, prepared: &Prepared) -> Vec<DepthNote> {
    let mut notes = Vec::new();
    let Some(asked) = options.heights.depth else { return notes };
    let Some(object) = prepared.scene.objects.iter().find(|o| o.material.heights.is_some()) else { return notes };
    let used = object.material.depth;
    if used < asked * (1.0 - 1e-6) {
        notes.push(DepthNote::Clamped { asked, used });
    }
    let size = object.material.heights.as_ref().map_or((1, 1), |h| (h.width(), h.height()));
    if let (Some(side), BumpSource::Heights(_)) = (object.texel_side(size), &spec.params.bumps) {
        let scale = spec.params.normal_map.scale;
        let texels = used / side;
        if (texels - scale).abs() > 0.01 * scale.abs().max(1e-6) {
            notes.push(DepthNote::Slopes { depth: used, texels, side, scale });
        }
    }
    notes
}
