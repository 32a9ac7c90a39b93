//! Ground truth: what a bump-mapped scene looks like when nothing is approximated that the
//! techniques approximate.
//!
//! Each sample of each pixel finds the surface it sees, evaluates the built-in object's exact
//! surface there (P, ∂P/∂u, ∂P/∂v), perturbs its normal as Blinn does (Kilgard Eq. 5, Peercy
//! Eq. 1–2) with the derivatives of a C¹ bicubic interpolant of the height field
//! (`bumpmap_math::interpolant`), and lights it with the project's one lighting model
//! (`bumpmap_core::shading::shade`) in float, with L and H exact at the sample. Blinn's formula
//! itself is `bumpmap_math::blinn`. A pixel is the mean of its samples: box filtering over the
//! pixel, which is what a mip chain approximates at a distance.
//!
//! With [`ReferenceOptions::displaced`] the heights are geometry: each object's surface carved
//! by them (`depth` per unit of height along the normal), the camera's rays traced to it, and
//! shadow rays cast against it ([`displaced`]): the ground truth of the parallax techniques.
//!
//! - [`visibility`]: which triangle each sample sees (sample positions, tiles, depth);
//! - [`displaced`]: a carved surface and rays against it — exact on flat surfaces,
//!   micro-tessellated (`tessellated`) on curved ones;
//! - [`DisplacedScene`]: every object's carved surface, the nearest hit of a camera ray and
//!   its colour ([`camera_ray`] makes the ray of an image point);
//! - [`occlusion`]: ambient occlusion and bent normals by occlusion rays from texel centres;
//! - [`render`](render()): the whole image, in parallel over tiles, with a progress callback;
//! - [`error`]: what the reference refuses.
//!
//! ```
//! use bumpmap_core::technique::ReferenceOptions;
//! use bumpmap_core::{SceneKind, SceneSpec};
//!
//! // The ground truth of the brick wall, 4 samples a pixel: the wall fills the middle.
//! let scene = SceneSpec::new(SceneKind::Wall).build()?;
//! let options = ReferenceOptions { samples_per_pixel: 4, ..Default::default() };
//! let image = bumpmap_reference::render(&scene, 32, 32, &options, &|_, _| {})?;
//! let centre = image.pixels[16 * 32 + 16];
//! assert!(centre.x > 0.05, "lit: {centre}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! What this crate does not do: it depends on no backend (it is an oracle for them); it
//! rasterizes no mip level and quantizes nothing to 8 bits; on the base surface it finds
//! visibility on the same tessellation the techniques draw, so silhouettes agree and the
//! comparison measures shading, while everything shaded is evaluated on the exact surface.
//! Loaded meshes (no analytic surface) and projected spotlight patterns are refused.

#![warn(missing_docs)]

pub mod displaced;
pub mod error;
pub mod occlusion;
mod render;
pub mod visibility;

pub use error::ReferenceError;
pub use render::{DisplacedScene, SceneHit, camera_ray};
pub use render::{LinearImage, MAX_SAMPLES_PER_PIXEL, MAX_SIDE, ReferenceOptions, render};
