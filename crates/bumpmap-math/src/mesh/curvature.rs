//! A mesh's mean curvature at each vertex (the baker's curvature map, a mesh's silhouettes):
//! the cotangent Laplacian over
//! the vertex's mixed (Voronoi) area, Meyer, Desbrun, Schröder & Barr 2003, *Discrete
//! differential-geometry operators for triangulated 2-manifolds*: `K = Σ (cot α + cot β)(pᵢ −
//! pⱼ) / 2A = 2H·n`, `H` read along the vertex's normal. Vertices at one position are one
//! vertex (their triangles pooled, their normals averaged), so a hard edge reads as the bend
//! it is, not as two flat faces. Positive where the surface bends away from its normal
//! (convex, a sphere seen from outside), negative in creases, in 1 / the mesh's units.
//!
//! What this module does not do: the principal curvatures or their directions (only their
//! mean), or smooth the estimate over a neighbourhood (a noisy scan reads noisy).

use std::collections::HashMap;

use super::Mesh;
use glam::Vec3;

impl Mesh {
    /// Each vertex's mean curvature (the same for every vertex at one position), in 1 / the
    /// mesh's units, positive where convex; the mesh must be valid and carry normals.
    ///
    /// ```
    /// use bumpmap_math::surface::Surface;
    /// let sphere = Surface::Sphere { radius: 2.0 }.tessellate(24, 12, glam::Vec2::ONE);
    /// let k = sphere.mean_curvature();
    /// // Away from the seam and the poles (whose copies lie a rounding error apart): 1/r.
    /// assert!((k[6 * 25 + 10] - 0.5).abs() < 0.01);
    /// ```
    pub fn mean_curvature(&self) -> Vec<f32> {
        vertex_curvature(self)
    }
}

/// Each vertex's mean curvature (the same for every vertex at one position); `mesh` carries
/// normals.
fn vertex_curvature(mesh: &Mesh) -> Vec<f32> {
    // One slot a position, so split vertices pool their triangles.
    let mut slot_of: HashMap<[u32; 3], u32> = HashMap::with_capacity(mesh.positions.len());
    let slots: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            let next = slot_of.len() as u32;
            *slot_of.entry(p.to_array().map(f32::to_bits)).or_insert(next)
        })
        .collect();
    let mut normals = vec![Vec3::ZERO; slot_of.len()];
    for (n, &s) in mesh.normals.iter().zip(&slots) {
        normals[s as usize] += *n;
    }
    // The Laplace–Beltrami operator's sum and each position's mixed area.
    let (mut laplacian, mut areas) = (vec![Vec3::ZERO; slot_of.len()], vec![0.0f32; slot_of.len()]);
    for t in &mesh.indices {
        let ids = t.map(|i| slots[i as usize] as usize);
        let p = t.map(|i| mesh.positions[i as usize]);
        let twice_area = (p[1] - p[0]).cross(p[2] - p[0]).length();
        // A triangle of no area (a pole's, a rounding error wide) bends nothing.
        if twice_area == 0.0 {
            continue;
        }
        // The cotangent of the angle at each corner.
        let cot: [f32; 3] = std::array::from_fn(|k| {
            let (a, b) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            a.dot(b) / twice_area
        });
        let obtuse = (0..3).find(|&k| cot[k] < 0.0);
        for k in 0..3 {
            let (i, j, o) = (k, (k + 1) % 3, (k + 2) % 3);
            // Edge i–j, opposite corner o.
            let d = p[i] - p[j];
            laplacian[ids[i]] += cot[o] * d;
            laplacian[ids[j]] -= cot[o] * d;
            areas[ids[k]] += match obtuse {
                // Voronoi area: the corner's share of its two edges.
                None => (d.length_squared() * cot[o] + (p[k] - p[o]).length_squared() * cot[j]) / 8.0,
                Some(c) if c == k => twice_area / 4.0,
                Some(_) => twice_area / 8.0,
            };
        }
    }
    slots
        .iter()
        .map(|&s| {
            let (s, n) = (s as usize, normals[s as usize].normalize_or_zero());
            // K = Σ (cot α + cot β)(pᵢ − pⱼ) / 2A = 2H·n.
            if areas[s] > 0.0 { laplacian[s].dot(n) / (4.0 * areas[s]) } else { 0.0 }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::*;
    use crate::surface::Surface;

    #[test]
    fn a_sphere_bends_by_its_inverse_radius_and_a_plane_not_at_all() {
        let mut sphere = Surface::Sphere { radius: 2.0 }.tessellate(24, 12, Vec2::ONE);
        // Its seam and poles as one point each, as a modelled sphere has them (the analytic
        // ones land a rounding error apart, and positions are matched exactly).
        for j in 0..=12 {
            sphere.positions[j * 25 + 24] = sphere.positions[j * 25];
        }
        for i in 0..25 {
            sphere.positions[12 * 25 + i] = glam::Vec3::Z * 2.0;
        }
        let k = vertex_curvature(&sphere);
        assert!(
            k.iter().all(|k| (k - 0.5).abs() < 0.02),
            "{:?}",
            k.iter().fold((f32::MAX, f32::MIN), |(l, h), k| (l.min(*k), h.max(*k)))
        );
        let wall = Surface::Wall { width: 1.0, height: 1.0 }.tessellate(4, 4, Vec2::ONE);
        assert!(vertex_curvature(&wall).iter().all(|k| k.abs() < 1e-6));
        // Inside out, it is a hollow: negative.
        let mut hollow = sphere.clone();
        hollow.indices.iter_mut().for_each(|t| t.swap(1, 2));
        hollow.normals.iter_mut().for_each(|n| *n = -*n);
        assert!(vertex_curvature(&hollow).iter().all(|k| (k + 0.5).abs() < 0.02));
    }
}
