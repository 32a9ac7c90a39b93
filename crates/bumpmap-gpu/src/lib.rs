//! The GPU backend: `bumpmap_core`'s techniques drawn with wgpu, headless (render to texture,
//! read back).
//!
//! - [`renderer`]: [`GpuRenderer`], a technique's passes as render passes into an RGBA8 target;
//! - [`pipelines`]: GL state (depth, blend, colour mask, culling) as pipeline state;
//! - [`textures`]: mip chains, normalization cube maps and samplers on the device;
//! - [`combiner_wgsl`]: register-combiner setups turned into WGSL by a generator;
//! - [`context`]: the adapter and device, and the faults wgpu reports out of band;
//! - `lit.rs` (private) with `lit.wgsl`: the single pass's fragment program, its uniforms and
//!   its override constants; `vertex.wgsl`: the shared vertex stage.
//!
//! Not here: a window or surface (the viewer's), and any CPU rasterization — this crate depends
//! on the core and math crates only.

pub mod combiner_wgsl;
pub mod context;
pub mod error;
mod lit;
pub mod pipelines;
pub mod renderer;
pub mod textures;

pub use error::GpuError;
pub use renderer::GpuRenderer;
