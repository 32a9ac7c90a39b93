//! `bumpmap view`'s options: `render`'s groups (what is drawn and how), a file to open, the
//! window's size, and the scripted runs (`--frames`, `--screenshot`, `--keys`, `--record`).

use std::path::PathBuf;

use clap::Args;

use crate::args::{SceneSetup, parse_side};

/// `bumpmap view`.
#[derive(Args, Debug, Clone)]
#[command(
    mut_arg("backend", |a| a.default_value("auto")),
    after_help = crate::view::after_help()
)]
pub struct ViewArgs {
    /// A height field, normal map or mesh (.obj, .gltf, .glb) to open; an image is taken for a normal map when it is mostly blue with red and green about the middle, else for heights
    pub file: Option<PathBuf>,
    /// What is drawn and how.
    #[command(flatten)]
    pub setup: SceneSetup,
    /// Window (or --record frame) width in pixels
    #[arg(long, default_value_t = 800, value_parser = parse_side)]
    pub width: usize,
    /// Window (or --record frame) height in pixels
    #[arg(long, default_value_t = 600, value_parser = parse_side)]
    pub height: usize,
    /// Square frames of this size instead of --width and --height
    #[arg(long, value_parser = parse_side, conflicts_with_all = ["width", "height"])]
    pub size: Option<usize>,
    /// Draw this many frames, then exit (with --screenshot, write the last one); with --record, the frames of one orbit [default, and the fewest with --keys: the keys given plus one; 48 for --record]
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: Option<u32>,
    /// Write the last frame, as the window shows it, to this PNG and exit
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Keys to press, one per frame from the second on, comma-separated: the characters, or space, plus, minus, bracketleft, bracketright
    #[arg(long, value_parser = crate::view::parse_keys_arg)]
    pub keys: Option<KeyList>,
    /// Write an animated PNG of the light orbiting once (no window, no display needed)
    #[arg(long, conflicts_with = "screenshot")]
    pub record: Option<PathBuf>,
    /// Milliseconds each --record frame is shown
    #[arg(long = "frame-ms", default_value_t = 60, value_parser = clap::value_parser!(u16).range(10..=5000))]
    pub frame_ms: u16,
}

/// `--keys`, parsed.
#[derive(Clone, Debug)]
pub struct KeyList(pub Vec<crate::view::Action>);

impl ViewArgs {
    /// The frame size asked for.
    pub fn frame_size(&self) -> (usize, usize) {
        self.size.map_or((self.width, self.height), |s| (s, s))
    }
}
