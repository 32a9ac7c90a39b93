//! `bumpmap render`: the flags made into the library's [`FrameRequest`], prepared and drawn by
//! `bumpmap::frame` on the renderer the backend names, written as a PNG (and, with `--passes`,
//! one PNG per pass).
//!
//! The library refuses what a technique cannot do with typed errors and says what it noted as
//! data; `bumpmap_words::frame` names the flags that caused them, for this command and for
//! Python alike.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap::{BackendChoice, Renderer};
use bumpmap_io::atomic::ensure_not_input;
use bumpmap_words::frame::{frame_err, lib_err, note_fallback, say_frame_notes};

use crate::args::RenderArgs;
use crate::error::CliError;

pub use bumpmap::frame::{Frame, FrameRequest, PreparedFrame};

/// The frame `render`'s flags ask for.
pub fn frame_request(args: &RenderArgs) -> Result<FrameRequest, CliError> {
    Ok(FrameRequest { size: args.frame.0.size, passes: args.passes, ..args.setup.0.clone() })
}

/// Runs `bumpmap render`.
pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let request = frame_request(args)?;
    let named = request.options.named_inputs();
    ensure_not_input(&args.output, &named.iter().map(PathBuf::as_path).collect::<Vec<_>>())?;
    let drawn = draw_request(&request, &args.output, &crate::report::Progress::Bar, &crate::setup::Given::default())?;
    let inputs: Vec<&Path> = drawn.inputs.iter().map(PathBuf::as_path).collect();
    let written = write_frame(&drawn.frame, &args.output, &inputs)?;
    eprintln!(
        "wrote {} ({})",
        written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "),
        drawn.by
    );
    Ok(())
}

/// What `render`'s options drew, before anything is written.
pub struct Drawn {
    /// The image, and the passes when `--passes` asked for them.
    pub frame: Frame,
    /// How it was drawn, in words: the technique and the backend.
    pub by: String,
    /// Every file read: no output may replace one.
    pub inputs: Vec<PathBuf>,
}

/// Sets up and prepares what `request` describes ([`bumpmap::frame::prepare_frame_told`]), with
/// the inputs `given` in memory in place of their options' files, a horizon map's rows told to
/// `progress`; what it refuses, in the flags' words.
fn prepare_request(
    request: &FrameRequest,
    given: &crate::setup::Given,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<PreparedFrame, CliError> {
    bumpmap::frame::prepare_frame_told(request, given, progress).map_err(|e| frame_err(e, &request.options, None))
}

/// Draws what `request` describes: the scene set up, the technique prepared, the frame drawn on
/// its backend (the reference always on the CPU, its tiles' progress shown as `progress` says)
/// and refused if black, `output` named in that refusal. The notes the assets bring (what a
/// glTF's material gave) go to stderr.
pub fn draw_request(
    request: &FrameRequest,
    output: &Path,
    progress: &crate::report::Progress,
    given: &crate::setup::Given,
) -> Result<Drawn, CliError> {
    let name = request.options.technique.technique;
    // Preparing a large scene (its maps, the heights and their bounds) takes a minute at 16384²
    // and tells no steps: a spinner with the time taken, on a terminal; where a horizon map is
    // made (minutes at 8192²), a bar of its rows.
    let spinner = match progress {
        crate::report::Progress::Bar => indicatif::ProgressBar::new_spinner().with_style(
            indicatif::ProgressStyle::with_template("preparing {msg} {spinner} {elapsed}").expect("valid template"),
        ),
        crate::report::Progress::Hidden => indicatif::ProgressBar::hidden(),
    };
    spinner.set_message(name.to_string());
    spinner.enable_steady_tick(std::time::Duration::from_millis(250));
    let as_bar = std::sync::Once::new();
    let rows = |done: usize, total: usize| {
        as_bar.call_once(|| {
            spinner.set_style(
                indicatif::ProgressStyle::with_template(
                    "preparing {msg}: horizon map {bar:30} {pos}/{len} rows {elapsed}",
                )
                .expect("valid template"),
            )
        });
        spinner.set_length(total as u64);
        spinner.set_position(done as u64);
    };
    let prepared = prepare_request(request, given, &rows);
    spinner.finish_and_clear();
    let prepared = prepared?;
    say_frame_notes(&prepared);
    let reference_progress = match progress {
        crate::report::Progress::Hidden => None,
        crate::report::Progress::Bar => Some(reference_bar()),
    };
    let mut renderer = bumpmap::frame::renderer_for(request, reference_progress).map_err(lib_err)?;
    note_fallback(&renderer);
    let frame = bumpmap::frame::draw_frame(&mut renderer, &prepared, request.passes)
        .map_err(|e| frame_err(e, &request.options, Some(output)))?;
    let by = if name.is_reference() {
        format!("reference, {} samples per pixel", prepared.set_up.options.reference.samples_per_pixel)
    } else {
        format!("{name}, {}", renderer.describe())
    };
    Ok(Drawn { frame, by, inputs: prepared.set_up.inputs })
}

/// A progress bar on stderr for the reference's tiles.
fn reference_bar() -> bumpmap::renderer::Progress {
    let bar = indicatif::ProgressBar::new(0).with_style(
        indicatif::ProgressStyle::with_template("reference {bar:40} {pos}/{len} tiles {elapsed}")
            .expect("valid template"),
    );
    Arc::new(move |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
        if done == total {
            bar.finish_and_clear();
        }
    })
}

/// Opens the backend `arg` names; `auto` says on stderr why it fell back to the CPU.
pub fn renderer(arg: BackendChoice) -> Result<Renderer, CliError> {
    let renderer = Renderer::new(arg).map_err(lib_err)?;
    note_fallback(&renderer);
    Ok(renderer)
}

/// Writes the frame and its pass images (`bumpmap::frame::write_frame`), all or none.
pub fn write_frame(frame: &Frame, out: &Path, inputs: &[&Path]) -> Result<Vec<PathBuf>, CliError> {
    Ok(bumpmap::frame::write_frame(frame, out, inputs)?)
}
