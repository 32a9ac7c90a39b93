//! The commands as functions over their parsed arguments that return what the command would
//! write instead of writing it: what the Python package (`python/`) calls, so that a script and
//! the command line make the same bytes from the same options, and read the same defaults
//! (`args`'s) to do so.
//!
//! `render`, `compare` and the maps made from heights take typed requests ([`Request`],
//! `bumpmap_compare::CompareOptions`, [`MapRequest`]) that the command line makes from its flags
//! and the Python package from its keywords; and `tangents` its `TangentOptions`. What
//! this module does not do: parse, print results, or write a file anywhere but where
//! [`write_texture`] and [`write_compare`] are told to.

use std::path::{Path, PathBuf};

use bumpmap_io::atomic::FileSet;
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::HeightField;
use bumpmap_math::mesh::Mesh;
use bumpmap_math::tangent::{TangentOptions, TangentReport, generate_tangents};

use crate::args::NormalmapArgs;
use crate::error::CliError;
pub use crate::report::Progress;

pub use crate::normalmap::Chain;
pub use crate::render::{Drawn, Frame};
pub use crate::render::{PreparedArgs, Request};
pub use crate::setup::{Given, Setup};
pub use bumpmap_compare::{Outcome, Rendered, Results, Scores};

/// How `normalmap` makes its maps from heights, typed: what its flags say, and what the Python
/// package's map functions take as keywords.
#[derive(Clone, Debug)]
pub struct MapRequest {
    /// How heights become normals (`--kernel`, `--scale`, `--wrap`, `--y-convention`,
    /// `--encoding`).
    pub normals: bumpmap_math::NormalMapOptions,
    /// The bits a channel the normal map and the heights are stored in: 8 or 16.
    pub bits: u8,
    /// What the smaller levels hold.
    pub mip_mode: bumpmap_math::MipMode,
    /// The surface's own perceptual roughness, in [0, 1], for the roughness map.
    pub roughness: f32,
    /// The roughness map's channels.
    pub roughness_layout: bumpmap::options::RoughnessLayout,
    /// Which channel of a colour image holds the heights.
    pub channel: bumpmap_io::Channel,
}

impl Default for MapRequest {
    /// What `bumpmap normalmap` makes with no flags (a test holds the two together).
    fn default() -> Self {
        MapRequest {
            normals: bumpmap_math::NormalMapOptions {
                y_convention: bumpmap_math::YConvention::YUp,
                ..Default::default()
            },
            bits: 8,
            mip_mode: bumpmap_math::MipMode::LengthInAlpha,
            roughness: 0.5,
            roughness_layout: bumpmap::options::RoughnessLayout::Gray,
            channel: bumpmap_io::Channel::Luminance,
        }
    }
}

impl MapRequest {
    /// The request `normalmap`'s flags make.
    pub fn from_args(args: &NormalmapArgs) -> Self {
        MapRequest {
            normals: args.map.options(),
            bits: args.bits,
            mip_mode: args.mip_mode,
            roughness: args.roughness,
            roughness_layout: args.roughness_layout,
            channel: args.map.channel,
        }
    }

    /// Refuses what the command line's value parsers refuse: bits other than 8 or 16, a
    /// roughness outside [0, 1]. (The scale's range is the library's to check.)
    pub fn check(&self) -> Result<(), CliError> {
        if !matches!(self.bits, 8 | 16) {
            return Err(CliError::Usage(format!("--bits must be 8 or 16, got {}", self.bits)));
        }
        if !(0.0..=1.0).contains(&self.roughness) {
            return Err(CliError::Usage(format!("--roughness must be in [0, 1], got {}", self.roughness)));
        }
        Ok(())
    }
}

/// `normalmap`'s chain for `field`: level 0, or every level with `mips`, at `map.bits` (RGBA8 or
/// RGBA16); `name` names the field in errors.
pub fn normal_map(map: &MapRequest, mips: bool, field: &HeightField, name: &str) -> Result<Chain, CliError> {
    map.check()?;
    let format = if map.bits == 16 { TextureFormat::Rgba16 } else { TextureFormat::Rgba8 };
    crate::normalmap::make_chain(field, &map.normals, mips, map.mip_mode, format, name)
}

/// The heights as `normalmap --height-out` stores them (level 0 rounded to `map.bits`, the mean
/// levels and the min–max levels): what the parallax techniques read from a height map.
pub fn heights(map: &MapRequest, field: &HeightField, name: &str) -> Result<bumpmap_math::HeightMips, CliError> {
    map.check()?;
    crate::normalmap::height_levels(field, map.bits, name)
}

/// `--horizon-out`'s horizon map of `field`, read beyond its edges as the normal map's wrap says
/// (ambient occlusion and bent normals come from it).
pub fn horizons(map: &MapRequest, field: &HeightField, name: &str) -> Result<bumpmap_math::HorizonMap, CliError> {
    map.check()?;
    crate::normalmap::horizon_map(field, map.normals.wrap, name)
}

/// `--roughness-out`'s levels for `field` (RGBA8, every level down to 1×1): the surface's
/// roughness made rougher where the normals a texel averages spread, laid out in the channels
/// the layout names.
pub fn roughness(map: &MapRequest, field: &HeightField, name: &str) -> Result<bumpmap_math::MipChain, CliError> {
    map.check()?;
    crate::normalmap::roughness_chain(field, &map.normals, map.roughness, map.roughness_layout, name)
}

/// `--lean-out`'s moments for `field`, every level, as the two files hold them: (Bx, By, Mxx,
/// Myy) and (Mxy, J, 0, 0), from the 8-bit normal map's level 0 whatever the bits say.
pub fn lean(
    map: &MapRequest,
    field: &HeightField,
    name: &str,
) -> Result<[Vec<bumpmap_math::Image<[f32; 4]>>; 2], CliError> {
    map.check()?;
    let chain = crate::normalmap::make_chain(field, &map.normals, true, map.mip_mode, TextureFormat::Rgba8, name)?;
    crate::normalmap::lean_levels(field, &map.normals, &chain, name)
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
/// it, without the output file, with the inputs `given` in memory in place of the files its
/// options name; the reference shows its tiles' progress as `progress` says.
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
    use clap::Parser;

    use super::MapRequest;
    use crate::args::{Cli, Command};

    #[test]
    fn normalmaps_defaults_are_the_map_requests() {
        let Command::Normalmap(args) =
            Cli::try_parse_from(["bumpmap", "normalmap", "bricks", "-o", "n.png"]).expect("parses").command
        else {
            unreachable!("normalmap parses as normalmap")
        };
        assert_eq!(format!("{:?}", MapRequest::from_args(&args)), format!("{:?}", MapRequest::default()));
    }
}
