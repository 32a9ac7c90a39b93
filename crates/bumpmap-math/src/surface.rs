//! Analytic surfaces with exact P, ∂P/∂s, ∂P/∂t and N at any parameter (Cg Tutorial §8.2–8.3,
//! Peercy §2, Figure 4), and their tessellation into meshes with tangent frames.
//!
//! Parameters (u, v) run over [0, 1]²; texture coordinates are `(s, t) = repeat ⊙ (u, v)`, so
//! ∂P/∂s = ∂P/∂u / repeat.s. The frame is `T = normalize(∂P/∂s)`, `B = N × T` (the Cg
//! Tutorial's torus and its errata; DESIGN.md notes the book's misprinted floor binormal), `N`
//! the unit surface normal. The reference renderer evaluates these directly; the rasterizers
//! use the tessellation.

use glam::{Vec2, Vec3, Vec4};
use std::f32::consts::{PI, TAU};

use crate::mesh::Mesh;

/// Position, derivatives and unit normal of a surface at one parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// P.
    pub position: Vec3,
    /// ∂P/∂u with respect to the parameter in [0, 1].
    pub dp_du: Vec3,
    /// ∂P/∂v with respect to the parameter in [0, 1].
    pub dp_dv: Vec3,
    /// The unit normal.
    pub normal: Vec3,
}

impl SurfacePoint {
    /// Tangent-space frame (T, B, N), orthonormal: `T = normalize(∂P/∂u)`, `B = N × T`.
    pub fn frame(&self) -> (Vec3, Vec3, Vec3) {
        let t = (self.dp_du - self.normal * self.normal.dot(self.dp_du)).normalize();
        (t, self.normal.cross(t), self.normal)
    }

    /// The tangent of a texture repeated `repeat` times over the surface (texture coordinates
    /// `repeat ⊙ (u, v)`), as glTF carries it: xyz the unit T along increasing s (turned where
    /// `repeat.x < 0`), w = ±1 the handedness, −1 where exactly one repeat is negative, so that
    /// B = w·(N × T) points along increasing t (for a right-handed parameterization).
    pub fn texture_tangent(&self, repeat: Vec2) -> Vec4 {
        let (t, _, _) = self.frame();
        let w = if repeat.x * repeat.y >= 0.0 { 1.0 } else { -1.0 };
        (if repeat.x >= 0.0 { t } else { -t }).extend(w)
    }

    /// (T, B, N) of [`SurfacePoint::texture_tangent`]: the frame a tangent-space map on this
    /// surface is read in.
    pub fn texture_frame(&self, repeat: Vec2) -> (Vec3, Vec3, Vec3) {
        let tangent = self.texture_tangent(repeat);
        let t = tangent.truncate();
        (t, tangent.w * self.normal.cross(t), self.normal)
    }
}

/// The analytic surfaces the scenes are made of.
#[derive(Clone, Debug, PartialEq)]
pub enum Surface {
    /// The Cg Tutorial's wall: a `width`×`height` rectangle in the x–y plane, N = +z.
    Wall {
        /// Along x.
        width: f32,
        /// Along y.
        height: f32,
    },
    /// The same rectangle lying in the x–z plane, N = +y, s along +x and t along −z.
    Floor {
        /// Along x.
        width: f32,
        /// Along z.
        depth: f32,
    },
    /// Cg Tutorial Eq. 8-3: major radius `major` (hole centre to tube centre), minor `minor`.
    Torus {
        /// Hole centre to tube centre.
        major: f32,
        /// The tube's radius.
        minor: f32,
    },
    /// Longitude u from +x toward +y, latitude v from the south pole (−z) to the north pole.
    Sphere {
        /// Its radius.
        radius: f32,
    },
    /// Peercy Figure 4: a highly stretched bicubic Bézier patch, ∂P/∂u and ∂P/∂v far from
    /// orthogonal and unequal in length.
    Patch(BicubicPatch),
}

impl Surface {
    /// The Cg Tutorial's torus proportions (Figure 8-8) and the peer's: M = 2, N = 0.7.
    pub fn default_torus() -> Self {
        Surface::Torus { major: 2.0, minor: 0.7 }
    }

    /// Evaluates the surface at (u, v) ∈ [0, 1]².
    pub fn eval(&self, u: f32, v: f32) -> SurfacePoint {
        match *self {
            Surface::Wall { width, height } => SurfacePoint {
                position: Vec3::new((u - 0.5) * width, (v - 0.5) * height, 0.0),
                dp_du: Vec3::X * width,
                dp_dv: Vec3::Y * height,
                normal: Vec3::Z,
            },
            Surface::Floor { width, depth } => SurfacePoint {
                position: Vec3::new((u - 0.5) * width, 0.0, (0.5 - v) * depth),
                dp_du: Vec3::X * width,
                dp_dv: Vec3::NEG_Z * depth,
                normal: Vec3::Y,
            },
            Surface::Torus { major, minor } => {
                // Cg Tutorial Eq. 8-3 to 8-6 (C8E6v_torus), with s = 2πu and t = 2πv.
                let (sin_s, cos_s) = (TAU * u).sin_cos();
                let (sin_t, cos_t) = (TAU * v).sin_cos();
                let ring = major + minor * cos_t;
                SurfacePoint {
                    position: Vec3::new(ring * cos_s, ring * sin_s, minor * sin_t),
                    dp_du: TAU * Vec3::new(-sin_s * ring, cos_s * ring, 0.0),
                    dp_dv: TAU * minor * Vec3::new(-sin_t * cos_s, -sin_t * sin_s, cos_t),
                    normal: Vec3::new(cos_s * cos_t, sin_s * cos_t, sin_t),
                }
            }
            Surface::Sphere { radius } => {
                let (sin_p, cos_p) = (TAU * u).sin_cos();
                let (sin_q, cos_q) = (PI * v).sin_cos();
                let normal = Vec3::new(sin_q * cos_p, sin_q * sin_p, -cos_q);
                // At the poles ∂P/∂u vanishes; its direction (−sin φ, cos φ, 0) still holds,
                // so keep a tiny multiple of it for a well-defined frame.
                let du = TAU * radius * sin_q.max(1e-6);
                SurfacePoint {
                    position: radius * normal,
                    dp_du: du * Vec3::new(-sin_p, cos_p, 0.0),
                    dp_dv: PI * radius * Vec3::new(cos_q * cos_p, cos_q * sin_p, sin_q),
                    normal,
                }
            }
            Surface::Patch(ref p) => p.eval(u, v),
        }
    }

    /// The deepest displacement along the normal that keeps a carved surface within the base
    /// surface's bounds: a quarter of a flat rectangle's shorter side, half the torus's tube
    /// radius or the sphere's radius, a quarter of the patch's narrower side (about 0.25).
    pub fn max_depth(&self) -> f32 {
        match self {
            Surface::Wall { width, height } => 0.25 * width.min(*height),
            Surface::Floor { width, depth } => 0.25 * width.min(*depth),
            Surface::Torus { minor, .. } => 0.5 * minor,
            Surface::Sphere { radius } => 0.5 * radius,
            Surface::Patch(_) => {
                let p = self.eval(0.5, 0.5);
                0.25 * p.dp_du.length().min(p.dp_dv.length())
            }
        }
    }

    /// How the surface bends along u and along v at (u, v): `N·∂²P/∂u²` and `N·∂²P/∂v²`
    /// (negative where it curves away from its normal, as a sphere does outward), from central
    /// differences of the first derivatives.
    pub fn normal_curvature(&self, u: f32, v: f32) -> (f32, f32) {
        const E: f32 = 1e-3;
        let p = self.eval(u, v);
        let d_uu = (self.eval(u + E, v).dp_du - self.eval(u - E, v).dp_du) / (2.0 * E);
        let d_vv = (self.eval(u, v + E).dp_dv - self.eval(u, v - E).dp_dv) / (2.0 * E);
        (p.normal.dot(d_uu), p.normal.dot(d_vv))
    }

    /// Tessellates into `nu`×`nv` quads (two triangles each) with texture coordinates
    /// `repeat ⊙ (u, v)` and analytic frames. Closed surfaces repeat their seam vertices so the
    /// texture coordinates can run to `repeat`. Panics if `nu` or `nv` is zero.
    pub fn tessellate(&self, nu: usize, nv: usize, repeat: Vec2) -> Mesh {
        assert!(nu > 0 && nv > 0, "tessellation {nu}x{nv}");
        let mut mesh = Mesh::default();
        for j in 0..=nv {
            for i in 0..=nu {
                let (u, v) = (i as f32 / nu as f32, j as f32 / nv as f32);
                let p = self.eval(u, v);
                mesh.positions.push(p.position);
                mesh.normals.push(p.normal);
                mesh.texcoords.push(repeat * Vec2::new(u, v));
                mesh.tangents.push(p.texture_tangent(repeat));
            }
        }
        let row = nu as u32 + 1;
        for j in 0..nv as u32 {
            for i in 0..nu as u32 {
                let (a, b, c, d) = (j * row + i, j * row + i + 1, (j + 1) * row + i + 1, (j + 1) * row + i);
                mesh.indices.push([a, b, c]);
                mesh.indices.push([a, c, d]);
            }
        }
        mesh
    }
}

/// A bicubic Bézier patch: 4×4 control points, row j along v, column i along u.
#[derive(Clone, Debug, PartialEq)]
pub struct BicubicPatch {
    /// `control[j][i]`: row j along v, column i along u.
    pub control: [[Vec3; 4]; 4],
}

impl BicubicPatch {
    /// Peercy Figure 4's spirit: four units long, one wide, sheared by 60° and gently curved,
    /// so ∂P/∂u and ∂P/∂v differ in length about 4:1 and meet far from 90°.
    pub fn stretched() -> Self {
        let mut control = [[Vec3::ZERO; 4]; 4];
        for (j, row) in control.iter_mut().enumerate() {
            for (i, c) in row.iter_mut().enumerate() {
                let (u, v) = (i as f32 / 3.0, j as f32 / 3.0);
                let bulge = if (1..=2).contains(&i) && (1..=2).contains(&j) { 0.35 } else { 0.0 };
                *c = Vec3::new(4.0 * (u - 0.5) + 0.6 * (v - 0.5), 1.0 * (v - 0.5), bulge - 0.15 * (u - 0.5));
            }
        }
        Self { control }
    }

    fn eval(&self, u: f32, v: f32) -> SurfacePoint {
        let bern = |t: f32| {
            let s = 1.0 - t;
            (
                [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t],
                [-3.0 * s * s, 3.0 * s * (s - 2.0 * t), 3.0 * t * (2.0 * s - t), 3.0 * t * t],
            )
        };
        let ((bu, dbu), (bv, dbv)) = (bern(u), bern(v));
        let (mut p, mut du, mut dv) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
        for j in 0..4 {
            for i in 0..4 {
                let c = self.control[j][i];
                p += bu[i] * bv[j] * c;
                du += dbu[i] * bv[j] * c;
                dv += bu[i] * dbv[j] * c;
            }
        }
        SurfacePoint { position: p, dp_du: du, dp_dv: dv, normal: du.cross(dv).normalize() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn surfaces() -> Vec<Surface> {
        vec![
            Surface::Wall { width: 2.0, height: 1.0 },
            Surface::Floor { width: 2.0, depth: 3.0 },
            Surface::default_torus(),
            Surface::Sphere { radius: 1.5 },
            Surface::Patch(BicubicPatch::stretched()),
        ]
    }

    proptest! {
        #[test]
        fn frames_are_orthonormal_and_match_the_derivatives(u in 0.0f32..1.0, v in 0.0f32..1.0) {
            for s in surfaces() {
                let p = s.eval(u, v);
                let (t, b, n) = p.frame();
                // Unit vectors from f32 sin/cos and one normalize: 1e-5 covers their rounding.
                for (name, x) in [("T", t), ("B", b), ("N", n)] {
                    prop_assert!((x.length() - 1.0).abs() < 1e-5, "{s:?} |{name}| = {}", x.length());
                }
                prop_assert!(t.dot(b).abs() < 1e-5 && t.dot(n).abs() < 1e-5 && b.dot(n).abs() < 1e-5, "{s:?}");
                prop_assert!((b - n.cross(t)).length() < 1e-5, "B = N × T");
                // N is perpendicular to both derivatives, B leans toward ∂P/∂v.
                let scale = p.dp_du.length().max(p.dp_dv.length());
                prop_assert!(n.dot(p.dp_du).abs() < 1e-4 * scale && n.dot(p.dp_dv).abs() < 1e-4 * scale, "{s:?}");
                prop_assert!(b.dot(p.dp_dv) > 0.0, "{s:?}: B must point along increasing t");
            }
        }

        #[test]
        fn derivatives_match_finite_differences(u in 0.05f32..0.95, v in 0.05f32..0.95) {
            for s in surfaces() {
                let h = 1e-3;
                let p = s.eval(u, v);
                let du = (s.eval(u + h, v).position - s.eval(u - h, v).position) / (2.0 * h);
                let dv = (s.eval(u, v + h).position - s.eval(u, v - h).position) / (2.0 * h);
                // Central differences at h = 1e-3 in f32: truncation ~h²·|P'''| plus rounding
                // ~ε·|P|/h ≈ 1e-4·|P|; 2e-2 relative covers the torus's 2π² curvature terms.
                let tol = 2e-2 * (1.0 + p.dp_du.length().max(p.dp_dv.length()));
                prop_assert!((du - p.dp_du).length() < tol, "{s:?} ∂P/∂u {du} vs {}", p.dp_du);
                prop_assert!((dv - p.dp_dv).length() < tol, "{s:?} ∂P/∂v {dv} vs {}", p.dp_dv);
            }
        }
    }

    #[test]
    fn torus_frame_equals_the_cg_tutorial_formulas() {
        // C8E6v_torus: T = normalize(dPds), N = (cosS cosT, sinS cosT, sinT), B = cross(N, T).
        let (m, n) = (2.0f32, 0.7f32);
        let torus = Surface::Torus { major: m, minor: n };
        for (u, v) in [(0.1f32, 0.2f32), (0.37, 0.81), (0.9, 0.55)] {
            let (sin_s, cos_s) = (TAU * u).sin_cos();
            let (sin_t, cos_t) = (TAU * v).sin_cos();
            let dpds = Vec3::new(-sin_s * (m + n * cos_t), cos_s * (m + n * cos_t), 0.0);
            let tangent = dpds.normalize();
            let normal = Vec3::new(cos_s * cos_t, sin_s * cos_t, sin_t);
            let (t, b, nn) = torus.eval(u, v).frame();
            assert!((t - tangent).length() < 1e-6 && (nn - normal).length() < 1e-6);
            assert!((b - normal.cross(tangent)).length() < 1e-6);
        }
    }

    #[test]
    fn curvature_is_zero_on_planes_and_one_over_the_radius_on_a_sphere() {
        let wall = Surface::Wall { width: 4.0, height: 3.0 };
        assert_eq!(wall.normal_curvature(0.3, 0.6), (0.0, 0.0));
        assert_eq!(wall.max_depth(), 0.75);
        // Sphere of radius r: along v (a meridian, |∂P/∂v| = πr) N·P_vv = −(πr)²/r.
        let r = 1.5;
        let (_, kv) = Surface::Sphere { radius: r }.normal_curvature(0.2, 0.4);
        let want = -(std::f32::consts::PI * r).powi(2) / r;
        assert!((kv - want).abs() < 1e-2 * want.abs(), "{kv} vs {want}");
        // The torus's outer equator curves away along u, its inner one toward the normal.
        let torus = Surface::default_torus();
        assert!(torus.normal_curvature(0.1, 0.0).0 < 0.0 && torus.normal_curvature(0.1, 0.5).0 > 0.0);
    }

    #[test]
    fn patch_is_stretched_and_skewed() {
        let p = Surface::Patch(BicubicPatch::stretched()).eval(0.5, 0.5);
        let ratio = p.dp_du.length() / p.dp_dv.length();
        let angle = p.dp_du.angle_between(p.dp_dv).to_degrees();
        assert!(ratio > 3.0, "|Pu|/|Pv| = {ratio}");
        assert!((angle - 90.0).abs() > 15.0, "Pu and Pv meet at {angle}°");
        let mesh = Surface::Patch(BicubicPatch::stretched()).tessellate(8, 8, Vec2::ONE);
        assert_eq!(mesh.triangle_count(), 8 * 8 * 2);
    }
}
