//! What is rendered and how, with no backend in it.
//!
//! A [`Scene`] (camera, lights, objects with meshes and materials holding plain
//! RGBA8 textures) and a [`Technique`] make a list of
//! [`Pass`]es — GL state plus a program — that a backend draws: the CPU
//! pipeline (`bumpmap-cpu`), wgpu (`bumpmap-gpu`), or, for ground truth, a reference renderer.
//! No module here rasterizes, samples a texture or evaluates a combiner over pixels.
//!
//! - [`cache`]: what a backend makes of shared scene data, kept per `Arc` while it is used;
//! - [`catalogue`]: every technique by name — what it is, what it needs, its maps and passes;
//! - [`spec`]: a scene before a technique makes its maps (the geometry, where the bumps come
//!   from, everything adjustable; [`spec::parts`]: a loaded model's parts, each with its own
//!   material); [`scene`], [`scenes`]: scene descriptions and the built-in scenes;
//! - [`bump_maps`]: the bump textures the compared techniques read (object-space,
//!   surface-dependent, offset and derivative maps);
//! - [`vertex`]: the vertex stage every technique shares (Kilgard §5.1, Appendix C);
//! - [`state`]: depth, blend and sampler state as data;
//! - [`combiners`]: NV_register_combiners setups and their validation; [`setups`]: the
//!   paper's (Kilgard Appendices G and H);
//! - [`shading`]: the lighting model (Kilgard Eq. 11, 12, 16), once; [`detail`]: a detail
//!   normal map laid over the base's per fragment, once;
//! - [`parallax`]: heights as geometry: the marches that find where a view ray meets the
//!   heights (parallax, steep parallax, POM, relief, the exact walk) and their shadows, once;
//! - [`technique`]: techniques as passes, with their capability checks;
//! - [`lane_math`]: max, min and clamp where a NaN takes the bound;
//! - [`error`]: what can go wrong, as values.

#![warn(missing_docs)]

pub mod bump_maps;
pub mod cache;
pub mod catalogue;
pub mod combiners;
pub mod detail;
pub mod error;
pub mod lane_math;
pub mod parallax;
mod requirement;
pub mod scene;
pub mod scenes;
pub mod setups;
pub mod shading;
pub mod spec;
pub mod state;
pub mod technique;
pub mod vertex;

pub use catalogue::{Requirement, TechniqueName, TechniqueOptions};
pub use error::{CoreError, Feature};
pub use scene::Scene;
pub use spec::BumpMap;
pub use spec::{BumpSource, SceneKind, SceneParams, SceneSpec};
pub use spec::{MeshPart, MeshParts, PartMaterial};
pub use technique::{Pass, Program, Technique};
