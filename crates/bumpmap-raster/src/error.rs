//! Errors of the CPU pipeline that user input can cause.

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RasterError {
    #[error("framebuffer {width}x{height} refused: it must be non-empty and at most {max_pixels} pixels")]
    FramebufferSize { width: usize, height: usize, max_pixels: usize },
    #[error("invalid register-combiner setup: {0}")]
    Combiner(#[from] crate::combiners::CombinerError),
    #[error("{0}")]
    Scene(String),
}
