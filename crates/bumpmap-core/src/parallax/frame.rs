//! How texture space (s, t, h) sits in a vertex's tangent frame: the map between the two
//! that the marches and the lighting need. What this module does not do: march.

use glam::{Vec2, Vec3};

use bumpmap_math::lighting::TangentFrame;

/// How texture space sits in a vertex's tangent frame (T, B, N): `∂(x, y)/∂(s, t)` in the
/// tangent plane (`[a, b, c, d]` = `[P_s·T, P_t·T, P_s·B, P_t·B]`, P_s = ∂P/∂s) and the depth
/// along N of one unit of height.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureFrame {
    /// `[P_s·T, P_t·T, P_s·B, P_t·B]`.
    pub jacobian: [f32; 4],
    /// Object units per unit of height.
    pub depth: f32,
}

impl TextureFrame {
    /// The frame of surface derivatives `p_s`, `p_t` (object space, per unit of s and t) at a
    /// vertex whose tangent frame is `frame`.
    pub fn new(p_s: Vec3, p_t: Vec3, frame: &TangentFrame, depth: f32) -> Self {
        Self { jacobian: [p_s.dot(frame.t), p_t.dot(frame.t), p_s.dot(frame.b), p_t.dot(frame.b)], depth }
    }

    /// A tangent-frame vector in texture space: `(J⁻¹ (x, y), z / depth)`; (0, 0, z/depth)
    /// where J is singular.
    #[inline]
    pub fn to_texture(&self, v: Vec3) -> Vec3 {
        let [a, b, c, d] = self.jacobian;
        let inv = self.inverse_determinant();
        Vec3::new((d * v.x - b * v.y) * inv, (a * v.y - c * v.x) * inv, v.z / self.depth)
    }

    /// 1 / det J, or 0 where J is singular (the inverses then map everything to 0).
    #[inline]
    fn inverse_determinant(&self) -> f32 {
        let [a, b, c, d] = self.jacobian;
        let det = a * d - b * c;
        if det != 0.0 && det.is_finite() { 1.0 / det } else { 0.0 }
    }

    /// A texture-space vector in the tangent frame: `(J (s, t), h · depth)`.
    #[inline]
    pub fn to_tangent(&self, v: Vec3) -> Vec3 {
        let [a, b, c, d] = self.jacobian;
        Vec3::new(a * v.x + b * v.y, c * v.x + d * v.y, v.z * self.depth)
    }

    /// The unit normal, in the tangent frame, of heights with gradient `g` = (∂h/∂s, ∂h/∂t):
    /// `(−depth · J⁻ᵀ g, 1)` normalized, turned to face +z whichever way J turns.
    #[inline]
    pub fn normal(&self, g: Vec2) -> Vec3 {
        let [a, b, c, d] = self.jacobian;
        let inv = self.inverse_determinant();
        let n = Vec3::new(-(d * g.x - c * g.y) * inv * self.depth, -(a * g.y - b * g.x) * inv * self.depth, 1.0);
        n.normalize_or(Vec3::Z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_texture_frame_round_trips_and_its_normal_tilts_downhill() {
        let frame = TextureFrame { jacobian: [0.5, 0.1, 0.0, 0.25], depth: 0.03 };
        let v = Vec3::new(0.3, -0.7, 0.2);
        assert!((frame.to_tangent(frame.to_texture(v)) - v).length() < 1e-6);
        // Heights rising along +s: the normal leans toward −T.
        let n = frame.normal(Vec2::new(2.0, 0.0));
        assert!(n.x < 0.0 && n.z > 0.0 && (n.length() - 1.0).abs() < 1e-6, "{n}");
        // On an unskewed frame the normal is (−depth·g/|P_s|, −depth·g/|P_t|, 1).
        let square = TextureFrame { jacobian: [0.5, 0.0, 0.0, 0.25], depth: 0.03 };
        let want = Vec3::new(-0.03 * 2.0 / 0.5, -0.03 * 1.0 / 0.25, 1.0).normalize();
        assert!((square.normal(Vec2::new(2.0, 1.0)) - want).length() < 1e-6);
    }
}
