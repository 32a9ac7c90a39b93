//! The vertex stage every technique shares: clip positions and the per-vertex tangent-space
//! vectors (Kilgard §5.1, Appendix C), as a flat array of varyings per vertex.
//!
//! The slots are fixed ([`var`]) so a backend can interpolate only the prefix a pass reads.
//! Clipping, the perspective divide and interpolation are the backends' work, not this
//! module's.

use glam::{Vec2, Vec3, Vec4};

use bumpmap_math::buffer::OutOfMemory;
use bumpmap_math::lighting::{Light, ObjectLighting, TangentFrame, Viewer};

use crate::error::CoreError;
use crate::parallax::TextureFrame;
use crate::scene::{NormalSpace, Scene, SceneLight, SceneObject, ViewerModel};

/// Varying slots the vertex stage fills.
pub mod var {
    /// Texture coordinate s.
    pub const S: usize = 0;
    /// Texture coordinate t.
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
    /// Embossing's shifted texture coordinates (2 slots): (s, t) moved toward the light by
    /// `(L_x, L_y)` texels of the height map (Kilgard Eq. 29–30), the shift forced to 0 where
    /// `L_z ≤ 0` as §3.1 says it must be.
    pub const EMBOSS: usize = 21;
    /// The same shift never forced to 0: what embossing does when nobody tests `L_z`.
    pub const EMBOSS_UNFORCED: usize = 23;
    /// The surface's derivatives in the tangent frame (3 slots): `|∂P/∂u|`, `∂P/∂v · T`,
    /// `∂P/∂v · B`, for Peercy Figure 2's per-pixel Blinn (objects with an exact surface only).
    pub const PARAM_FRAME: usize = 25;
    /// Heights as geometry (materials with heights only, `crate::parallax`): the vector toward
    /// the eye in texture space (s, t, h), unnormalized (3 slots). Affine in the position on
    /// a flat surface, so interpolation keeps it exact there.
    pub const TEX_VIEW: usize = 28;
    /// The vector toward the light (or its direction) in texture space (3 slots).
    pub const TEX_LIGHT: usize = 31;
    /// `∂(x, y)/∂(s, t)` in the tangent plane, `[P_s·T, P_t·T, P_s·B, P_t·B]` (4 slots).
    pub const TANGENT_FROM_TEX: usize = 34;
    /// How far the surface falls below its tangent plane, in heights per unit of s² and t²
    /// (2 slots): `−½ N·∂²P/∂s² / depth`, likewise for t; zero on flat surfaces, a fitted
    /// quadric's on meshes (`bumpmap_math::mesh::Mesh::st_normal_curvature`).
    pub const CURVATURE: usize = 38;
    /// The vertex colour, linear RGBA (4 slots): what multiplies the base colour, for meshes
    /// with colours only (glTF `COLOR_0`); a pass reads it where its program says so.
    pub const COLOR: usize = 40;
    /// The object-space vertex tangent and its handedness w (4 slots), for a tangent-space map
    /// decoded per pixel ([`crate::scene::NormalSpace::TangentPerPixel`], which puts the normal in
    /// [`N`]).
    pub const TANGENT: usize = 44;
    /// Slots in use.
    pub const COUNT: usize = 48;
}

/// Varyings per vertex (texture coordinates, light and half-angle vectors, …): twelve vec4s.
pub const MAX_VARYINGS: usize = 48;

/// A vertex after the vertex stage: clip-space position and its varyings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    /// `clip_from_object · position`.
    pub clip: Vec4,
    /// The slots of [`var`]; the rest are zero.
    pub varyings: [f32; MAX_VARYINGS],
}

/// Vertex `i`'s texture-space varyings ([`var::TEX_VIEW`] to [`var::CURVATURE`]) from the
/// vectors toward the eye and the light (object space) and its tangent frame.
fn texture_space(
    object: &SceneObject,
    i: usize,
    frame: &TangentFrame,
    to_eye: Vec3,
    to_light: Vec3,
    varyings: &mut [f32; MAX_VARYINGS],
) {
    let depth = object.material.depth;
    let (p_s, p_t, curvature) = match (&object.source, &object.st_derivatives) {
        (Some(source), _) => {
            let st = object.mesh.texcoords[i];
            let (u, v) = (st.x / source.repeat.x, st.y / source.repeat.y);
            let p = source.surface.eval(u, v);
            let (k_u, k_v) = source.surface.normal_curvature(u, v);
            let r = source.repeat;
            // Per unit of s = repeat.x · u: ∂P/∂s = ∂P/∂u / repeat.x, ∂²P/∂s² = ∂²P/∂u² / repeat.x².
            let fall = Vec2::new(-0.5 * k_u / (r.x * r.x), -0.5 * k_v / (r.y * r.y)) / depth;
            (p.dp_du / r.x, p.dp_dv / r.y, fall)
        }
        (None, Some(d)) => {
            // As for a surface: −½ N·∂²P/∂s² per unit of height (the mesh's fitted quadric).
            (d.first[i][0], d.first[i][1], -0.5 * d.second[i] / depth)
        }
        // Not built by `scenes::build` (which gives meshes their derivatives): unit texels.
        (None, None) => (frame.t, frame.b, Vec2::ZERO),
    };
    let tex = TextureFrame::new(p_s, p_t, frame, depth);
    let to_eye = tex.to_texture(frame.tangent_from_object(to_eye));
    let to_light = tex.to_texture(frame.tangent_from_object(to_light));
    varyings[var::TEX_VIEW..var::TEX_VIEW + 3].copy_from_slice(&to_eye.to_array());
    varyings[var::TEX_LIGHT..var::TEX_LIGHT + 3].copy_from_slice(&to_light.to_array());
    varyings[var::TANGENT_FROM_TEX..var::TANGENT_FROM_TEX + 4].copy_from_slice(&tex.jacobian);
    varyings[var::CURVATURE..var::CURVATURE + 2].copy_from_slice(&curvature.to_array());
}

impl Scene {
    /// The viewer of the half-angle vector: the eye, or the direction toward it.
    pub fn viewer(&self) -> Viewer {
        match self.viewer {
            ViewerModel::Local => Viewer::Local(self.camera.eye),
            ViewerModel::Infinite => Viewer::Infinite((self.camera.eye - self.camera.target).normalize_or(Vec3::Z)),
        }
    }

    /// The vertex stage for one object and one light: clip position, texture coordinates and
    /// the tangent-space L, H and V of every vertex. Fails, rather than aborting, when the
    /// machine cannot hold the outputs (192 bytes a vertex).
    pub fn vertices(&self, object: &SceneObject, light: &SceneLight, aspect: f32) -> Result<Vec<Vertex>, CoreError> {
        use rayon::prelude::*;
        let mesh = &object.mesh;
        let mut out = Vec::new();
        out.try_reserve_exact(mesh.positions.len())
            .map_err(|_| OutOfMemory::of::<Vertex>("the vertex stage's output", mesh.positions.len()))?;
        debug_assert_eq!(mesh.tangents.len(), mesh.positions.len(), "meshes carry tangents");
        let clip_from_object = self.camera.clip_from_world(aspect) * object.world_from_object;
        let lighting = ObjectLighting::new(object.world_from_object, light.light, self.viewer());
        let object_from_world = object.world_from_object.inverse();
        // The eye the rays through the heights come from: the camera's, whatever the viewer model.
        let eye = object_from_world.transform_point3(self.camera.eye);
        out.par_extend((0..mesh.positions.len()).into_par_iter().map(|i| {
            let p = mesh.positions[i];
            let n = mesh.normals[i];
            let t = mesh.tangents[i];
            let (frame, geometric) = match object.material.normal_space {
                NormalSpace::Tangent | NormalSpace::SurfaceTangent { .. } => {
                    (TangentFrame { t: t.truncate(), b: t.w * n.cross(t.truncate()), n }, Vec3::Z)
                }
                // Object space: no rotation; the surface normal is what self-shadowing tests (and,
                // decoded per pixel, what the frame is made of with the tangent).
                NormalSpace::Object { .. } | NormalSpace::TangentPerPixel => {
                    (TangentFrame { t: Vec3::X, b: Vec3::Y, n: Vec3::Z }, n)
                }
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
            if object.material.normal_space == NormalSpace::TangentPerPixel {
                varyings[var::TANGENT..var::TANGENT + 4].copy_from_slice(&t.to_array());
            }
            if let (Some(source), NormalSpace::Tangent) = (&object.source, object.material.normal_space) {
                let st = mesh.texcoords[i];
                let sp = source.surface.eval(st.x / source.repeat.x, st.y / source.repeat.y);
                let frame = [sp.dp_du.length(), sp.dp_dv.dot(frame.t), sp.dp_dv.dot(frame.b)];
                varyings[var::PARAM_FRAME..var::PARAM_FRAME + 3].copy_from_slice(&frame);
            }
            if object.material.heights.is_some() {
                texture_space(object, i, &frame, eye - p, lighting.to_light(p), &mut varyings);
            }
            if let Some(heights) = &object.material.height_map {
                // One texel of the height map's level 0 per unit of L_x, L_y.
                let shift = glam::Vec2::new(l.x / heights.width() as f32, l.y / heights.height() as f32);
                let st = mesh.texcoords[i];
                let forced = if l.z > 0.0 { st + shift } else { st };
                varyings[var::EMBOSS..var::EMBOSS + 2].copy_from_slice(&forced.to_array());
                varyings[var::EMBOSS_UNFORCED..var::EMBOSS_UNFORCED + 2].copy_from_slice(&(st + shift).to_array());
            }
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
            if let Some(color) = mesh.colors.get(i) {
                varyings[var::COLOR..var::COLOR + 4].copy_from_slice(&color.to_array());
            }
            Vertex { clip: clip_from_object * p.extend(1.0), varyings }
        }));
        Ok(out)
    }
}
