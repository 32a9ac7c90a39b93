//! The GPU backend: `bumpmap_core`'s techniques drawn with wgpu, headless (render to texture,
//! read back) or into a window's surface.
//!
//! - `renderer`: [`GpuRenderer`], a technique's passes as render passes into an RGBA8 target;
//! - `pipelines`: GL state (depth, blend, colour mask, culling) as pipeline state;
//! - `textures`: mip chains, normalization cube maps and samplers on the device;
//! - `combiner_wgsl`: register-combiner setups turned into WGSL by a generator
//!   ([`combiners_wgsl`]);
//! - `prelude`: the WGSL generated from the Rust constants it must agree with — the vertex
//!   stage and its varying slots, the lit program's switches ([`shading_wgsl`]);
//! - `lit` with `lit.wgsl`, `shading.wgsl`, `detail.wgsl` and `parallax.wgsl`: the single
//!   pass's fragment program (with a detail map, with heights as geometry), its uniforms and its
//!   override constants;
//! - `context`: the adapter and device, and the faults wgpu reports out of band ([`Context`]);
//! - `present`: a frame shown on a window's surface with an overlay over it
//!   ([`WindowSurface`]).
//!
//! ```
//! use bumpmap_core::{SceneKind, SceneSpec, TechniqueName, TechniqueOptions};
//! use bumpmap_gpu::GpuRenderer;
//!
//! // The single pass on the brick torus, read back, where an adapter exists (Mesa's lavapipe
//! // will do; without one, `new` says why).
//! let (scene, technique) =
//!     TechniqueName::SinglePass.prepare(&SceneSpec::new(SceneKind::Torus), &TechniqueOptions::default())?;
//! let Ok(mut gpu) = GpuRenderer::new() else { return Ok(()) };
//! let image = gpu.render(&scene, &technique, 64, 64, |_, _| {})?;
//! assert!(image.texels.iter().any(|t| t[0] > 40), "lit on {}", gpu.adapter_name());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Not here: making a window (the viewer's), and any CPU rasterization — this crate depends
//! on the core and math crates only. Most users reach it through the `bumpmap` crate's
//! renderer, which picks this backend or the CPU's.

#![warn(missing_docs)]

mod combiner_wgsl;
mod context;
mod error;
mod lit;
mod pipelines;
mod prelude;
mod present;
mod renderer;
mod textures;

pub use combiner_wgsl::combiners_wgsl;
pub use context::Context;
pub use error::GpuError;
pub use lit::{
    detail_name, parallax_name, parallax_shadow_name, self_shadow_name, specular_filter_name, specular_shadow_name,
};
pub use prelude::{parallax_wgsl, shading_wgsl};
pub use present::WindowSurface;
pub use renderer::GpuRenderer;
/// What a window must offer for [`GpuRenderer::window_surface`] (wgpu's own bound).
pub use wgpu::DisplayAndWindowHandle;
