//! The commands as functions over their parsed arguments that return what the command would
//! write instead of writing it: what the Python package (`python/`) calls, so that a script and
//! the command line make the same bytes from the same options, and read the same defaults
//! (`args`'s) to do so.
//!
//! Each function takes the command's own argument struct, parsed by clap from the same words
//! the command line takes. What this module does not do: parse, print results, or write a file
//! anywhere but where [`write_texture`] and [`write_compare`] are told to.

use std::path::{Path, PathBuf};

use bumpmap_io::atomic::FileSet;
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::HeightField;
use bumpmap_math::mesh::Mesh;
use bumpmap_math::tangent::{TangentReport, generate_tangents};

use crate::args::{CompareArgs, NormalmapArgs, RenderArgs, TangentsArgs};
use crate::error::CliError;
pub use crate::report::Progress;

pub use crate::normalmap::Chain;
pub use crate::render::{Drawn, Frame};
pub use crate::render::{PreparedArgs, Request};
pub use crate::setup::{Given, Setup};
pub use bumpmap_compare::{Outcome, Rendered, Results, Scores};

/// `normalmap`'s chain for `field`: level 0, or every level with `--mips`, at the depth
/// `--bits` and `--format` ask for; `name` names the field in errors.
pub fn normal_map(args: &NormalmapArgs, field: &HeightField, name: &str) -> Result<Chain, CliError> {
    let format = crate::normalmap::texel_format(args)?;
    crate::normalmap::make_chain(field, &args.map.options(), args.mips, args.mip_mode.into(), format, name)
}

/// The heights as `normalmap --height-out` stores them (level 0 rounded to `args.bits`, the mean
/// levels and the min–max levels): what the parallax techniques read from a height map.
pub fn heights(args: &NormalmapArgs, field: &HeightField, name: &str) -> Result<bumpmap_math::HeightMips, CliError> {
    crate::normalmap::height_levels(field, args.bits, name)
}

/// `--horizon-out`'s horizon map of `field`, read beyond its edges as the normal map's wrap says
/// (ambient occlusion and bent normals come from it).
pub fn horizons(args: &NormalmapArgs, field: &HeightField, name: &str) -> Result<bumpmap_math::HorizonMap, CliError> {
    crate::normalmap::horizon_map(field, args.map.wrap.into(), name)
}

/// `--roughness-out`'s levels for `field` (RGBA8, every level down to 1×1): the surface's
/// `--roughness` made rougher where the normals a texel averages spread, laid out in the channels
/// `--roughness-layout` names.
pub fn roughness(args: &NormalmapArgs, field: &HeightField, name: &str) -> Result<bumpmap_math::MipChain, CliError> {
    crate::normalmap::roughness_chain(field, &args.map.options(), args.roughness, args.roughness_layout, name)
}

/// `--lean-out`'s moments for `field`, every level, as the two files hold them: (Bx, By, Mxx,
/// Myy) and (Mxy, J, 0, 0), from the 8-bit normal map's level 0 whatever `--bits` says.
pub fn lean(
    args: &NormalmapArgs,
    field: &HeightField,
    name: &str,
) -> Result<[Vec<bumpmap_math::Image<[f32; 4]>>; 2], CliError> {
    let options = args.map.options();
    let chain = crate::normalmap::make_chain(field, &options, true, args.mip_mode.into(), TextureFormat::Rgba8, name)?;
    crate::normalmap::lean_levels(field, &options, &chain, name)
}

/// The texel format `normalmap`'s `--format` and `--bits` ask for together.
pub fn texel_format(args: &NormalmapArgs) -> Result<TextureFormat, CliError> {
    crate::normalmap::texel_format(args)
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

/// `render`'s image (and passes, with `--passes`), drawn as the command draws it, without the
/// output file; the reference shows its tiles' progress as `progress` says.
pub fn render(args: &RenderArgs, progress: &Progress) -> Result<Drawn, CliError> {
    crate::render::draw_request(&Request::from_args(args)?, progress, &Given::default())
}

/// [`render`] of a typed request, with the inputs `given` in memory in place of the files its
/// options name.
pub fn render_given(request: &Request, progress: &Progress, given: &Given) -> Result<Drawn, CliError> {
    crate::render::draw_request(request, progress, given)
}

/// The renderer `--backend` opens (with `auto`, the reason for drawing on the CPU on stderr).
pub fn open_renderer(backend: bumpmap::BackendChoice) -> Result<bumpmap::Renderer, CliError> {
    crate::render::renderer(backend)
}

/// What `render` would draw, set up and prepared once, for drawing many frames of it (moving
/// the light or the eye) with a [`bumpmap::Renderer`] kept between them.
pub fn prepare_render(request: &Request, given: &Given) -> Result<PreparedArgs, CliError> {
    crate::render::prepare_request(request, given)
}

/// `tangents`' mesh for `mesh`: the tangents made by `--mode` (vertices split where `--split-angle`
/// says), and what was degenerate, mirrored or split.
pub fn tangents(args: &TangentsArgs, mesh: &Mesh) -> Result<(Mesh, TangentReport), CliError> {
    let options = crate::mesh::tangent_options(args)?;
    generate_tangents(mesh, &options).map_err(|e| CliError::Path { path: args.input.clone(), reason: e.to_string() })
}

/// Everything `compare` measures, and the files it read; its steps shown as `progress` says.
pub fn compare(args: &CompareArgs, progress: &Progress) -> Result<(Results, Vec<PathBuf>), CliError> {
    crate::compare::measure(args, progress)
}

/// [`compare`] of typed options; `output`, where the results will be written, for messages.
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
