//! A frame's refusals and notes ([`bumpmap::frame`], the renderer, the core's and the
//! reference's errors), named by the flags that caused them.

use std::path::Path;

use bumpmap::Renderer;
use bumpmap::bumpmap_math::buffer::OutOfMemory;
use bumpmap::frame::{DepthNote, FrameError, PreparedFrame, SceneSize};
use bumpmap::options::SceneOptions;

use crate::Error;
pub use crate::library::{core_err, lib_err, reference_err};

/// The note for a renderer that `--backend auto` opened on the CPU, `why` being the renderer's
/// [`fallback_reason`](bumpmap::Renderer::fallback_reason).
pub fn on_the_cpu(why: &str) -> String {
    format!("--backend auto: drawing on the CPU ({why})")
}

/// Says why `renderer` draws on the CPU when `--backend auto` opened it there, as a note
/// ([`crate::report::note`]); nothing otherwise.
pub fn note_fallback(renderer: &Renderer) {
    if let Some(why) = renderer.fallback_reason() {
        crate::report::note(on_the_cpu(why));
    }
}

/// What setting `prepared` up noted and what its depth did, a line each as stderr shows them
/// (a warning's line starts `warning: `).
pub fn frame_notes(prepared: &PreparedFrame) -> Vec<String> {
    let setup = prepared.set_up.notes.iter().map(crate::setup::note_line);
    setup.chain(prepared.depth_notes.iter().map(depth_line)).collect()
}

/// Says [`frame_notes`] (each warning as a warning, the rest as notes: [`crate::report`]) and
/// returns them.
pub fn say_frame_notes(prepared: &PreparedFrame) -> Vec<String> {
    let notes = frame_notes(prepared);
    for note in &notes {
        crate::report::setup_line(note);
    }
    notes
}

/// The file or preset the bumps come from, as messages name it.
fn bumps_name(options: &SceneOptions) -> Option<String> {
    match &options.height_field {
        Some(source) => Some(source.to_string()),
        None => options.normal_map.as_ref().map(|p| p.display().to_string()),
    }
}

/// A frame's refusal in the command line's words: the flags that caused it, the inputs that
/// made a scene too big, and `output` where a black image was not written.
pub fn frame_err(e: FrameError, options: &SceneOptions, output: Option<&Path>) -> Error {
    match e {
        FrameError::Passes { technique } => Error::Usage(format!(
            "--passes shows the three passes of --technique kilgard; {technique} draws {}",
            if technique.is_reference() { "no passes (it samples the exact surface)" } else { "one pass per light" }
        )),
        FrameError::SetUp(e) => crate::setup::setup_err(e),
        FrameError::TooBig { size, source } => too_big(source, size, bumps_name(options).as_deref()),
        FrameError::Black => not_drawn(output.unwrap_or(Path::new("the frame"))),
        FrameError::Library(e) => lib_err(e),
    }
}

/// A depth note as stderr shows it, naming the flags.
fn depth_line(note: &DepthNote) -> String {
    match *note {
        DepthNote::Clamped { asked, used } => format!(
            "note: --depth {asked} would carve past the surface's bounds; drawn at {used} (a quarter of a wall's or floor's shorter side, half a torus's tube radius or a sphere's radius, a quarter of the patch's narrower side)"
        ),
        DepthNote::Slopes { depth, texels, side, scale } => format!(
            "note: --depth {depth} is {texels:.3} texels of this surface's mean texel side ({side:.5}); the normal map keeps --bump-scale {scale}'s slopes: add --bump-scale {texels:.3} for the slopes of the geometry"
        ),
    }
}

/// Refuses `output` for a frame that came out black (`black`: no pixel has any colour): nothing
/// in view was drawn or lit, and a black PNG with exit status 0 would pass for a result. Judged
/// from the image, so it holds for every backend and the reference alike; the causes are named,
/// since the image cannot tell them apart.
pub fn ensure_drawn(black: bool, output: &Path) -> Result<(), Error> {
    if black { Err(not_drawn(output)) } else { Ok(()) }
}

/// [`ensure_drawn`]'s refusal.
fn not_drawn(output: &Path) -> Error {
    Error::Path {
        path: output.to_path_buf(),
        reason: "not written: the image is black (no pixel was drawn or lit). The object may be out of \
                 view (--eye, --target, --up, --fov), too small or too flat to cover a pixel (--tessellation, \
                 --torus-radii, the mesh), or facing away from the eye or the light (--light, --ambient)"
            .into(),
    }
}

/// An out-of-memory error with the sizes that caused it: the bump texture's (and `bumps`, the
/// file or preset it came from) and the tessellation's: what a user can make smaller.
pub fn too_big(oom: OutOfMemory, size: SceneSize, bumps: Option<&str>) -> Error {
    let (w, h) = size.bumps;
    let from = bumps.map(|b| format!(" from {b}")).unwrap_or_default();
    let mesh = match size.tessellation {
        Some((u, v)) => format!(", tessellation {u}x{v}"),
        None => String::new(),
    };
    let decal = match size.decal {
        Some((dw, dh)) => format!(", decal {dw}x{dh}"),
        None => String::new(),
    };
    Error::Render(format!(
        "this scene (bumps {w}x{h}{from}{decal}{mesh}) is too big for the memory this process may use: {oom}. \
         The README's \"Memory\" section gives what the largest inputs need; a smaller --height-field, \
         --normal-map, --decal, --gloss or --tessellation needs less"
    ))
}
