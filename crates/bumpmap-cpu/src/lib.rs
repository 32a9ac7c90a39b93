//! The CPU backend: an emulated GL 1.2 + NV_register_combiners GeForce that draws the passes
//! of `bumpmap_core`'s techniques.
//!
//! Pipeline, bottom up:
//! - [`texture`]: texture units with GL 1.2 filtering and wrapping, 2D and cube maps;
//! - [`combiners`]: the NV_register_combiners evaluator over fragment batches;
//! - [`raster`]: clipping, setup, tiled rasterization of 2×2 quads, the depth test and
//!   blending into the [`framebuffer`]'s tiles, with [`pixel`]'s conversions;
//! - [`fixed_function`]: texture units + combiners as a fragment shader;
//! - `single_pass`: the lighting model of `bumpmap_core::shading` as a fragment shader;
//! - [`renderer`]: a technique's passes executed in order.
//!
//! What is drawn and with which state is not decided here: scenes, GL state, combiner setups
//! and techniques are `bumpmap_core`'s.

pub mod combiners;
pub mod error;
pub mod fixed_function;
pub mod framebuffer;
pub mod pixel;
pub mod raster;
pub mod renderer;
mod single_pass;
pub mod texture;

pub use error::CpuError;
pub use framebuffer::Framebuffer;
pub use renderer::{CpuRenderer, render};
