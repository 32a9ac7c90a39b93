//! Errors of the CPU backend that user input can cause.

use bumpmap_core::CoreError;

/// Why the CPU backend could not render.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CpuError {
    /// The framebuffer is empty or larger than the backend accepts.
    #[error("framebuffer {width}x{height} refused: it must be non-empty and at most {max_pixels} pixels")]
    FramebufferSize {
        /// The width asked for.
        width: usize,
        /// The height asked for.
        height: usize,
        /// The largest framebuffer accepted, in pixels.
        max_pixels: usize,
    },
    /// A texture unit's copy of a texture is more than the machine gives.
    #[error(transparent)]
    OutOfMemory(#[from] bumpmap_math::buffer::OutOfMemory),
    /// The scene or the technique refused (see [`CoreError`]).
    #[error(transparent)]
    Core(#[from] CoreError),
}

impl From<bumpmap_core::combiners::CombinerError> for CpuError {
    fn from(e: bumpmap_core::combiners::CombinerError) -> Self {
        CpuError::Core(e.into())
    }
}
