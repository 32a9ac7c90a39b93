//! The viewer: a scene with the light orbiting, keys that switch technique, passes and options,
//! the mouse moving camera and light, files dropped on it loaded in place; and, with no window
//! at all, a recording of one orbit. `bumpmap view` is a thin skin over this crate (its flags
//! made into a [`Run`] and the scene's options), and so will be the browser's page.
//!
//! - [`keys`]: every key, its `--keys` name and its help line, in one table ([`Action`]);
//! - [`Viewer`]: the model (what is chosen, where things are, the prepared scene), with no
//!   window, so every key is tested without a display;
//! - [`files`]: what a file given or dropped is taken for;
//! - [`record`]: one orbit as an animated PNG, and the frames of it ([`record::orbit`]);
//! - `window` (the `window` feature): winit and softbuffer, or the GPU's surface, with an
//!   overlay (`overlay`) of text and wireframe.
//!
//! What this crate does not do: draw (the front door's renderer does, on either backend), know
//! a technique (the catalogue does; `t` walks it), or parse a command line.

#![warn(missing_docs)]

/// Says a line as a note (`bumpmap_words::report::note`): on stderr, or to whoever collects the
/// notes.
macro_rules! say {
    ($($words:tt)*) => {
        bumpmap_words::report::note(format!($($words)*))
    };
}

pub mod files;
pub mod keys;
#[cfg(feature = "window")]
mod overlay;
pub mod record;
mod setup;
mod state;
#[cfg(feature = "window")]
pub mod window;

use std::path::PathBuf;

pub use keys::Action;
pub use setup::{Setup, set_up_options};
pub use state::Viewer;

/// How a viewer runs: the frame's size and what a script does (the frames drawn, the keys
/// pressed one a frame, a screenshot written at the end), as `bumpmap view`'s flags give them.
#[derive(Clone, Debug)]
pub struct Run {
    /// Width and height of the window, or of a recording's frames.
    pub size: (usize, usize),
    /// Frames to draw before exiting (a recording: the frames of one orbit); `None`: until the
    /// window is closed (a recording: [`record::DEFAULT_FRAMES`]).
    pub frames: Option<u32>,
    /// Keys pressed, one a frame from the second on (`None`: no script).
    pub keys: Option<Vec<Action>>,
    /// Write the last frame, as the window shows it, to this PNG and exit.
    pub screenshot: Option<PathBuf>,
    /// How long each frame of a recording is shown, in milliseconds.
    pub frame_ms: u16,
}

impl Default for Run {
    /// 800×600, no script, 60 ms a recorded frame.
    fn default() -> Self {
        Run { size: (800, 600), frames: None, keys: None, screenshot: None, frame_ms: 60 }
    }
}

impl Run {
    /// The keys the script presses, none when it presses none.
    pub fn scripted_keys(&self) -> Vec<Action> {
        self.keys.clone().unwrap_or_default()
    }
}

/// The renderer `backend` opens, its CPU fallback noted (`bumpmap_words::frame::note_fallback`).
pub fn renderer(backend: bumpmap::BackendChoice) -> Result<bumpmap::Renderer, bumpmap_words::Error> {
    let renderer = bumpmap::Renderer::new(backend).map_err(bumpmap_words::frame::lib_err)?;
    bumpmap_words::frame::note_fallback(&renderer);
    Ok(renderer)
}

/// An image's RGB bytes, alpha left out (the self-shadowing term, not coverage).
fn rgb(image: &bumpmap::Rgba8Image) -> Vec<u8> {
    image.texels.iter().flat_map(|&[r, g, b, _]| [r, g, b]).collect()
}
