//! The errors of every layer as one type, each message naming the file or value at fault, and
//! the one rule for how serious each is (the command line's exit status; Python picks its
//! exception class from the same variants).

use std::path::PathBuf;

/// What a command or a Python function could not do, in words that name the option at fault.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error(transparent)]
    Io(#[from] bumpmap_io::IoError),
    /// A height field that cannot become a normal map.
    #[error("{path}: {source}")]
    NormalMap {
        /// The height field (a file or a preset).
        path: String,
        /// Why.
        source: bumpmap_math::normalmap::NormalMapError,
    },
    /// A path that cannot be used as given.
    #[error("{}: {reason}", bumpmap_io::error::shown(path))]
    Path {
        /// The path.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// A scene or technique that cannot be drawn as asked.
    #[error("{0}")]
    Render(String),
    /// A value outside its option's range, found after parsing: a malformed command line, as
    /// clap's own range errors are (exit status 2).
    #[error("{0}")]
    Usage(String),
    /// A buffer the inputs ask for is more than the machine gives (exit status 1: the same
    /// command fits on a bigger machine). The command adds which inputs made it that big.
    #[error(transparent)]
    OutOfMemory(bumpmap::bumpmap_math::buffer::OutOfMemory),
    /// No device to draw with (no GPU adapter for `--backend gpu`).
    #[error("{0}")]
    NoDevice(String),
    /// The caller asked to stop before the files were put in place (none were).
    #[error("interrupted: nothing was written")]
    Interrupted,
    /// Some files of a folder run failed.
    #[error("{failed} of {total} files failed (see the messages above)")]
    Batch {
        /// How many failed.
        failed: usize,
        /// How many there were.
        total: usize,
    },
}

impl Error {
    /// The exit status, the one rule every command follows: 2 for a malformed command line (as
    /// clap uses), which includes a value out of its range however it was noticed (by the
    /// argument parser, the command or a library); 1 for everything else (files, devices, inputs
    /// that cannot be used).
    pub fn exit_code(&self) -> i32 {
        use bumpmap_math::normalmap::NormalMapError;
        match self {
            Error::Usage(_) => 2,
            Error::NormalMap { source: NormalMapError::BadScale(_), .. } => 2,
            Error::Io(bumpmap_io::IoError::NotAPreset { out_of_range: true, .. }) => 2,
            // Two options naming one file, however it was noticed.
            Error::Io(bumpmap_io::IoError::SameOutput { .. }) => 2,
            _ => 1,
        }
    }
}
