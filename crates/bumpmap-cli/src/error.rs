//! The CLI's error type: every layer's errors, each message naming the file or value at fault.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum CliError {
    #[error(transparent)]
    Io(#[from] bumpmap_io::IoError),
    #[error("{path}: {source}")]
    NormalMap { path: String, source: bumpmap_math::normalmap::NormalMapError },
    #[error("{}: {reason}", bumpmap_io::error::shown(path))]
    Path { path: PathBuf, reason: String },
    #[error("{0}")]
    Render(String),
    /// A value outside its option's range, found after parsing: a malformed command line, as
    /// clap's own range errors are (exit status 2).
    #[error("{0}")]
    Usage(String),
    #[error("{failed} of {total} files failed (see the messages above)")]
    Batch { failed: usize, total: usize },
}

impl CliError {
    /// The exit status: 2 for a malformed command line (as clap uses), 1 for everything else.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Usage(_) => 2,
            _ => 1,
        }
    }
}
