//! `bumpmap view`: its flags made into the viewer's [`bumpmap_view::Run`] and the scene's
//! options (a FILE put where it belongs), the outputs checked, then the window or the
//! recording, both `bumpmap_view`'s.

use std::path::{Path, PathBuf};

pub use bumpmap_view::Action;
use bumpmap_view::{Run, files, keys};

use bumpmap::options::SceneChoice;
use bumpmap_io::HeightSource;

use crate::args::{KeyList, SceneSetup, ViewArgs};
use crate::error::CliError;

/// Runs `bumpmap view`.
pub fn run(args: &ViewArgs) -> Result<(), CliError> {
    let setup = with_file(args)?;
    // The flags made into options once: the viewer keeps these and changes them as keys and
    // dropped files ask.
    let options = crate::setup::scene_options(&setup);
    let backend = setup.0.backend;
    let named = options.named_inputs();
    let inputs: Vec<&Path> = named.iter().map(PathBuf::as_path).collect();
    for (flag, out, what) in
        [("--record", &args.record, "an animated PNG"), ("--screenshot", &args.screenshot, "a PNG")]
    {
        let Some(out) = out else { continue };
        // The file is what its name says: an APNG is a PNG (.png, or .apng).
        let ext = out.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
        if !matches!(ext.as_deref(), Some("png") | Some("apng") if flag == "--record" || ext.as_deref() == Some("png"))
        {
            return Err(CliError::Usage(format!(
                "{flag} {}: writes {what}; name it .png{}",
                out.display(),
                if flag == "--record" { " or .apng" } else { "" }
            )));
        }
        bumpmap_io::atomic::ensure_not_input(out, &inputs)?;
    }
    // --keys presses one key a frame, and the last key's effect shows in the frame after it.
    if let (None, Some(frames), Some(keys)) = (&args.record, args.frames, &args.keys)
        && (frames as usize) <= keys.0.len()
    {
        let need = keys.0.len() + 1;
        return Err(CliError::Usage(format!(
            "--frames {frames} would leave keys of --keys unpressed: its {} keys take one frame each and the last shows in the frame after, {need} frames; give --frames {need} or more, or leave --frames out",
            keys.0.len()
        )));
    }
    let run = Run {
        size: args.frame_size(),
        frames: args.frames,
        keys: args.keys.as_ref().map(|k| k.0.clone()),
        screenshot: args.screenshot.clone(),
        frame_ms: args.frame_ms,
    };
    match &args.record {
        Some(out) => bumpmap_view::record::record(&run, options, backend, out, &inputs, &RecordBar::default()),
        #[cfg(feature = "viewer")]
        None => bumpmap_view::window::run(&run, options, backend, &inputs),
        #[cfg(not(feature = "viewer"))]
        None => Err(CliError::Usage(
            "this build of bumpmap has no window (built without the `viewer` feature); --record still works".into(),
        )),
    }
}

/// `render`'s options with FILE put where it belongs: a mesh as the scene, an image as the
/// height field or the normal map. FILE and the option it would set cannot both be given.
fn with_file(args: &ViewArgs) -> Result<SceneSetup, CliError> {
    let mut setup = args.setup.clone();
    let Some(file) = &args.file else { return Ok(setup) };
    let kind = files::classify(file).map_err(|reason| CliError::Path { path: file.clone(), reason })?;
    let scene = &mut setup.0.options;
    let clash = match kind {
        files::Kind::Mesh => (scene.scene != SceneChoice::default()).then_some("--scene"),
        _ => {
            scene.height_field.as_ref().map(|_| "--height-field").or(scene.normal_map.as_ref().map(|_| "--normal-map"))
        }
    };
    if let Some(flag) = clash {
        return Err(CliError::Usage(format!("{}: give the file or {flag}, not both", file.display())));
    }
    let taken = match kind {
        files::Kind::Mesh => "a mesh",
        files::Kind::HeightField => "a height field",
        files::Kind::NormalMap => "a normal map",
    };
    eprintln!("{}: opened as {taken}", file.display());
    match kind {
        files::Kind::Mesh => scene.scene = SceneChoice::Mesh(file.clone()),
        files::Kind::HeightField => scene.height_field = Some(HeightSource::File(file.clone())),
        files::Kind::NormalMap => scene.normal_map = Some(file.clone()),
    }
    Ok(setup)
}

/// `--keys`' value parser.
pub fn parse_keys_arg(s: &str) -> Result<KeyList, String> {
    keys::parse_keys(s).map(KeyList)
}

/// `view --help`'s text after the options: examples, then every key from the key table.
pub fn after_help() -> String {
    let keys: Vec<String> = Action::ALL
        .iter()
        .map(|a| {
            let key = match a.key() {
                ' ' => "space".to_string(),
                c => c.to_string(),
            };
            format!("  {key:<6} {}", a.description())
        })
        .collect();
    format!(
        "Examples:\n  \
bumpmap view                                   # the paper's torus; the light orbits\n  \
bumpmap view heights.png                       # your height field (drop files on the window too)\n  \
bumpmap view model.glb --technique single-pass\n  \
bumpmap view --record orbit.png --size 256     # an animated PNG of one orbit, no window needed\n  \
bumpmap view --keys t,t,s --screenshot shot.png # press keys, write the last frame, exit\n\n\
Keys (h or F1 shows them in the window):\n{}\n\n\
Mouse: left-drag orbits the camera, right-drag moves the light, the wheel zooms.\n\n\
The window needs a display (X11 or Wayland). Without one, --record still works; on a server, \
run the window under xvfb-run (Debian: xvfb, xauth).",
        keys.join("\n")
    )
}

/// A recording's frames on a bar on stderr.
#[derive(Default)]
struct RecordBar(std::cell::OnceCell<indicatif::ProgressBar>);

impl bumpmap_view::record::Progress for RecordBar {
    fn start(&self, frames: usize, what: &str) {
        let bar = indicatif::ProgressBar::new(frames as u64).with_style(
            indicatif::ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} frames, {eta} left")
                .expect("a valid template")
                .progress_chars("=> "),
        );
        bar.set_message(what.to_string());
        let _ = self.0.set(bar);
    }

    fn frame(&self) {
        if let Some(bar) = self.0.get() {
            bar.inc(1);
        }
    }

    fn finish(&self) {
        if let Some(bar) = self.0.get() {
            bar.finish_and_clear();
        }
    }
}
