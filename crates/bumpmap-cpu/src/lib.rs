//! The CPU backend: an emulated GL 1.2 + NV_register_combiners GeForce that draws the passes
//! of `bumpmap_core`'s techniques.
//!
//! Pipeline, bottom up (all private; what a user needs is re-exported below):
//! - `texture`: texture units with GL 1.2 filtering and wrapping, 2D and cube maps;
//! - `combiners`: the NV_register_combiners evaluator over fragment batches ([`Combiners`]);
//! - `raster`: clipping, setup, tiled rasterization of 2×2 quads, the depth test and
//!   blending into the `framebuffer`'s tiles, with `pixel`'s conversions;
//! - `fixed_function`: texture units + combiners as a fragment shader;
//! - `single_pass`: the lighting model of `bumpmap_core::shading` as a fragment shader;
//! - `renderer`: a technique's passes executed in order ([`CpuRenderer`]).
//!
//! What is drawn and with which state is not decided here: scenes, GL state, combiner setups
//! and techniques are `bumpmap_core`'s. Most users reach this backend through the `bumpmap`
//! crate's renderer, which picks it or the GPU's.

#![warn(missing_docs)]

mod combiners;
mod error;
mod fixed_function;
mod framebuffer;
mod pixel;
mod raster;
mod renderer;
mod single_pass;
mod texture;

pub use combiners::{Combiners, LANES, Lanes, RegisterFile};
pub use error::CpuError;
pub use framebuffer::{Framebuffer, MAX_PIXELS};
pub use renderer::{CpuRenderer, render};
pub use texture::texture_unit_bytes;
