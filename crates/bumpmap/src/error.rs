//! Every layer's errors as one type, each naming the value or the file at fault. The command
//! line turns them into its own words (which flag caused them); nothing here names a flag.

use std::path::PathBuf;

use bumpmap_core::CoreError;
use bumpmap_cpu::CpuError;
#[cfg(feature = "gpu")]
use bumpmap_gpu::GpuError;
use bumpmap_io::IoError;
use bumpmap_math::imported::ImportError;
use bumpmap_reference::ReferenceError;

/// Why the front door could not load, prepare or draw.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A scene or technique the core refuses (a requirement the scene lacks, an option a
    /// technique cannot do, a value out of range).
    #[error(transparent)]
    Core(#[from] CoreError),
    /// The CPU backend refused (a framebuffer too large).
    #[error(transparent)]
    Cpu(CpuError),
    /// The GPU backend failed (no adapter, a limit, a lost device).
    #[cfg(feature = "gpu")]
    #[error(transparent)]
    Gpu(GpuError),
    /// The GPU backend was asked for where this build has none (a web page's module).
    #[cfg(not(feature = "gpu"))]
    #[error("this build of bumpmap has no GPU backend (the `gpu` feature); draw on the CPU")]
    NoGpuBackend,
    /// The reference refused (a mesh, a projected spotlight pattern, a size).
    #[error(transparent)]
    Reference(ReferenceError),
    /// A file could not be read or written.
    #[error(transparent)]
    Io(#[from] IoError),
    /// A map too big for the memory its work needs.
    #[error("{what}: {source}")]
    OutOfMemory {
        /// The file (or array) being worked on.
        what: String,
        /// The buffer that would not fit.
        source: bumpmap_math::buffer::OutOfMemory,
    },
    /// A normal map file whose levels cannot be a normal map.
    #[error("{}: {source}", .path.display())]
    NormalMap {
        /// The file.
        path: PathBuf,
        /// Why.
        source: ImportError,
    },
}

impl From<CpuError> for Error {
    fn from(e: CpuError) -> Self {
        match e {
            CpuError::Core(e) => Error::Core(e),
            other => Error::Cpu(other),
        }
    }
}

#[cfg(feature = "gpu")]
impl From<GpuError> for Error {
    fn from(e: GpuError) -> Self {
        match e {
            GpuError::Core(e) => Error::Core(e),
            other => Error::Gpu(other),
        }
    }
}

impl From<ReferenceError> for Error {
    fn from(e: ReferenceError) -> Self {
        Error::Reference(e)
    }
}
