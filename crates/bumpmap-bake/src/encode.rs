//! The tangent-space encode that inverts a decode exactly: a decode that forms the object-space
//! normal as `x·T + y·B + z·N` from interpolated, unnormalized T, B and N (MikkTSpace's header
//! states it; this renderer's vertex stage does the same by taking L into the per-vertex frame
//! with dot products) is inverted by `[T B N]⁻¹ · n`, normalized — not by dot products with an
//! orthonormalized frame, which is what leaves seams and waviness where the frame is skewed.
//!
//! `bumpmap_math::tangent::TangentDecode` names the two decodes a bake is made for (each picks
//! its B), and the renderer decodes with the same.

use glam::{Mat3, Vec3};

pub use bumpmap_math::tangent::TangentDecode;

/// The unit tangent-space normal `v` with `normalize(v.x·t + v.y·b + v.z·n) = normal` for the
/// frame `t`, `b`, `n` (unnormalized, not orthogonal), or `None` where the frame is degenerate
/// (its determinant near zero against its vectors' lengths).
///
/// ```
/// use bumpmap_bake::encode_in_frame;
/// use glam::Vec3;
/// let (t, b, n) = (Vec3::new(2.0, 0.0, 0.3), Vec3::new(0.1, 0.8, 0.0), Vec3::new(0.0, 0.2, 1.0));
/// let normal = Vec3::new(0.3, -0.2, 0.9).normalize();
/// let v = encode_in_frame(normal, t, b, n).unwrap();
/// assert!(((v.x * t + v.y * b + v.z * n).normalize() - normal).length() < 1e-5);
/// ```
pub fn encode_in_frame(normal: Vec3, t: Vec3, b: Vec3, n: Vec3) -> Option<Vec3> {
    let frame = Mat3::from_cols(t, b, n);
    let det = frame.determinant();
    let scale = t.length() * b.length() * n.length();
    if !det.is_finite() || det.abs() <= 1e-6 * scale || scale == 0.0 {
        return None;
    }
    let v = frame.inverse() * normal;
    // A hit normal that faces away from N (behind the cage) still encodes; the sign of z says so.
    v.try_normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_encode_inverts_the_decode_for_skewed_frames() {
        let mut worst = 0.0f32;
        for k in 0..200 {
            let f = k as f32;
            let t = Vec3::new(1.0 + (f * 0.37).sin(), 0.3 * (f * 0.11).cos(), 0.2 * (f * 0.7).sin());
            let n = Vec3::new(0.2 * (f * 0.5).cos(), 0.1 * (f * 0.3).sin(), 0.7 + 0.5 * (f * 0.9).cos().abs());
            let b = if k % 2 == 0 { n.cross(t) } else { -n.cross(t) * 0.8 + t * 0.1 };
            let normal = Vec3::new((f * 0.13).sin(), (f * 0.29).cos(), 1.5).normalize();
            let v = encode_in_frame(normal, t, b, n).expect("not degenerate");
            worst = worst.max(((v.x * t + v.y * b + v.z * n).normalize() - normal).length());
            assert!((v.length() - 1.0).abs() < 1e-5);
        }
        assert!(worst < 1e-5, "{worst}");
    }

    #[test]
    fn the_renderers_per_pixel_decode_reads_back_what_the_encode_wrote() {
        // The bake's frame for MikkTSpace's decode (B = sign · N × T of the interpolated
        // vectors), and the renderer's decode of the encoded normal: the normal again.
        let mut worst = 0.0f32;
        for k in 0..400 {
            let f = k as f32;
            let t = Vec3::new(1.0 + 0.8 * (f * 0.37).sin(), 0.4 * (f * 0.11).cos(), 0.3 * (f * 0.7).sin());
            let n = Vec3::new(0.3 * (f * 0.5).cos(), 0.2 * (f * 0.3).sin(), 0.6 + 0.5 * (f * 0.9).cos().abs());
            let sign = if k % 3 == 0 { -1.0 } else { 1.0 };
            let normal = Vec3::new((f * 0.13).sin(), (f * 0.29).cos(), 1.2).normalize();
            let v = encode_in_frame(normal, t, sign * n.cross(t), n).expect("not degenerate");
            let back = bumpmap_math::tangent::decode_per_pixel(v, t, sign, n);
            worst = worst.max((back - normal).length());
        }
        assert!(worst < 1e-5, "{worst}");
    }

    #[test]
    fn an_orthonormal_frame_is_its_transpose_and_a_flat_frame_has_none() {
        let v = encode_in_frame(Vec3::new(0.0, 0.6, 0.8), Vec3::X, Vec3::Y, Vec3::Z).unwrap();
        assert!((v - Vec3::new(0.0, 0.6, 0.8)).length() < 1e-6);
        assert_eq!(encode_in_frame(Vec3::Z, Vec3::X, Vec3::X, Vec3::Z), None, "T and B the same");
        assert_eq!(encode_in_frame(Vec3::Z, Vec3::ZERO, Vec3::Y, Vec3::Z), None);
    }
}
