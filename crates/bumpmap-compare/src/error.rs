//! What `compare` can refuse or fail at, naming the value or the file; the command line words
//! each as its flags have it.

use std::path::PathBuf;

use bumpmap::SceneKind;

/// Why `compare` could not measure or write.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// A scene the reference cannot evaluate exactly.
    #[error("{} is not a built-in surface ({}): the reference evaluates the exact surface", .0.name(), SceneKind::built_in_names())]
    NotASurface(SceneKind),
    /// A bump scale below zero or not a number.
    #[error("bump_scale must be a number ≥ 0, got {0}")]
    BumpScale(f32),
    /// The reference's samples per pixel out of range.
    #[error("spp must be in 1..={max}, got {0}", max = bumpmap::options::MAX_SAMPLES_PER_PIXEL)]
    Spp(u32),
    /// A technique named twice (it would be drawn twice and collide on its own image).
    #[error("techniques names {0} twice")]
    Twice(String),
    /// The scene and one technique's maps will not fit in memory together.
    #[error("this scene (bumps {}x{}) is too big for the memory this process may use: {source}", .bumps.0, .bumps.1)]
    TooBig {
        /// What would not fit.
        source: bumpmap_math::buffer::OutOfMemory,
        /// The bump texture's size.
        bumps: (usize, usize),
    },
    /// The reference drew nothing: there is nothing to measure against.
    #[error("the reference image is black: nothing in view is lit")]
    BlackReference,
    /// A study's own scene could not be drawn.
    #[error("{study}: {reason}")]
    Study {
        /// Which study.
        study: &'static str,
        /// Why.
        reason: String,
    },
    /// A study's normal map could not be made.
    #[error("{name}: {source}")]
    NormalMap {
        /// The height field's name.
        name: &'static str,
        /// Why.
        source: bumpmap_math::normalmap::NormalMapError,
    },
    /// The output is a file, not a folder.
    #[error("{}: is a file; compare writes a folder of results", bumpmap_io::error::shown(.0))]
    OutputIsAFile(PathBuf),
    /// The caller asked to stop before the files were put in place (none were).
    #[error("interrupted: nothing was written")]
    Interrupted,
    /// The reference refused.
    #[error(transparent)]
    Reference(#[from] bumpmap_reference::ReferenceError),
    /// A file could not be read or written.
    #[error(transparent)]
    Io(#[from] bumpmap_io::IoError),
    /// A scene, technique or renderer the library refused.
    #[error(transparent)]
    Library(#[from] bumpmap::Error),
}

impl From<bumpmap_core::CoreError> for CompareError {
    fn from(e: bumpmap_core::CoreError) -> Self {
        CompareError::Library(bumpmap::Error::Core(e))
    }
}
