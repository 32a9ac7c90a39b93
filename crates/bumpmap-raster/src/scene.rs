//! What is rendered, independent of how: camera, lights, objects with their meshes and
//! materials, and the vertex stage every technique shares (clip positions and per-vertex
//! tangent-space vectors, Kilgard §5.1, Appendix C).
//!
//! A technique turns a `Scene` into passes; a backend draws them. Nothing here knows about
//! register combiners or framebuffers.

use std::sync::Arc;

use glam::{Mat4, Vec3};

use bumpmap_math::lighting::{Light, ObjectLighting, TangentFrame, Viewer};
use bumpmap_math::mesh::Mesh;

use crate::raster::{MAX_VARYINGS, Vertex};
use crate::texture::Texture2d;

/// Varying slots the vertex stage fills.
pub mod var {
    /// Texture coordinates s, t.
    pub const S: usize = 0;
    pub const T: usize = 1;
    /// Tangent-space unit light vector L (3 slots).
    pub const L: usize = 2;
    /// Tangent-space unit half-angle vector H (3 slots).
    pub const H: usize = 5;
    /// Tangent-space unit vector toward the eye V (3 slots).
    pub const V: usize = 8;
    /// Distance to a positional light (0 for a directional one).
    pub const LIGHT_DISTANCE: usize = 11;
    /// Tangent-space direction of a spotlight's axis (3 slots).
    pub const SPOT: usize = 12;
    /// Projective coordinates (s, t, q) of the spotlight's pattern (3 slots).
    pub const PROJ: usize = 15;
    /// The geometric normal in the lighting space (3 slots): (0, 0, 1) in tangent space, the
    /// surface normal in object space.
    pub const N: usize = 18;
    /// Slots in use.
    pub const COUNT: usize = 21;
}

/// A perspective camera (`gluLookAt` + `gluPerspective`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    pub fov_y_degrees: f32,
    pub near: f32,
    pub far: f32,
}

impl Camera {
    /// `clip_from_world` for an image of the given aspect ratio (width / height).
    pub fn clip_from_world(&self, aspect: f32) -> Mat4 {
        Mat4::perspective_rh_gl(self.fov_y_degrees.to_radians(), aspect, self.near, self.far)
            * Mat4::look_at_rh(self.eye, self.target, self.up)
    }
}

/// Local or infinite viewer for the half-angle vector (Kilgard §6).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ViewerModel {
    #[default]
    Local,
    Infinite,
}

/// A light, its colour, its fall-off with distance and an optional spotlight cone.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneLight {
    pub light: Light,
    pub color: Vec3,
    pub attenuation: Attenuation,
    pub spot: Option<Spot>,
}

impl SceneLight {
    /// A white light with no attenuation and no cone.
    pub fn white(light: Light) -> Self {
        Self { light, color: Vec3::ONE, attenuation: Attenuation::None, spot: None }
    }
}

/// Fall-off with the distance d to a positional light (Kilgard §5.6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Attenuation {
    None,
    /// OpenGL's `1 / (constant + linear·d + quadratic·d²)`.
    Polynomial {
        constant: f32,
        linear: f32,
        quadratic: f32,
    },
    /// The fog-coordinate style `exp(−density·d)`.
    Exponential {
        density: f32,
    },
    /// `exp(−(density·d)²)`.
    ExponentialSquared {
        density: f32,
    },
}

impl Attenuation {
    /// The factor at distance `d`, in [0, 1] for valid parameters.
    #[inline]
    pub fn factor(&self, d: f32) -> f32 {
        match *self {
            Attenuation::None => 1.0,
            Attenuation::Polynomial { constant, linear, quadratic } => {
                (1.0 / (constant + linear * d + quadratic * d * d)).clamp(0.0, 1.0)
            }
            Attenuation::Exponential { density } => (-density * d).exp(),
            Attenuation::ExponentialSquared { density } => (-(density * d).powi(2)).exp(),
        }
    }
}

/// A spotlight: a cone around `direction` (world space, pointing away from the light) with
/// GL's `cos^exponent` fall-off, and optionally a pattern projected from the light (Segal et
/// al., Kilgard §5.6) through a square frustum whose half-angle is the cutoff.
#[derive(Clone, Debug, PartialEq)]
pub struct Spot {
    pub direction: Vec3,
    /// Half-angle of the cone in degrees, in (0, 90).
    pub cutoff_degrees: f32,
    pub exponent: f32,
    pub pattern: Option<Arc<Texture2d>>,
}

impl Spot {
    /// The light's `clip_from_world` for projecting the pattern from `position`.
    pub fn clip_from_world(&self, position: Vec3) -> Mat4 {
        let d = self.direction.normalize();
        let up = if d.cross(Vec3::Z).length() > 1e-3 { Vec3::Z } else { Vec3::Y };
        Mat4::perspective_rh_gl(2.0 * self.cutoff_degrees.to_radians(), 1.0, 0.05, 1000.0)
            * Mat4::look_at_rh(position, position + d, up)
    }
}

/// The space a normal map's vectors live in (Peercy §2, Kilgard §5).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum NormalSpace {
    /// Tangent space: usable on any surface, lit with tangent-space L and H.
    #[default]
    Tangent,
    /// Object space, made for one surface: lit with object-space L and H. The map covers the
    /// surface once; it is addressed with the texture coordinates times `scale`.
    Object { scale: glam::Vec2 },
}

/// Surface appearance: a normal map with its mip chain, an optional decal and the lighting
/// coefficients of Kilgard Eq. 11 and 16.
#[derive(Clone, Debug)]
pub struct Material {
    /// RGB = range-compressed normal (unorm encoding), A = length of the filtered normal.
    pub normal_map: Arc<Texture2d>,
    pub normal_space: NormalSpace,
    pub decal: Option<Arc<Texture2d>>,
    pub ambient: Vec3,
    pub diffuse: Vec3,
    pub specular: Vec3,
    pub shininess: f32,
}

/// A mesh placed in the world. The mesh must have normals, texture coordinates and tangents.
#[derive(Clone, Debug)]
pub struct SceneObject {
    pub mesh: Arc<Mesh>,
    pub world_from_object: Mat4,
    pub material: Material,
}

/// Everything a technique renders.
#[derive(Clone, Debug)]
pub struct Scene {
    pub camera: Camera,
    pub viewer: ViewerModel,
    pub lights: Vec<SceneLight>,
    pub objects: Vec<SceneObject>,
}

impl Scene {
    /// The vertex stage for one object and one light: clip position, texture coordinates and
    /// the tangent-space L, H and V of every vertex.
    pub fn vertices(&self, object: &SceneObject, light: &SceneLight, aspect: f32) -> Vec<Vertex> {
        use rayon::prelude::*;
        let mesh = &object.mesh;
        debug_assert_eq!(mesh.tangents.len(), mesh.positions.len(), "meshes carry tangents");
        let clip_from_object = self.camera.clip_from_world(aspect) * object.world_from_object;
        let viewer = match self.viewer {
            ViewerModel::Local => Viewer::Local(self.camera.eye),
            ViewerModel::Infinite => Viewer::Infinite((self.camera.eye - self.camera.target).normalize_or(Vec3::Z)),
        };
        let lighting = ObjectLighting::new(object.world_from_object, light.light, viewer);
        let object_from_world = object.world_from_object.inverse();
        (0..mesh.positions.len())
            .into_par_iter()
            .map(|i| {
                let p = mesh.positions[i];
                let n = mesh.normals[i];
                let t = mesh.tangents[i];
                let (frame, geometric) = match object.material.normal_space {
                    NormalSpace::Tangent => {
                        (TangentFrame { t: t.truncate(), b: t.w * n.cross(t.truncate()), n }, Vec3::Z)
                    }
                    // Object space: no rotation; the surface normal is what self-shadowing tests.
                    NormalSpace::Object { .. } => (TangentFrame { t: Vec3::X, b: Vec3::Y, n: Vec3::Z }, n),
                };
                let (l, h) = lighting.tangent_space(p, &frame);
                let v = frame.tangent_from_object(lighting.to_eye(p)).normalize_or(Vec3::Z);
                let mut varyings = [0.0; MAX_VARYINGS];
                varyings[var::S] = mesh.texcoords[i].x;
                varyings[var::T] = mesh.texcoords[i].y;
                varyings[var::L..var::L + 3].copy_from_slice(&l.to_array());
                varyings[var::H..var::H + 3].copy_from_slice(&h.to_array());
                varyings[var::V..var::V + 3].copy_from_slice(&v.to_array());
                varyings[var::N..var::N + 3].copy_from_slice(&geometric.to_array());
                varyings[var::LIGHT_DISTANCE] = match light.light {
                    Light::Positional(_) => (object.world_from_object.transform_vector3(lighting.to_light(p))).length(),
                    Light::Directional(_) => 0.0,
                };
                if let (Some(spot), Light::Positional(at)) = (&light.spot, light.light) {
                    let axis = object_from_world.transform_vector3(spot.direction);
                    let axis = frame.tangent_from_object(axis).normalize_or(Vec3::Z);
                    varyings[var::SPOT..var::SPOT + 3].copy_from_slice(&axis.to_array());
                    let c = spot.clip_from_world(at) * (object.world_from_object * p.extend(1.0));
                    varyings[var::PROJ..var::PROJ + 3].copy_from_slice(&[0.5 * (c.x + c.w), 0.5 * (c.y + c.w), c.w]);
                }
                Vertex { clip: clip_from_object * p.extend(1.0), varyings }
            })
            .collect()
    }
}
