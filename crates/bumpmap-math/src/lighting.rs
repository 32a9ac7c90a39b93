//! Per-vertex tangent-space light and half-angle vectors (Kilgard §5.1, Appendix C; Cg Tutorial
//! §8.2–8.3), and the lighting equations they feed (Kilgard Eq. 11, 12, 16).
//!
//! Lights and the eye are given in world space; a vertex's frame and position are in object
//! space, so both are first brought into object space with `object_from_world`. The vectors are
//! returned normalized, as Appendix C stores them; a light exactly on a vertex or a half-angle
//! that vanishes falls back to the surface normal rather than producing NaN.

use glam::{Mat4, Vec3};

/// Where light comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A point light at a world-space position.
    Positional(Vec3),
    /// A light at infinity; the vector points from the surface toward the light.
    Directional(Vec3),
}

/// Where the viewer is, for the half-angle vector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Viewer {
    /// An eye at a world-space position (a local viewer).
    Local(Vec3),
    /// An infinite viewer; the vector points from the surface toward the eye.
    Infinite(Vec3),
}

/// An orthonormal tangent frame in object space: T along increasing s, B along increasing t.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentFrame {
    /// The tangent T.
    pub t: Vec3,
    /// The binormal B.
    pub b: Vec3,
    /// The normal N.
    pub n: Vec3,
}

impl TangentFrame {
    /// Rotates an object-space vector into tangent space: `(v·T, v·B, v·N)` (Appendix C).
    #[inline]
    pub fn tangent_from_object(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.t), v.dot(self.b), v.dot(self.n))
    }

    /// The inverse rotation (the frame is orthonormal, so it is the transpose).
    #[inline]
    pub fn object_from_tangent(&self, v: Vec3) -> Vec3 {
        self.t * v.x + self.b * v.y + self.n * v.z
    }
}

/// The light and viewer of a scene expressed in one object's space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectLighting {
    light: Light,
    viewer: Viewer,
}

impl ObjectLighting {
    /// Brings a world-space light and viewer into the object space of `world_from_object`.
    /// Preconditions: `world_from_object` is invertible (a rigid or scaled transform).
    pub fn new(world_from_object: Mat4, light: Light, viewer: Viewer) -> Self {
        let object_from_world = world_from_object.inverse();
        let light = match light {
            Light::Positional(p) => Light::Positional(object_from_world.transform_point3(p)),
            Light::Directional(d) => Light::Directional(object_from_world.transform_vector3(d)),
        };
        let viewer = match viewer {
            Viewer::Local(p) => Viewer::Local(object_from_world.transform_point3(p)),
            Viewer::Infinite(d) => Viewer::Infinite(object_from_world.transform_vector3(d)),
        };
        Self { light, viewer }
    }

    /// Unnormalized object-space vector from `position` toward the light.
    #[inline]
    pub fn to_light(&self, position: Vec3) -> Vec3 {
        match self.light {
            Light::Positional(p) => p - position,
            Light::Directional(d) => d,
        }
    }

    /// Unnormalized object-space vector from `position` toward the eye.
    #[inline]
    pub fn to_eye(&self, position: Vec3) -> Vec3 {
        match self.viewer {
            Viewer::Local(p) => p - position,
            Viewer::Infinite(d) => d,
        }
    }

    /// Appendix C for one vertex: normalized tangent-space L and H = normalize(L̂ + V̂).
    pub fn tangent_space(&self, position: Vec3, frame: &TangentFrame) -> (Vec3, Vec3) {
        let l = frame.tangent_from_object(self.to_light(position)).normalize_or(Vec3::Z);
        let v = frame.tangent_from_object(self.to_eye(position)).normalize_or(Vec3::Z);
        (l, (l + v).normalize_or(Vec3::Z))
    }

    /// The object-space variant (Peercy §2.1, Kilgard §5): L and H not rotated into a frame, for
    /// object-space normal maps.
    pub fn object_space(&self, position: Vec3) -> (Vec3, Vec3) {
        let identity = TangentFrame { t: Vec3::X, b: Vec3::Y, n: Vec3::Z };
        self.tangent_space(position, &identity)
    }
}

/// Kilgard Eq. 12: the self-shadowing term, a steep ramp of L_z = L·N.
#[inline]
pub fn s_self(l_z: f32) -> f32 {
    (8.0 * l_z).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_positions_give_no_nan() {
        let frame = TangentFrame { t: Vec3::X, b: Vec3::Y, n: Vec3::Z };
        let p = Vec3::new(1.0, 2.0, 3.0);
        // Light exactly on the vertex; eye = light; eye opposite the light.
        for (light, eye) in [
            (p, Vec3::new(0.0, 0.0, 9.0)),
            (Vec3::new(0.0, 0.0, 9.0), Vec3::new(0.0, 0.0, 9.0)),
            (p + Vec3::Z, p - Vec3::Z),
        ] {
            let lit = ObjectLighting::new(Mat4::IDENTITY, Light::Positional(light), Viewer::Local(eye));
            let (l, h) = lit.tangent_space(p, &frame);
            assert!(l.is_finite() && h.is_finite(), "{light} {eye}: {l} {h}");
            assert!((l.length() - 1.0).abs() < 1e-6 && (h.length() - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn model_transform_moves_the_light_into_object_space() {
        // Object rotated 90° about z: a world light on +y sits on +x in object space.
        let world_from_object = Mat4::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let lit = ObjectLighting::new(world_from_object, Light::Directional(Vec3::Y), Viewer::Infinite(Vec3::Y));
        let frame = TangentFrame { t: Vec3::X, b: Vec3::Y, n: Vec3::Z };
        let (l, h) = lit.tangent_space(Vec3::ZERO, &frame);
        assert!((l - Vec3::X).length() < 1e-6 && (h - Vec3::X).length() < 1e-6, "{l} {h}");
        assert_eq!(s_self(0.05), 0.4);
        assert_eq!(s_self(-0.2), 0.0);
    }
}
