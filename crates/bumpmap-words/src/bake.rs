//! What a bake refused ([`BakeFileError`]), named by the files and flags that caused it: a value
//! out of range is its flag's fault (exit status 2), a mesh that cannot be baked its file's.

use std::path::Path;

use bumpmap::bake::{BakeError, BakeFileError};

use crate::Error;

/// A bake of `high` onto `low` that made nothing, in the command line's words.
pub fn bake_error(e: BakeFileError, high: &Path, low: &Path) -> Error {
    let at = |path: &Path, reason: String| Error::Path { path: path.to_path_buf(), reason };
    match e {
        BakeFileError::Io(e) => Error::Io(e),
        BakeFileError::Save(e) => crate::maps::save_error(e),
        BakeFileError::Bits(bits) => Error::Usage(format!("--bits must be 8 or 16, got {bits}")),
        BakeFileError::LowNeedsPng { path } => Error::Usage(format!(
            "--low-out {}: the glTF carries the normal map as a PNG, green up as glTF has it: give -o a .png and --y-convention opengl",
            path.display()
        )),
        BakeFileError::Clash { path, what } => Error::Usage(format!("{}: {what}", path.display())),
        e @ BakeFileError::Unmatched { .. } => Error::Render(format!("--match-names: {e}")),
        e @ BakeFileError::Unnamed { .. } => Error::Render(format!("--match-names: {e}")),
        BakeFileError::Cage { path, reason } => at(&path, format!("--cage: {reason}")),
        BakeFileError::Tangents { path, source } => at(&path, format!("its tangents: {source}")),
        BakeFileError::Bake(e) => match e {
            BakeError::NoTexcoords => at(low, "has no texture coordinates: LOW needs a UV layout to bake into".into()),
            BakeError::NoTangents => at(low, "has no tangents".into()),
            BakeError::CageSize { cage, low: vertices } => {
                Error::Usage(format!("--cage has {cage} points for the low-poly mesh's {vertices} vertices"))
            }
            BakeError::CageNotFinite(i) => Error::Usage(format!("--cage: its point {i} is not finite")),
            BakeError::Mesh { which, source } => at(if which == "high-poly" { high } else { low }, source.to_string()),
            BakeError::Size { width, height } => {
                Error::Usage(format!("--size must be 1 to {}, got {width}x{height}", bumpmap::bake::MAX_SIDE))
            }
            BakeError::OcclusionRays(n) => {
                Error::Usage(format!("--ao-rays must be 0 to {}, got {n}", bumpmap::bake::MAX_OCCLUSION_RAYS))
            }
            BakeError::Samples(n) => {
                Error::Usage(format!("--spp must be 1 to {}, got {n}", bumpmap::bake::MAX_SAMPLES))
            }
            BakeError::Distance { front, back } => Error::Usage(format!(
                "--extrude and --max-distance must be finite, not negative and not both 0, got {front} and {back}"
            )),
            BakeError::NothingCovered { width, height } => at(
                low,
                format!(
                    "no texel of the {width}x{height} map lies inside its UV layout (texture coordinates outside [0, 1], or degenerate)"
                ),
            ),
            BakeError::MostMissed { missed, covered, front, back } => Error::Render(format!(
                "{} onto {}: {missed} of {covered} texels' rays met the high-poly mesh nowhere within {front} in front (--extrude) and {back} behind (--max-distance): the meshes do not overlap there, or the distances are too short; nothing was written",
                high.display(),
                low.display()
            )),
            BakeError::Pairing(why) => Error::Render(format!("--match-names: {why}")),
            BakeError::OutOfMemory(e) => Error::OutOfMemory(e),
        },
    }
}
