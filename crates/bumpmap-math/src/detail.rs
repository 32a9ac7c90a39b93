//! Detail normals: a second, usually tiling normal map laid over a base one, by the blends
//! engines use (Barré-Brisebois & Hill, *Blending in Detail*, 2012), and the two exact
//! compositions they approximate, against which each is measured:
//!
//! - **added heights** ([`added`]): base and detail are height fields that add, so their slopes
//!   add — the normal of `h₁ + h₂` is `normalize(−(p₁ + p₂), −(q₁ + q₂), 1)` with
//!   `p = −x/z`, `q = −y/z`;
//! - **draped detail** ([`draped`]): the detail lies on the base's bumpy surface, in its tangent
//!   frame — the detail normal turned by the rotation that takes `(0, 0, 1)` to the base normal.
//!
//! Normals here are unit vectors in tangent space, `x`, `y` in `[−1, 1]`, `z` toward the
//! viewer; `y` may point either way (the blends treat `x` and `y` alike, so flipping both
//! inputs' `y` flips the output's).
//!
//! ```
//! use bumpmap_math::detail::{BlendMethod, blend, draped};
//! use glam::Vec3;
//!
//! let base = Vec3::new(0.3, 0.0, 1.0).normalize();
//! let detail = Vec3::new(0.0, 0.2, 1.0).normalize();
//! // Reoriented normal mapping is the draped detail's rotation.
//! let rnm = blend(base, detail, BlendMethod::Rnm);
//! assert!(rnm.angle_between(draped(base, detail)) < 1e-5);
//! // A flat detail leaves the base as it is, except under linear blending.
//! assert!(blend(base, Vec3::Z, BlendMethod::Whiteout).angle_between(base) < 1e-6);
//! assert!(blend(base, Vec3::Z, BlendMethod::Linear).angle_between(base) > 0.05);
//! ```
//!
//! What this module does not do: sample, tile or filter maps, or read their encodings (the
//! caller decodes texels to unit vectors first).

use glam::{Quat, Vec3};

/// How a detail normal is laid over a base normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BlendMethod {
    /// Reoriented normal mapping: the detail turned into the base's frame (Unreal's
    /// `BlendAngleCorrectedNormals`); exact for draped detail.
    #[default]
    Rnm,
    /// Partial derivatives: the slopes `x/z`, `y/z` added; exact for added heights.
    PartialDerivative,
    /// Whiteout: `normalize(x₁ + x₂, y₁ + y₂, z₁·z₂)`.
    Whiteout,
    /// UDN: `normalize(x₁ + x₂, y₁ + y₂, z₁)`, the detail's z dropped.
    Udn,
    /// The two normals added and normalized: flattens both.
    Linear,
    /// Photoshop's overlay per channel of the stored (0..1) values, renormalized.
    Overlay,
}

crate::named!(BlendMethod {
    Rnm => "rnm" | "reoriented": "Reoriented normal mapping: the detail turned into the base's frame (exact for detail draped over the base)",
    PartialDerivative => "partial-derivative" | "pd": "The slopes x/z and y/z added (exact for heights that add)",
    Whiteout => "whiteout": "normalize(x1 + x2, y1 + y2, z1·z2)",
    Udn => "udn": "normalize(x1 + x2, y1 + y2, z1): the detail's z dropped",
    Linear => "linear": "normalize(n1 + n2): flattens both maps",
    Overlay => "overlay": "Photoshop's overlay blend of the stored values per channel, renormalized",
});

/// `detail` laid over `base` by `method`; both unit, the result unit.
pub fn blend(base: Vec3, detail: Vec3, method: BlendMethod) -> Vec3 {
    let (n1, n2) = (base, detail);
    let blended = match method {
        BlendMethod::Rnm => {
            // Barré-Brisebois & Hill's form of the shortest-arc rotation of (0, 0, 1) onto n1.
            let t = n1 + Vec3::Z;
            let u = n2 * Vec3::new(-1.0, -1.0, 1.0);
            t * t.dot(u) / t.z - u
        }
        BlendMethod::PartialDerivative => Vec3::new(n1.x * n2.z + n2.x * n1.z, n1.y * n2.z + n2.y * n1.z, n1.z * n2.z),
        BlendMethod::Whiteout => Vec3::new(n1.x + n2.x, n1.y + n2.y, n1.z * n2.z),
        BlendMethod::Udn => Vec3::new(n1.x + n2.x, n1.y + n2.y, n1.z),
        BlendMethod::Linear => n1 + n2,
        BlendMethod::Overlay => {
            let overlay = |a: f32, b: f32| if a < 0.5 { 2.0 * a * b } else { 1.0 - 2.0 * (1.0 - a) * (1.0 - b) };
            let (a, b) = (n1 * 0.5 + 0.5, n2 * 0.5 + 0.5);
            Vec3::new(overlay(a.x, b.x), overlay(a.y, b.y), overlay(a.z, b.z)) * 2.0 - 1.0
        }
    };
    blended.normalize_or(base)
}

/// `detail` with its slopes multiplied by `strength` (0: flat, 1: as it is): the normal of
/// its heights scaled by `strength`.
pub fn with_strength(detail: Vec3, strength: f32) -> Vec3 {
    Vec3::new(detail.x * strength, detail.y * strength, detail.z).normalize_or(Vec3::Z)
}

/// The exact normal of heights that add: the slopes of both summed. Where either faces away
/// from the surface (z ≤ 0, no slope) the base is returned.
pub fn added(base: Vec3, detail: Vec3) -> Vec3 {
    if base.z <= 0.0 || detail.z <= 0.0 {
        return base;
    }
    Vec3::new(base.x / base.z + detail.x / detail.z, base.y / base.z + detail.y / detail.z, 1.0).normalize()
}

/// The exact normal of a detail draped over the base's surface: `detail` turned by the
/// shortest rotation that takes `(0, 0, 1)` to `base` (a quaternion here, independent of
/// [`BlendMethod::Rnm`]'s formula).
pub fn draped(base: Vec3, detail: Vec3) -> Vec3 {
    Quat::from_rotation_arc(Vec3::Z, base) * detail
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Named;

    fn unit(x: f32, y: f32) -> Vec3 {
        Vec3::new(x, y, 1.0).normalize()
    }

    #[test]
    fn every_method_keeps_a_flat_base_under_a_flat_detail() {
        for &m in BlendMethod::ALL {
            assert!(blend(Vec3::Z, Vec3::Z, m).angle_between(Vec3::Z) < 1e-6, "{}", m.name());
        }
    }

    #[test]
    fn partial_derivatives_add_slopes_and_rnm_rotates() {
        for (b, d) in [((0.3, -0.1), (0.2, 0.4)), ((-0.8, 0.5), (0.1, -0.9)), ((0.0, 0.0), (1.5, 0.2))] {
            let (base, detail) = (unit(b.0, b.1), unit(d.0, d.1));
            let pd = blend(base, detail, BlendMethod::PartialDerivative);
            assert!(pd.angle_between(added(base, detail)) < 1e-5);
            assert!(pd.angle_between(unit(b.0 + d.0, b.1 + d.1)) < 1e-5);
            let rnm = blend(base, detail, BlendMethod::Rnm);
            assert!(rnm.angle_between(draped(base, detail)) < 1e-5);
            // The rotation keeps the angle the detail makes with the surface.
            assert!((rnm.dot(base) - detail.z).abs() < 1e-5);
        }
    }

    #[test]
    fn strength_scales_the_slopes() {
        let d = unit(0.4, -0.2);
        let half = with_strength(d, 0.5);
        assert!((half.x / half.z - 0.2).abs() < 1e-6 && (half.y / half.z + 0.1).abs() < 1e-6);
        assert_eq!(with_strength(d, 0.0), Vec3::Z);
    }
}
