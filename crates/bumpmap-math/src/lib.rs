//! Pure mathematics of bump mapping: everything the techniques need that is not a pipeline.
//!
//! This crate knows no file formats and draws no pixels. It turns height fields into normal
//! maps and mip chains (Kilgard §2.4.2, §2.6, §5.3, Appendices E–F), builds and samples
//! normalization cube maps (Kilgard §5.2, Appendix D, Table 1), describes surfaces and their
//! tangent frames (Cg Tutorial §8.2–8.4, Peercy §2) and computes the per-vertex tangent-space
//! light and half-angle vectors (Kilgard §5.1, Appendix C).
//!
//! Every chain's level sizes and footprints, and the one check of a chain handed over, are
//! [`levels`]'s; every deterministic integer hash (noise, the reference's jitter) is [`hash`]'s.
//!
//! Conventions (pinned by tests):
//! - texture coordinate `t` grows with the row index of texel memory (row 0 is t = 0);
//! - normals follow Kilgard Eq. 25, `n ∝ (-∂F/∂u, -∂F/∂v, 1)`;
//! - tangent frames are `T = normalize(∂P/∂s)`, `B = N × T` (times the handedness `w`).

#![warn(missing_docs)]

pub mod blinn;
pub mod buffer;
pub mod cubemap;
pub mod detail;
pub mod encoding;
mod fourier;
pub mod hash;
pub mod height;
pub mod height_mips;
pub mod height_trace;
pub mod horizon;
pub mod image;
pub mod imported;
pub mod inspect;
pub mod integration;
pub mod interpolant;
pub mod kernel;
pub mod lean;
pub mod levels;
pub mod lighting;
pub mod mesh;
pub mod mip;
pub mod named;
pub mod normalmap;
pub mod progress;
pub mod roughness;
pub mod surface;
pub mod tangent;

pub use cubemap::{CubeFace, NormalizationCubeMap};
pub use encoding::{Encoding, Texel};
pub use height::{HeightField, HeightPreset, HeightSamples, bricks_decal};
pub use height_mips::{HeightChain, HeightLevel, HeightMips, HeightMipsError};
pub use horizon::{HorizonError, HorizonLevel, HorizonMap, Horizons};
pub use image::{Image, Rgba8Image, Rgba8Mips, Rgba16Image};
pub use imported::{ImportOptions, ImportedNormalMap, import_normal_map};
pub use kernel::{Kernel, Wrap};
pub use lean::{LeanMips, LeanMoments};
pub use mip::{MipChain, MipMode};
pub use named::Named;
pub use normalmap::{NormalMapOptions, YConvention};
