//! The CLI's error type: every layer's errors, each message naming the file or value at fault.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum CliError {
    #[error(transparent)]
    Io(#[from] bumpmap_io::IoError),
    #[error("{path}: {source}")]
    NormalMap { path: String, source: bumpmap_math::normalmap::NormalMapError },
    #[error("{}: {reason}", path.display())]
    Path { path: PathBuf, reason: String },
    #[error("{0}")]
    Render(String),
    #[error("{failed} of {total} files failed (see the messages above)")]
    Batch { failed: usize, total: usize },
}
