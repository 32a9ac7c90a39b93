//! Baking: the detail of a high-poly mesh stored in a normal map over a low-poly mesh's UV
//! layout (Cignoni et al. 1998; Cohen, Olano & Manocha 1998), encoded in the tangent frame the
//! renderer decodes with, so the low-poly drawn with its map shades as the high-poly does.
//!
//! ```
//! use bumpmap_bake::{BakeOptions, bake};
//! use bumpmap_math::surface::Surface;
//!
//! // A sphere baked onto itself: every texel's normal is the surface's own, (0, 0, 1).
//! let low = Surface::Sphere { radius: 1.0 }.tessellate(24, 12, glam::Vec2::ONE);
//! let high = low.clone();
//! let options = BakeOptions { width: 32, height: 32, front: Some(0.05), back: Some(0.05), ..Default::default() };
//! let baked = bake(&high, &low, &options, &|_, _| {}).unwrap();
//! assert!(baked.hit.iter().filter(|h| **h).count() > 32 * 30, "the layout covers the texels");
//! let z: Vec<f32> = baked.tangent.iter().zip(&baked.hit).filter(|(_, h)| **h).map(|(n, _)| n.z).collect();
//! assert!(z.iter().all(|&z| z > 0.99), "flat against itself");
//! ```
//!
//! How a texel is baked: each of its samples (stratified in the texel) that falls inside a
//! triangle of LOW's UV layout gives a point on LOW and a direction — LOW's averaged normal by
//! default, the same on both sides of a hard edge, or its own normal ([`RayMode`]). The ray
//! starts [`BakeOptions::front`] in front of the point (on the *cage*) and goes inward as far as
//! [`BakeOptions::back`] behind it; the **first hit from the cage inward** wins, as xNormal and
//! Marmoset Toolbag do. The hit's normal (HIGH's interpolated vertex normal) is stored in
//! object space and in LOW's tangent frame at the point ([`TangentDecode`]: the exact inverse
//! of the decode, interpolated and unnormalized as the renderer has it), with the signed
//! distance from LOW along the ray. Texels no sample covers are filled from their neighbours
//! for [`BakeOptions::padding`] texels, so mips and filtering do not bleed the background in.
//!
//! What this crate does not do: read or write files, make LOW's tangents (the caller makes them
//! with `bumpmap_math::tangent` in the mode the renderer will use, and bakes on that mesh), or
//! say anything (progress goes to a function).

#![warn(missing_docs)]

mod bake;
mod encode;
mod frame;
mod high;
mod pad;
mod texels;

pub use bake::{
    BakeError, BakeOptions, Baked, MAX_OCCLUSION_RAYS, MAX_SAMPLES, MAX_SIDE, Pairing, RayMode, bake, bake_paired,
    bake_with_cage,
};
pub use encode::{TangentDecode, encode_in_frame};
