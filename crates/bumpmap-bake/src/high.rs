//! The high-poly mesh as rays see it: its triangles in a BVH (obvhs' eight-wide CWBVH, built by
//! PLOC) and the normal at a hit, HIGH's vertex normals interpolated by the hit's barycentric
//! weights (the face's own normal where a triangle has no usable vertex normals), and HIGH's
//! mean curvature there, interpolated the same way.
//!
//! What this module does not do: decide where rays start or which hit counts (the baker does:
//! the first from the cage inward, which is the closest to the ray's origin).

use std::time::Duration;

use bumpmap_math::mesh::Mesh;
use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;

/// Bytes a triangle of HIGH costs while baking: the BVH's nodes and indices, its triangle copy
/// and the build's temporary arrays (an upper bound of what obvhs allocates, rounded up), and
/// the curvature's per-vertex arrays (a mesh has about half as many vertices as triangles).
pub const BYTES_PER_TRIANGLE: u64 = 176;

/// HIGH, or some of its triangles, ready to be hit.
pub struct HighPoly<'a> {
    mesh: &'a Mesh,
    /// The mesh's triangle each of the BVH's primitives is.
    ids: Vec<u32>,
    /// The triangles in the BVH's primitive order, so a leaf's index reads its triangle
    /// without going through the BVH's index list.
    triangles: Vec<Triangle>,
    bvh: CwBvh,
    /// Each vertex's mean curvature (empty: not asked for, 0 at every hit).
    curvature: &'a [f32],
}

/// Where a ray met HIGH.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// Distance along the ray from its origin.
    pub t: f32,
    /// HIGH's unit normal there.
    pub normal: Vec3,
    /// HIGH's mean curvature there (1 / the mesh's units, positive where convex).
    pub curvature: f32,
}

impl<'a> HighPoly<'a> {
    /// The BVH over `mesh`'s triangles (which must be valid and carry normals), or over those
    /// of `only` (indices into [`Mesh::indices`], not empty); `curvature` holds each vertex's.
    pub fn new(mesh: &'a Mesh, curvature: &'a [f32], only: Option<&[u32]>) -> Self {
        let triangle = |k: u32| {
            let [a, b, c] = mesh.indices[k as usize].map(|i| Vec3A::from(mesh.positions[i as usize]));
            Triangle { v0: a, v1: b, v2: c }
        };
        let ids: Vec<u32> = match only {
            Some(ids) => ids.to_vec(),
            None => (0..mesh.indices.len() as u32).collect(),
        };
        let triangles: Vec<Triangle> = ids.iter().map(|&k| triangle(k)).collect();
        let bvh = build_cwbvh_from_tris(&triangles, BvhBuildParams::medium_build(), &mut Duration::default());
        let ids: Vec<u32> = bvh.primitive_indices.iter().map(|&p| ids[p as usize]).collect();
        let triangles = bvh.primitive_indices.iter().map(|&p| triangles[p as usize]).collect();
        HighPoly { mesh, ids, triangles, bvh, curvature }
    }

    /// The first hit along `origin + t·direction` for `t` in `[0, reach]`.
    pub fn first_hit(&self, origin: Vec3, direction: Vec3, reach: f32) -> Option<Hit> {
        // −0.0 becomes +0.0: the wide BVH picks a ray's octant from its direction's sign bits, and
        // a negated axis-aligned direction (−0, −0, −1) otherwise misses every node.
        let direction = direction + Vec3::ZERO;
        let ray = Ray::new(origin.into(), direction.into(), 0.0, reach);
        let mut hit = RayHit::none();
        let found = self.bvh.ray_traverse(ray, &mut hit, |ray, id| self.triangles[id].intersect(ray));
        if !found {
            return None;
        }
        let ids = self.mesh.indices[self.ids[hit.primitive_id as usize] as usize].map(|i| i as usize);
        let Some((w, face)) = self.weights(ids, origin + direction * hit.t) else {
            return Some(Hit { t: hit.t, normal: Vec3::Z, curvature: 0.0 });
        };
        let n = &self.mesh.normals;
        let smooth = n[ids[0]] * w[0] + n[ids[1]] * w[1] + n[ids[2]] * w[2];
        let curvature = match self.curvature.is_empty() {
            true => 0.0,
            false => ids.iter().zip(w).map(|(&i, w)| self.curvature[i] * w).sum(),
        };
        Some(Hit { t: hit.t, normal: smooth.try_normalize().unwrap_or(face), curvature })
    }

    /// Whether the ray `origin + t·direction`, `t` in `[near, far]`, meets HIGH anywhere.
    pub fn blocked(&self, origin: Vec3, direction: Vec3, near: f32, far: f32) -> bool {
        let direction = direction + Vec3::ZERO;
        let ray = Ray::new(origin.into(), direction.into(), near, far);
        !self.bvh.ray_traverse_miss(ray, |ray, id| self.triangles[id].intersect(ray))
    }

    /// The barycentric weights of `p` on the triangle of vertices `ids`, and its unit face
    /// normal (`None` for a triangle of no area).
    fn weights(&self, ids: [usize; 3], p: Vec3) -> Option<([f32; 3], Vec3)> {
        let [a, b, c] = ids.map(|i| self.mesh.positions[i]);
        let face = (b - a).cross(c - a);
        let area = face.length_squared();
        if area == 0.0 {
            return None;
        }
        // From sub-triangle areas, measured along the face normal.
        let w1 = (p - a).cross(c - a).dot(face) / area;
        let w2 = (b - a).cross(p - a).dot(face) / area;
        Some(([1.0 - w1 - w2, w1, w2], face.normalize()))
    }
}
