//! The commands as functions over their parsed arguments that return what the command would
//! write instead of writing it: what the Python package (`python/`) calls, so that a script and
//! the command line make the same bytes from the same options, and read the same defaults
//! (`args`'s) to do so.
//!
//! `render` and `compare` take typed requests ([`FrameRequest`], `bumpmap_compare::CompareOptions`)
//! that the command line makes from its flags and the Python package from its keywords; and
//! `tangents` its `TangentOptions`. The maps made from heights are the library's
//! (`bumpmap::maps`); [`map_error`] says their errors as `normalmap` does. What
//! this module does not do: parse, print results, or write a file anywhere but where
//! [`write_texture`] and [`write_compare`] are told to.

use std::path::{Path, PathBuf};

use bumpmap_io::atomic::FileSet;
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::mesh::Mesh;
use bumpmap_math::tangent::{TangentOptions, TangentReport, generate_tangents};

use crate::error::CliError;
pub use crate::report::Progress;

pub use crate::render::Drawn;
pub use crate::setup::{Given, Setup};
pub use bumpmap::frame::{Frame, FrameRequest, PreparedFrame};
pub use bumpmap::maps::Chain;
pub use bumpmap_compare::{Outcome, Rendered, Results, Scores};

/// A map that could not be made from `name`'s heights, in the command line's words.
pub fn map_error(e: bumpmap::maps::MapError, name: &str) -> CliError {
    crate::normalmap::map_error(e, name)
}

/// Writes `chain` as `normalmap -o OUT` does: by the extension, PNG files (`OUT.mip1.png`, …
/// beside level 0), or one DDS or KTX2 file with every level in `format`; all files or none, none
/// of them replacing one of `inputs`. When `cancelled`, asked once right before the files go
/// into place, says so, nothing is ([`CliError::Interrupted`]). Returns the paths written.
pub fn write_texture(
    out: &Path,
    chain: &Chain,
    format: TextureFormat,
    inputs: &[&Path],
    cancelled: &dyn Fn() -> bool,
) -> Result<Vec<PathBuf>, CliError> {
    crate::normalmap::check_format(out, format)?;
    let mut set = FileSet::new(inputs);
    crate::normalmap::write_into(&mut set, out, chain, format)?;
    if cancelled() {
        return Err(CliError::Interrupted);
    }
    Ok(set.commit()?)
}

/// `render`'s image (and passes, with `passes`) for a typed request, drawn as the command draws
/// it, without the output file (`output` names the frame in a refusal), with the inputs
/// `given` in memory in place of the files its options name; the reference shows its tiles'
/// progress as `progress` says.
pub fn render_given(
    request: &FrameRequest,
    output: &Path,
    progress: &Progress,
    given: &Given,
) -> Result<Drawn, CliError> {
    crate::render::draw_request(request, output, progress, given)
}

/// The renderer `--backend` opens (with `auto`, the reason for drawing on the CPU on stderr).
pub fn open_renderer(backend: bumpmap::BackendChoice) -> Result<bumpmap::Renderer, CliError> {
    crate::render::renderer(backend)
}

/// What `render` would draw, set up and prepared once, for drawing many frames of it (moving
/// the light or the eye) with a [`bumpmap::Renderer`] kept between them.
pub fn prepare_render(request: &FrameRequest, given: &Given) -> Result<PreparedFrame, CliError> {
    crate::render::prepare_request(request, given)
}

/// What setting `prepared` up noted, a line each as `render` prints them (a warning's line
/// starts `warning: `).
pub fn frame_notes(prepared: &PreparedFrame) -> Vec<String> {
    crate::render::frame_notes(prepared)
}

/// `tangents`' mesh for `mesh`: the tangents made by `options.mode` (vertices split where the split angle
/// says), and what was degenerate, mirrored or split.
pub fn tangents(options: &TangentOptions, mesh: &Mesh) -> Result<(Mesh, TangentReport), CliError> {
    crate::mesh::check_tangent_options(options)?;
    generate_tangents(mesh, options).map_err(|e| CliError::Render(format!("the mesh: {e}")))
}

/// Everything `compare` measures for typed options, and the files it read; its steps shown as
/// `progress` says; `output`, where the results will be written, for messages.
pub fn compare_options(
    options: &bumpmap_compare::CompareOptions,
    output: Option<&Path>,
    progress: &Progress,
) -> Result<(Results, Vec<PathBuf>), CliError> {
    crate::compare::measure_options(options, output, progress)
}

/// A library error in the command line's words (what `render`, `inspect` and `height` report).
pub fn library_error(e: bumpmap::Error) -> CliError {
    crate::render::lib_err(e)
}

/// `compare`'s `results.json`, as text.
pub fn compare_json(results: &Results) -> String {
    bumpmap_compare::json(results)
}

/// Refuses a `compare` output that cannot be a folder (before the work, not after).
pub fn check_compare_output(out: &Path) -> Result<(), CliError> {
    crate::compare::check_output(out)
}

/// Writes `compare`'s folder (images, heat maps, plots, `results.json`, `report.html`) into
/// `out`, all or none, none of the files replacing one of `inputs`. When `cancelled`, asked once
/// right before the files go into place, says so, nothing is ([`CliError::Interrupted`]).
/// Returns the paths written.
pub fn write_compare(
    out: &Path,
    results: &Results,
    inputs: &[&Path],
    cancelled: &dyn Fn() -> bool,
) -> Result<Vec<PathBuf>, CliError> {
    crate::compare::check_output(out)?;
    crate::compare::write(out, results, inputs, cancelled)
}

#[cfg(test)]
mod tests {
    use bumpmap::maps::MapOptions;
    use clap::Parser;

    use crate::args::{Cli, Command};

    #[test]
    fn normalmaps_defaults_are_the_librarys() {
        let Command::Normalmap(args) =
            Cli::try_parse_from(["bumpmap", "normalmap", "bricks", "-o", "n.png"]).expect("parses").command
        else {
            unreachable!("normalmap parses as normalmap")
        };
        assert_eq!(crate::normalmap::map_options(&args), MapOptions::default());
    }
}
