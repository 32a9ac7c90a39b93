//! `view --record OUT.png`: the light orbiting once as an animated PNG, frames straight from the
//! renderer, no window (so no display is needed). `--keys` are pressed first, so a recording can
//! start from any technique or toggle.

use std::path::{Path, PathBuf};

use bumpmap_io::atomic::FileSet;
use bumpmap_io::image_file::save_apng_into;

use super::keys::Action;
use super::state::Viewer;
use crate::Run;
use bumpmap::options::SceneOptions;
use bumpmap_words::Error;
use bumpmap_words::frame::lib_err;

/// `frames` frames of `prepared` at `width`×`height`, its first light carried once round the
/// point looked at (`bumpmap::motion::LightOrbit`), as RGB bytes; `tick` after each. What
/// `--record` and the demo's animation draw.
pub fn orbit(
    renderer: &mut bumpmap::Renderer,
    prepared: &mut bumpmap::Prepared,
    width: usize,
    height: usize,
    frames: usize,
    mut tick: impl FnMut(),
) -> Result<Vec<Vec<u8>>, Error> {
    let path = bumpmap::motion::LightOrbit::of(&prepared.scene);
    let mut images = Vec::with_capacity(frames);
    for k in 0..frames {
        path.place(&mut prepared.scene, k as f32 / frames as f32, 0.0);
        images.push(crate::rgb(&renderer.draw(prepared, width, height).map_err(lib_err)?));
        tick();
    }
    Ok(images)
}

/// Frames in a recording when `--frames` does not say.
pub const DEFAULT_FRAMES: u32 = 48;

/// What a recording tells as it goes: its frames' count and what it draws, then each frame.
pub trait Progress {
    /// Before the first frame.
    fn start(&self, frames: usize, what: &str);
    /// After each frame.
    fn frame(&self);
    /// After the last frame, before the file is written.
    fn finish(&self);
}

/// Tells nothing.
impl Progress for () {
    fn start(&self, _: usize, _: &str) {}
    fn frame(&self) {}
    fn finish(&self) {}
}

/// Writes the recording of `run` (its size, its frames, its keys pressed first) into `out`, no
/// file of `inputs` or of the scene's replaced, all or nothing; says on stderr what it wrote.
pub fn record(
    run: &Run,
    options: SceneOptions,
    backend: bumpmap::BackendChoice,
    out: &Path,
    inputs: &[&Path],
    progress: &dyn Progress,
) -> Result<(), Error> {
    let (width, height) = run.size;
    bumpmap::Renderer::check_size(width, height).map_err(lib_err)?;
    let frames = run.frames.unwrap_or(DEFAULT_FRAMES) as usize;
    let bytes = (frames * width * height * 3) as u64;
    bumpmap::bumpmap_math::buffer::ensure_available(bytes, "the recording's frames").map_err(Error::OutOfMemory)?;
    let mut viewer = Viewer::new(options)?;
    let read: Vec<PathBuf> = inputs.iter().map(|p| p.to_path_buf()).chain(viewer.inputs().iter().cloned()).collect();
    let inputs: Vec<&Path> = read.iter().map(PathBuf::as_path).collect();
    bumpmap_io::atomic::ensure_not_input(out, &inputs)?;
    for action in run.scripted_keys() {
        if !matches!(action, Action::Screenshot | Action::Quit | Action::Backend) {
            viewer.apply(action);
        }
        if let Some(m) = viewer.message.take() {
            say!("{}: {m}", action.name());
        }
    }
    let reference = viewer.technique().is_reference();
    let mut renderer = if reference {
        bumpmap::Renderer::new(bumpmap::BackendChoice::Cpu).map_err(lib_err)?
    } else {
        crate::renderer(backend)?
    };
    progress.start(frames, &format!("recording {}", viewer.technique()));
    viewer.settle();
    let mut prepared = viewer.frame().clone();
    let images = orbit(&mut renderer, &mut prepared, width, height, frames, || progress.frame())?;
    progress.finish();
    let lit = images.iter().any(|frame| frame.iter().any(|&c| c != 0));
    bumpmap_words::frame::ensure_drawn(!lit, out)?;
    let mut set = FileSet::new(&inputs);
    save_apng_into(&mut set, out, width, height, &images, run.frame_ms)?;
    set.commit()?;
    say!(
        "wrote {} ({frames} frames of {width}x{height}, {} ms each: {} on {})",
        out.display(),
        run.frame_ms,
        viewer.technique(),
        if reference { "the CPU".to_string() } else { renderer.describe() }
    );
    Ok(())
}
