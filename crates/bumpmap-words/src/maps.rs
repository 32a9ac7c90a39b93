//! What making maps from heights refused ([`MapError`]), a chain that could not be written
//! ([`SaveError`]), a set of maps that could not be written ([`OutputsError`]) and tangents that
//! could not be made ([`MeshError`]), a blend of two normal maps ([`BlendError`]), named by the
//! flags that caused them.

use bumpmap::maps::{BlendError, MapError, Output, OutputsError, SaveError};
use bumpmap_math::mesh::MeshError;
use bumpmap_math::normalmap::{MAX_SCALE, NormalMapError};
use bumpmap_math::{HeightMipsError, HorizonError};

use crate::Error;

/// A normal map that could not be made from `name`'s heights, in the command line's words: a
/// scale out of range is the flag's fault, not the input's.
pub fn scale_err(source: NormalMapError, name: &str) -> Error {
    match source {
        NormalMapError::BadScale(s) => {
            Error::Usage(format!("--scale must be a number in [-{MAX_SCALE:e}, {MAX_SCALE:e}], got {s} (for {name})"))
        }
        source => Error::NormalMap { path: name.to_string(), source },
    }
}

/// A map that could not be made from `name`'s heights, in the command line's words: a value
/// out of range is its flag's fault (exit status 2), a buffer too big the machine's.
pub fn map_error(e: MapError, name: &str) -> Error {
    match e {
        MapError::Bits(bits) => Error::Usage(format!("--bits must be 8 or 16, got {bits}")),
        MapError::Roughness(r) => Error::Usage(format!("--roughness must be in [0, 1], got {r}")),
        MapError::NormalMap(source) => scale_err(source, name),
        MapError::Heights(HeightMipsError::OutOfMemory(e))
        | MapError::Horizons(HorizonError::OutOfMemory(e))
        | MapError::OutOfMemory(e) => Error::OutOfMemory(e),
        other => Error::Path { path: name.into(), reason: other.to_string() },
    }
}

/// The flag that names `output`.
pub fn output_flag(output: Output) -> &'static str {
    match output {
        Output::NormalMap => "-o",
        Output::Roughness => "--roughness-out",
        Output::Lean => "--lean-out",
        Output::Heights => "--height-out",
        Output::Horizons => "--horizon-out",
        Output::AmbientOcclusion => "--ao-out",
        Output::BentNormals => "--bent-normals-out",
    }
}

/// A set of maps of `name`'s heights that could not be written, in the command line's words:
/// two outputs on one file and a file that holds no floats are the flags' fault (exit status 2).
pub fn outputs_error(e: OutputsError, name: &str) -> Error {
    use Output::*;
    match e {
        OutputsError::Clash { output: Roughness, other: NormalMap, path } => {
            Error::Usage(format!("--roughness-out {} is the normal map's own file", path.display()))
        }
        OutputsError::Clash { output: output @ (Lean | Heights), other: NormalMap | Roughness, path } => {
            Error::Usage(format!("{}: {} is another output's file", output_flag(output), path.display()))
        }
        OutputsError::Clash { output: Lean, other: Heights, path } => {
            Error::Usage(format!("--lean-out: {} is --height-out's file", path.display()))
        }
        OutputsError::Clash { output, other, path } => {
            Error::Usage(format!("{}: {} is also {}'s file", output_flag(output), path.display(), output_flag(other)))
        }
        OutputsError::LeanNeedsFloats { path, extension } => Error::Usage(format!(
            "--lean-out {}: the moments are floats, which .ktx2 or .dds hold (not .{extension})",
            path.display()
        )),
        OutputsError::TooBig { width, height, source } => Error::Render(format!(
            "{name}: {source} from its {width}x{height} heights, more than this process may use. Fewer outputs at \
             once (--lean-out, --roughness-out, --height-out, --horizon-out, --ao-out, --bent-normals-out) \
             or a smaller field need less"
        )),
        OutputsError::Map(e) => map_error(e, name),
        OutputsError::Save(e) => save_error(e),
        OutputsError::Io(e) => Error::Io(e),
    }
}

/// A chain that could not be written, in the command line's words: a compressed format asked of
/// a PNG is `--format`'s fault (exit status 2).
pub fn save_error(e: SaveError) -> Error {
    match e {
        SaveError::NeedsContainer { path, format } => Error::Usage(format!(
            "{}: --format {} needs a .dds or .ktx2 output (PNG holds uncompressed texels only)",
            path.display(),
            format.dxgi_name()
        )),
        SaveError::Io(e) => Error::Io(e),
    }
}

/// A blend that made nothing, in the command line's words: a value out of range is its flag's
/// fault (exit status 2), an input that cannot be read its file's.
pub fn blend_error(e: BlendError) -> Error {
    match e {
        BlendError::Strength(s) => Error::Usage(format!("--detail-strength must be finite and not negative, got {s}")),
        BlendError::Repeat(n) => {
            Error::Usage(format!("--detail-repeat must be 1 to {}, got {n}", bumpmap::maps::MAX_REPEAT))
        }
        BlendError::Bits(b) => Error::Usage(format!("--bits must be 8 or 16, got {b}")),
        BlendError::Empty(which) => Error::Render(format!("the {which} map has no texels")),
        BlendError::OutOfMemory(e) => Error::OutOfMemory(e),
        BlendError::Read(e) => crate::library::lib_err(e),
        BlendError::Save(e) => save_error(e),
    }
}

/// Tangents that could not be made, in the command line's words: a split angle out of range is
/// `--split-angle`'s fault (exit status 2), anything else the mesh's.
pub fn tangent_error(e: MeshError) -> Error {
    match e {
        MeshError::SplitAngle(angle) => Error::Usage(format!("--split-angle must be in [0, 180], got {angle}")),
        e => Error::Render(format!("the mesh: {e}")),
    }
}
