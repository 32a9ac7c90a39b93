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
//! ```
//! use bumpmap_core::{SceneKind, SceneSpec, TechniqueName, TechniqueOptions};
//! use bumpmap_cpu::{CpuRenderer, Framebuffer};
//!
//! // The paper's three passes on the brick torus, at 64×64.
//! let (scene, technique) =
//!     TechniqueName::Kilgard.prepare(&SceneSpec::new(SceneKind::Torus), &TechniqueOptions::default())?;
//! let mut fb = Framebuffer::new(64, 64)?;
//! let mut passes = Vec::new();
//! CpuRenderer::new().render(&scene, &technique, &mut fb, |name, _| passes.push(name.to_string()))?;
//! assert_eq!(passes, ["decal", "diffuse", "specular"], "Kilgard Figure 12's snapshots");
//! let lit = fb.to_rgba8().iter().filter(|t| t[0] > 40).count();
//! assert!(lit > 64 * 64 / 10, "the torus is lit ({lit} pixels)");
//! assert_eq!(fb.pixel(0, 0), [0, 0, 0, 0], "the corner shows the cleared framebuffer");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
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
