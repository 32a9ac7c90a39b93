//! # bumpmap
//!
//! Bump mapping as three papers describe it — Kilgard, *A Practical and Robust Bump-mapping
//! Technique for Today's GPUs* (2000); the Cg Tutorial, chapter 8; Peercy, Airey & Cabral,
//! *Efficient Bump Mapping Hardware* (1997) — as a library: every technique by name, drawn on the
//! CPU (an emulated GeForce 256 with its register combiners) or the GPU (wgpu) by one renderer,
//! measured against a ground-truth reference, with your own normal maps and glTF materials.
//!
//! ```
//! use bumpmap::{BackendChoice, Renderer, SceneKind, SceneSpec, TechniqueName};
//!
//! // The paper's brick torus, drawn by its three passes on whatever backend exists.
//! let mut renderer = Renderer::new(BackendChoice::Auto)?;
//! let image = renderer.render(&SceneSpec::new(SceneKind::Torus), TechniqueName::Kilgard, 96, 96)?;
//! let lit = image.texels.iter().filter(|t| t[0] > 40).count();
//! assert!(lit > 96 * 96 / 10, "the torus fills part of the frame");
//! # Ok::<(), bumpmap::Error>(())
//! ```
//!
//! - [`Renderer`] ([`renderer`]): one renderer over both backends, [`BackendChoice`] CPU, GPU or
//!   automatic; [`Prepared`] makes a technique's maps once for many frames; [`WindowSurface`]
//!   shows the GPU's frames in a window;
//! - [`TechniqueName`]: the catalogue — every technique by name, what it needs, how it draws;
//! - [`SceneSpec`]: what is drawn — a built-in surface or a mesh, camera, lights, material,
//!   bumps from a height field or a normal map;
//! - [`options`]: the same set up from typed options with their defaults ([`options::SceneOptions`],
//!   every option `bumpmap render` takes), files loaded and values checked;
//! - [`option_table`]: every option of a command as data (name, kind, default, help, what it
//!   needs), which the command line and the Python package are made from;
//! - [`frame`]: one frame from those options: prepared once, drawn, refused when black;
//! - [`motion`]: the light orbiting and the camera turning between frames;
//! - [`maps`]: one height field into the maps a material is made of (the normal map and its
//!   chain, the heights, the horizons, the roughness map, LEAN's moments);
//! - [`assets`]: your own normal map files and meshes with their glTF materials;
//! - [`inspect`]: what a normal map made elsewhere is (DirectX or OpenGL, a normal map at all,
//!   its mips, its seam); [`heights`]: its heights back;
//! - [`bake`]: normal maps baked from a high-poly mesh onto a low-poly one's UV layout, in the
//!   tangent frame the renderer decodes with;
//! - [`bench`](mod@bench): the hot paths timed, as `bumpmap bench` reports them;
//! - [`cpu`]: the x86-64 level this build needs, and whether the processor has it;
//! - [`Error`]: everything that can go wrong, naming the value or the file.
//!
//! The crates behind it are re-exported for what this page does not cover: [`bumpmap_math`]
//! (height fields, normal maps, mip chains, tangents), [`bumpmap_core`] (scenes, GL state,
//! combiner setups, passes), [`bumpmap_io`] (files), [`bumpmap_reference`] (ground truth in
//! float). The examples (`examples/`) show one idea each.

#![warn(missing_docs)]

pub mod assets;
pub mod bake;
pub mod bench;
pub mod cpu;
mod error;
pub mod frame;
pub mod heights;
pub mod inspect;
pub mod maps;
pub mod motion;
pub mod option_table;
pub mod options;
pub mod renderer;

pub use error::Error;
#[cfg(feature = "gpu")]
pub use renderer::WindowSurface;
pub use renderer::{Backend, BackendChoice, Prepared, Renderer};

pub use bumpmap_core::parallax::{HitNormal, Parallax, ParallaxMethod, ParallaxOptions, ParallaxShadow};
pub use bumpmap_core::scene::{Attenuation, Camera, SceneLight, Spot, ViewerModel};
pub use bumpmap_core::technique::{
    BackFacing, EmbossOptions, Gloss, HalfAngle, KilgardOptions, Normalize, ReferenceOptions, SelfShadow,
    SinglePassOptions, SpecularFilter, SpecularMode, SpecularShadow,
};
pub use bumpmap_core::{
    BumpMap, BumpSource, CoreError, Requirement, Scene, SceneKind, SceneParams, SceneSpec, Technique, TechniqueName,
    TechniqueOptions,
};
pub use bumpmap_math::imported::ImportOptions;
pub use bumpmap_math::lighting::Light;
pub use bumpmap_math::{
    Encoding, HeightField, HeightMips, HeightPreset, Kernel, MipChain, MipMode, Named, NormalMapOptions, Rgba8Image,
    Rgba8Mips, Wrap, YConvention,
};

pub use bumpmap_core;
pub use bumpmap_io;
pub use bumpmap_math;
pub use bumpmap_reference;
