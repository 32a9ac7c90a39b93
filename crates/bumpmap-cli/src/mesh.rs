//! Meshes for `render --scene mesh:FILE` and `bumpmap tangents`.

use std::path::Path;

use bumpmap_math::mesh::Mesh;

use crate::error::CliError;

/// Loads a mesh and makes sure it has tangents (generated when the file has none).
pub fn load_for_render(path: &Path) -> Result<Mesh, CliError> {
    Err(CliError::Render(format!("{}: mesh scenes are not available yet", path.display())))
}
