//! The CPU pipeline: an emulated GL 1.2 + NV_register_combiners GeForce, and the techniques
//! that render bump-mapped scenes on it.
//!
//! Pipeline, bottom up:
//! - [`texture`]: texture units with GL 1.2 filtering and wrapping, 2D and cube maps;
//! - [`combiners`]: NV_register_combiners, validated and evaluated over fragment batches;
//! - [`raster`]: clipping, setup, tiled rasterization of 2×2 quads, depth test, blending
//!   ([`framebuffer`]);
//! - [`fixed_function`]: texture units + combiners as a fragment shader;
//! - [`lane_math`]: max, min and clamp that compile to one vector instruction.
//!
//! What is drawn and how:
//! - [`scene`], [`scenes`]: scene descriptions and the built-in scenes;
//! - [`setups`]: the paper's combiner setups (Kilgard Appendices G and H) as data;
//! - [`kilgard`]: the paper's three-pass technique;
//! - [`single_pass`]: the same lighting model (and more) in one float pass per light.

pub mod combiners;
pub mod error;
pub mod fixed_function;
pub mod framebuffer;
pub mod kilgard;
pub mod lane_math;
pub mod raster;
pub mod scene;
pub mod scenes;
pub mod setups;
pub mod single_pass;
pub mod texture;

pub use error::RasterError;
pub use framebuffer::Framebuffer;
