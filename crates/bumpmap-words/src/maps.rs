//! What making maps from heights refused ([`MapError`]), a chain that could not be written
//! ([`SaveError`]) and tangents that could not be made ([`MeshError`]), named by the flags that caused them.

use bumpmap::maps::{MapError, SaveError};
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

/// Tangents that could not be made, in the command line's words: a split angle out of range is
/// `--split-angle`'s fault (exit status 2), anything else the mesh's.
pub fn tangent_error(e: MeshError) -> Error {
    match e {
        MeshError::SplitAngle(angle) => Error::Usage(format!("--split-angle must be in [0, 180], got {angle}")),
        e => Error::Render(format!("the mesh: {e}")),
    }
}
