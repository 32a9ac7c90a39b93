//! How a tangent-space normal becomes an object-space one: the two decodes a renderer uses,
//! named once ([`TangentDecode`]) for the renderer that decodes and the baker that inverts.
//!
//! Both form `x·T + y·B + z·N` from the interpolated, unnormalized vertex tangent T and normal N;
//! they differ in B. MikkTSpace's (its header's "per pixel" decode) forms B at the fragment,
//! `sign · N × T` of the interpolated vectors, and normalizes the sum. The per-vertex decode
//! interpolates each vertex's own `B = w · N × T` with T and N; this renderer's papers do it
//! without forming the normal at all, by taking L and H into the vertex's frame with dot
//! products, which is the same sum seen from the light's side. What this module does not do:
//! interpolate (the backends do) or invert (the baker's `encode_in_frame`).

use glam::Vec3;

/// How the renderer forms the object-space normal from a tangent-space one (the baker inverts
/// the same decode exactly).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum TangentDecode {
    /// MikkTSpace's per-pixel decode: B = sign · cross(N, T) of the interpolated vectors
    /// ([`decode_per_pixel`]).
    #[default]
    MikkTSpace,
    /// Each vertex's B = w · cross(N, T), interpolated as T and N are: the papers' per-vertex
    /// tangent space.
    PerVertex,
}

crate::named!(TangentDecode {
    MikkTSpace => "mikktspace": "MikkTSpace's per-pixel decode, B = sign·cross(N, T) of the interpolated vectors (Blender, Unity, Unreal, glTF viewers)",
    PerVertex => "per-vertex": "Each vertex's B = w·cross(N, T) interpolated with T and N: the papers' per-vertex tangent space, L and H taken into it at the vertices",
});

/// MikkTSpace's per-pixel decode of the tangent-space normal `v` with the interpolated,
/// unnormalized tangent `t`, handedness `sign` and normal `n`: the direction of
/// `v.x·t + v.y·sign·(n × t) + v.z·n`, at `v`'s length (a filtered normal keeps how much it
/// shortened). Where the sum has no direction, `n`'s (or +Z).
///
/// ```
/// use bumpmap_math::tangent::decode_per_pixel;
/// use glam::Vec3;
/// // An orthonormal frame turns the normal without changing it; a mirrored one flips B.
/// let (t, n) = (Vec3::Y, Vec3::X);
/// let v = Vec3::new(0.0, 0.6, 0.8);
/// assert!((decode_per_pixel(v, t, 1.0, n) - Vec3::new(0.8, 0.0, 0.6)).length() < 1e-6);
/// assert!((decode_per_pixel(v, t, -1.0, n) - Vec3::new(0.8, 0.0, -0.6)).length() < 1e-6);
/// ```
pub fn decode_per_pixel(v: Vec3, t: Vec3, sign: f32, n: Vec3) -> Vec3 {
    let b = sign.signum() * n.cross(t);
    let sum = v.x * t + v.y * b + v.z * n;
    sum.normalize_or(n.normalize_or(Vec3::Z)) * v.length()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_length_is_kept_and_a_skewed_frame_is_not_orthonormalized() {
        let (t, n) = (Vec3::new(2.0, 0.0, 0.5), Vec3::new(0.0, 0.0, 0.5));
        let v = Vec3::new(0.3, 0.0, 0.4);
        let d = decode_per_pixel(v, t, 1.0, n);
        assert!((d.length() - 0.5).abs() < 1e-6);
        // Not what an orthonormal frame gives: T's length weighs x.
        let expected = (0.3 * t + 0.4 * n).normalize() * 0.5;
        assert!((d - expected).length() < 1e-6, "{d} {expected}");
    }

    #[test]
    fn a_degenerate_sum_falls_back_to_the_normal() {
        assert_eq!(decode_per_pixel(Vec3::ZERO, Vec3::X, 1.0, Vec3::Z), Vec3::ZERO);
        let d = decode_per_pixel(Vec3::new(1.0, 0.0, 0.0), Vec3::ZERO, 1.0, Vec3::new(0.0, 2.0, 0.0));
        assert_eq!(d, Vec3::Y);
    }
}
