//! Errors of the GPU backend: no adapter, limits, a lost device, validation, and the core's.

use bumpmap_core::CoreError;

/// Why the GPU backend could not render.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GpuError {
    /// No adapter of any enabled backend answered.
    #[error("no GPU adapter: {0}")]
    NoAdapter(String),
    /// The adapter refused to open a device.
    #[error("the adapter refused a device: {0}")]
    RequestDevice(String),
    /// A texture or the framebuffer is larger than the adapter allows.
    #[error("{what} is {width}x{height}, larger than this adapter's limit of {max} texels a side")]
    TooLarge {
        /// What is too large.
        what: &'static str,
        /// Its width.
        width: usize,
        /// Its height.
        height: usize,
        /// `max_texture_dimension_2d`.
        max: u32,
    },
    /// The framebuffer is empty.
    #[error("framebuffer {width}x{height} refused: it must be non-empty")]
    EmptyFramebuffer {
        /// The width asked for.
        width: usize,
        /// The height asked for.
        height: usize,
    },
    /// The device was lost (driver reset, GPU removed, or destroyed).
    #[error("the GPU device was lost: {0}")]
    DeviceLost(String),
    /// wgpu reported an error (a bug of this backend, or an out-of-memory).
    #[error("wgpu: {0}")]
    Wgpu(String),
    /// A window's surface could not be made or shown.
    #[error("the window's surface: {0}")]
    Surface(String),
    /// Reading the frame back failed.
    #[error("reading the frame back failed: {0}")]
    Readback(String),
    /// The scene or the technique refused (see [`CoreError`]).
    #[error(transparent)]
    Core(#[from] CoreError),
}
