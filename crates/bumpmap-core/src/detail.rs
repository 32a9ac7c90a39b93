//! Detail normals at render time: a second normal map, tiling `repeat` times over the base's
//! texture coordinates and sampled with its own mip chain, laid over the base's filtered normal
//! per fragment by one of `bumpmap_math::detail`'s blends. [`detail_normal`] is the one
//! definition; the CPU pipeline calls it per lane and `detail.wgsl` is its copy, tested
//! against it.
//!
//! The filtered normals' lengths (what Toksvig's filter and Eq. 11's diffuse term read) are
//! combined as independent bumps combine: each length stands for a slope variance by Toksvig's
//! model, `|N̄| = 1 / (1 + σ²)`, the detail's variance grows with the square of its strength,
//! and the two variances add.
//!
//! What this module does not do: read the detail's file (`bumpmap::options`), sample it (the
//! backends), or blend whole maps into a file (`bumpmap::maps::blend_maps`). Techniques that
//! cannot read a second normal map (the paper's combiners, emboss, the reference) refuse one:
//! the checks are in [`crate::technique::single_pass::validate`] and the options' layer.

use std::sync::Arc;

use glam::{Vec3, Vec4};

use bumpmap_math::Rgba8Mips;
pub use bumpmap_math::detail::BlendMethod;
use bumpmap_math::detail::{blend, with_strength};

/// A detail normal map as the single pass reads it.
#[derive(Clone, Debug, PartialEq)]
pub struct DetailLayer {
    /// The detail's texels as the normal map's: RGB the range-compressed unit normal in the
    /// renderer's texture space (green up the image), A its filtered length, every level.
    pub map: Arc<Rgba8Mips>,
    /// How many times the detail repeats over one repeat of the base (the same both ways).
    pub repeat: f32,
    /// How the detail is laid over the base.
    pub method: BlendMethod,
    /// What the detail's slopes are multiplied by (0: no detail, 1: as stored).
    pub strength: f32,
}

/// The most a detail may repeat over one repeat of the base: texture coordinates stay far
/// inside single precision's whole numbers.
pub const MAX_DETAIL_REPEAT: f32 = 1024.0;

/// `detail` (a filtered texel: RGB range-compressed, A its length) laid over `base` (the same
/// form) by `method` at `strength`: RGB the blended unit normal range-compressed, A the
/// combined length (the module's note).
///
/// ```
/// use bumpmap_core::detail::{BlendMethod, detail_normal};
/// use glam::Vec4;
///
/// let flat = Vec4::new(0.5, 0.5, 1.0, 1.0);
/// let tilted = Vec4::new(0.8, 0.5, 0.9, 0.9);
/// // A flat detail leaves the base; a flat base under RNM takes the detail's direction.
/// assert!((detail_normal(tilted, flat, BlendMethod::Rnm, 1.0) - tilted).abs().max_element() < 0.01);
/// let n = detail_normal(flat, tilted, BlendMethod::Rnm, 1.0);
/// assert!((n.truncate() - tilted.truncate()).abs().max_element() < 0.01);
/// // Strength 0: no detail at all, its length included.
/// assert_eq!(detail_normal(tilted, tilted, BlendMethod::Whiteout, 0.0), tilted);
/// ```
pub fn detail_normal(base: Vec4, detail: Vec4, method: BlendMethod, strength: f32) -> Vec4 {
    if strength == 0.0 {
        return base;
    }
    let unit = |t: Vec4| (t.truncate() * 2.0 - 1.0).normalize_or(Vec3::Z);
    let n = blend(unit(base), with_strength(unit(detail), strength), method);
    let n = n * 0.5 + 0.5;
    n.extend(combined_length(base.w, detail.w, strength))
}

/// The length of two independent bumps' filtered normal: Toksvig's variances
/// `σ² = 1/|N̄| − 1`, the detail's times `strength²`, added.
fn combined_length(base: f32, detail: f32, strength: f32) -> f32 {
    let variance = |a: f32| 1.0 / a.clamp(1e-4, 1.0) - 1.0;
    1.0 / (1.0 + variance(base) + strength * strength * variance(detail))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpmap_math::Named;
    use bumpmap_math::detail::draped;
    use proptest::prelude::*;

    fn texel(n: Vec3, a: f32) -> Vec4 {
        (n.normalize() * 0.5 + 0.5).extend(a)
    }

    proptest! {
        /// Every method gives a unit normal and a length in (0, 1]; unit texels keep length 1.
        #[test]
        fn unit_normals_and_lengths_in_range(
            bx in -2.0f32..2.0, by in -2.0f32..2.0, dx in -2.0f32..2.0, dy in -2.0f32..2.0,
            a1 in 0.05f32..1.0, a2 in 0.05f32..1.0, s in 0.0f32..3.0,
        ) {
            for &m in BlendMethod::ALL {
                let out = detail_normal(texel(Vec3::new(bx, by, 1.0), a1), texel(Vec3::new(dx, dy, 1.0), a2), m, s);
                let n = out.truncate() * 2.0 - 1.0;
                prop_assert!((n.length() - 1.0).abs() < 1e-4, "{} {n}", m.name());
                prop_assert!(out.w > 0.0 && out.w <= a1 + 1e-6);
                let unit = detail_normal(texel(Vec3::new(bx, by, 1.0), 1.0), texel(Vec3::new(dx, dy, 1.0), 1.0), m, s);
                prop_assert!((unit.w - 1.0).abs() < 1e-6);
            }
        }

        /// RNM at strength 1 is the draped detail of the decoded texels.
        #[test]
        fn rnm_is_the_draped_detail(bx in -1.5f32..1.5, by in -1.5f32..1.5, dx in -1.5f32..1.5, dy in -1.5f32..1.5) {
            let (b, d) = (Vec3::new(bx, by, 1.0).normalize(), Vec3::new(dx, dy, 1.0).normalize());
            let out = detail_normal(texel(b, 1.0), texel(d, 1.0), BlendMethod::Rnm, 1.0);
            prop_assert!((out.truncate() * 2.0 - 1.0).angle_between(draped(b, d)) < 1e-3);
        }
    }

    #[test]
    fn lengths_combine_as_variances() {
        // σ² = 1 each: 1 / (1 + 1 + 1).
        assert!((combined_length(0.5, 0.5, 1.0) - 1.0 / 3.0).abs() < 1e-6);
        // Half strength: a quarter of the detail's variance.
        assert!((combined_length(1.0, 0.5, 0.5) - 1.0 / 1.25).abs() < 1e-6);
    }
}
