//! The high-poly mesh as rays see it: its triangles in a BVH (obvhs' eight-wide CWBVH, built by
//! PLOC) and the normal at a hit, HIGH's vertex normals interpolated by the hit's barycentric
//! weights (the face's own normal where a triangle has no usable vertex normals).
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
/// and the build's temporary arrays (an upper bound of what obvhs allocates, rounded up).
pub const BYTES_PER_TRIANGLE: u64 = 160;

/// HIGH, ready to be hit.
pub struct HighPoly<'a> {
    mesh: &'a Mesh,
    triangles: Vec<Triangle>,
    bvh: CwBvh,
}

/// Where a ray met HIGH.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// Distance along the ray from its origin.
    pub t: f32,
    /// HIGH's unit normal there.
    pub normal: Vec3,
}

impl<'a> HighPoly<'a> {
    /// The BVH over `mesh`'s triangles (which must be valid and carry normals).
    pub fn new(mesh: &'a Mesh) -> Self {
        let triangles: Vec<Triangle> = mesh
            .indices
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| Vec3A::from(mesh.positions[i as usize]));
                Triangle { v0: a, v1: b, v2: c }
            })
            .collect();
        let bvh = build_cwbvh_from_tris(&triangles, BvhBuildParams::medium_build(), &mut Duration::default());
        HighPoly { mesh, triangles, bvh }
    }

    /// The first hit along `origin + t·direction` for `t` in `[0, reach]`.
    pub fn first_hit(&self, origin: Vec3, direction: Vec3, reach: f32) -> Option<Hit> {
        // −0.0 becomes +0.0: the wide BVH picks a ray's octant from its direction's sign bits, and
        // a negated axis-aligned direction (−0, −0, −1) otherwise misses every node.
        let direction = direction + Vec3::ZERO;
        let ray = Ray::new(origin.into(), direction.into(), 0.0, reach);
        let mut hit = RayHit::none();
        let found = self.bvh.ray_traverse(ray, &mut hit, |ray, id| {
            self.triangles[self.bvh.primitive_indices[id] as usize].intersect(ray)
        });
        if !found {
            return None;
        }
        let index = self.bvh.primitive_indices[hit.primitive_id as usize] as usize;
        Some(Hit { t: hit.t, normal: self.normal_at(index, origin + direction * hit.t) })
    }

    /// Whether the ray `origin + t·direction`, `t` in `[near, far]`, meets HIGH anywhere.
    pub fn blocked(&self, origin: Vec3, direction: Vec3, near: f32, far: f32) -> bool {
        let direction = direction + Vec3::ZERO;
        let ray = Ray::new(origin.into(), direction.into(), near, far);
        !self
            .bvh
            .ray_traverse_miss(ray, |ray, id| self.triangles[self.bvh.primitive_indices[id] as usize].intersect(ray))
    }

    /// HIGH's normal on triangle `index` at `p`: its vertex normals interpolated.
    fn normal_at(&self, index: usize, p: Vec3) -> Vec3 {
        let [i0, i1, i2] = self.mesh.indices[index].map(|i| i as usize);
        let [a, b, c] = [i0, i1, i2].map(|i| self.mesh.positions[i]);
        let face = (b - a).cross(c - a);
        let area = face.length_squared();
        if area == 0.0 {
            return Vec3::Z;
        }
        // Barycentric weights from sub-triangle areas, measured along the face normal.
        let w1 = (p - a).cross(c - a).dot(face) / area;
        let w2 = (b - a).cross(p - a).dot(face) / area;
        let w0 = 1.0 - w1 - w2;
        let n = &self.mesh.normals;
        let smooth = n[i0] * w0 + n[i1] * w1 + n[i2] * w2;
        smooth.try_normalize().unwrap_or_else(|| face.normalize())
    }
}
