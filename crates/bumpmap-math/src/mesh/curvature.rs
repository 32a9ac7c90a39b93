//! A mesh's mean curvature at each vertex (the baker's curvature map, a mesh's silhouettes):
//! the cotangent Laplacian over
//! the vertex's mixed (Voronoi) area, Meyer, Desbrun, Schröder & Barr 2003, *Discrete
//! differential-geometry operators for triangulated 2-manifolds*: `K = Σ (cot α + cot β)(pᵢ −
//! pⱼ) / 2A = 2H·n`, `H` read along the vertex's normal. Vertices at one position are one
//! vertex (their triangles pooled, their normals averaged), so a hard edge reads as the bend
//! it is, not as two flat faces. Positive where the surface bends away from its normal
//! (convex, a sphere seen from outside), negative in creases, in 1 / the mesh's units.
//!
//! Also each vertex's normal curvature along its texture directions (the curvature a ray
//! through the heights bends with, Oliveira & Policarpo 2005): a quadric `h = a u² + b uv + c v²`
//! fitted by least squares to the heights of the vertex's neighbours above its tangent plane,
//! whose second fundamental form `[[2a, b], [b, 2c]]` is read along ∂P/∂s and ∂P/∂t.
//!
//! What this module does not do: the principal curvatures' directions, or smooth the estimate
//! over a neighbourhood wider than a vertex's own (a noisy scan reads noisy).

use std::collections::HashMap;

use super::Mesh;
use glam::{DMat3, DVec3, Vec2, Vec3};
use rayon::prelude::*;

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

    /// Each vertex's `N·∂²P/∂s²` and `N·∂²P/∂t²` for its `∂P/∂s`, `∂P/∂t` in `st`
    /// ([`Mesh::st_derivatives`]): the normal curvature along each texture direction times that
    /// derivative's length squared, from a quadric fitted to the neighbours (module docs).
    /// Negative where the surface falls away from its normal (convex); 0 where a vertex has
    /// too few neighbours to fit, or no derivatives. The mesh must be valid and carry normals.
    ///
    /// ```
    /// use bumpmap_math::surface::Surface;
    /// // A sphere of radius 2, s = u once round: |∂P/∂s| = 2π·2 at the equator, so
    /// // N·∂²P/∂s² = −|∂P/∂s|² / 2 there.
    /// let sphere = Surface::Sphere { radius: 2.0 }.tessellate(48, 24, glam::Vec2::ONE);
    /// let st = sphere.st_derivatives();
    /// let at = 12 * 49 + 10; // on the equator
    /// let expected = -st[at][0].length_squared() / 2.0;
    /// let got = sphere.st_normal_curvature(&st)[at].x;
    /// assert!((got / expected - 1.0).abs() < 0.02, "{got} {expected}");
    /// ```
    pub fn st_normal_curvature(&self, st: &[[Vec3; 2]]) -> Vec<Vec2> {
        st_normal_curvature(self, st)
    }
}

/// One slot per distinct position (split vertices pool), each vertex's slot, and each slot's
/// position.
fn position_slots(mesh: &Mesh) -> (Vec<u32>, Vec<Vec3>) {
    let mut slot_of: HashMap<[u32; 3], u32> = HashMap::with_capacity(mesh.positions.len());
    let mut at = Vec::new();
    let slots = mesh
        .positions
        .iter()
        .map(|p| {
            let next = slot_of.len() as u32;
            *slot_of.entry(p.to_array().map(f32::to_bits)).or_insert_with(|| {
                at.push(*p);
                next
            })
        })
        .collect();
    (slots, at)
}

/// [`Mesh::st_normal_curvature`].
fn st_normal_curvature(mesh: &Mesh, st: &[[Vec3; 2]]) -> Vec<Vec2> {
    let (slots, at) = position_slots(mesh);
    // Each position's neighbours: the positions it shares an edge with.
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); at.len()];
    for t in &mesh.indices {
        let ids = t.map(|i| slots[i as usize]);
        for k in 0..3 {
            let (a, b) = (ids[k], ids[(k + 1) % 3]);
            if a != b {
                neighbours[a as usize].push(b);
                neighbours[b as usize].push(a);
            }
        }
    }
    neighbours.par_iter_mut().for_each(|n| {
        n.sort_unstable();
        n.dedup();
    });
    (0..mesh.positions.len())
        .into_par_iter()
        .map(|i| {
            let (n, Some(&[p_s, p_t])) = (mesh.normals[i].normalize_or_zero(), st.get(i)) else {
                return Vec2::ZERO;
            };
            let slot = slots[i] as usize;
            let Some(form) = fitted_form(at[slot], n, p_s, neighbours[slot].iter().map(|&j| at[j as usize])) else {
                return Vec2::ZERO;
            };
            let along = |d: Vec3| {
                let w = (d - n * n.dot(d)).normalize_or_zero();
                form(w) * d.length_squared()
            };
            Vec2::new(along(p_s), along(p_t))
        })
        .collect()
}

/// The second fundamental form at `p` (unit normal `n`) fitted to `around`, as the normal
/// curvature along a unit tangent direction; `None` where fewer than three neighbours, or
/// ones in a line, leave the quadric undetermined. The tangent frame's first axis follows `toward`.
fn fitted_form(p: Vec3, n: Vec3, toward: Vec3, around: impl Iterator<Item = Vec3>) -> Option<impl Fn(Vec3) -> f32> {
    if n == Vec3::ZERO {
        return None;
    }
    let e1 = (toward - n * n.dot(toward)).try_normalize().unwrap_or_else(|| n.any_orthonormal_vector());
    let e2 = n.cross(e1);
    // Normal equations of h = a u² + b uv + c v², in f64 (the terms are fourth powers of edge
    // lengths).
    let (mut m, mut r) = (DMat3::ZERO, DVec3::ZERO);
    for q in around {
        let d = q - p;
        let (u, v, h) = (d.dot(e1) as f64, d.dot(e2) as f64, d.dot(n) as f64);
        let x = DVec3::new(u * u, u * v, v * v);
        m += DMat3::from_cols(x * x.x, x * x.y, x * x.z);
        r += x * h;
    }
    let scale = m.x_axis.x + m.y_axis.y + m.z_axis.z;
    if scale.is_nan() || scale <= 0.0 || m.determinant().abs() <= 1e-9 * scale * scale * scale {
        return None;
    }
    let [a, b, c] = (m.inverse() * r).to_array();
    Some(move |w: Vec3| {
        let (wu, wv) = (w.dot(e1) as f64, w.dot(e2) as f64);
        (2.0 * a * wu * wu + 2.0 * b * wu * wv + 2.0 * c * wv * wv) as f32
    })
}

/// Each vertex's mean curvature (the same for every vertex at one position); `mesh` carries
/// normals.
fn vertex_curvature(mesh: &Mesh) -> Vec<f32> {
    // One slot a position, so split vertices pool their triangles.
    let (slots, at) = position_slots(mesh);
    let mut normals = vec![Vec3::ZERO; at.len()];
    for (n, &s) in mesh.normals.iter().zip(&slots) {
        normals[s as usize] += *n;
    }
    // The Laplace–Beltrami operator's sum and each position's mixed area.
    let (mut laplacian, mut areas) = (vec![Vec3::ZERO; at.len()], vec![0.0f32; at.len()]);
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
    fn the_torus_bends_along_its_texture_directions_as_its_surface_says() {
        // Away from nothing: the torus's grid is closed but its seam vertices are pooled by
        // position, so every vertex has its ring.
        let torus = Surface::Torus { major: 2.0, minor: 0.7 };
        let (nu, nv) = (96, 48);
        let mesh = torus.tessellate(nu, nv, Vec2::ONE);
        let st = mesh.st_derivatives();
        let fitted = mesh.st_normal_curvature(&st);
        let mut worst: f32 = 0.0;
        for j in 1..nv {
            for i in 1..nu {
                let k = j * (nu + 1) + i;
                let (u, v) = (i as f32 / nu as f32, j as f32 / nv as f32);
                let (k_u, k_v) = torus.normal_curvature(u, v);
                // Relative to the larger of the two (one of them passes through 0).
                let scale = k_u.abs().max(k_v.abs());
                worst = worst.max((fitted[k].x - k_u).abs() / scale).max((fitted[k].y - k_v).abs() / scale);
            }
        }
        assert!(worst < 0.03, "worst relative error {worst}");
        let wall = Surface::Wall { width: 1.0, height: 1.0 }.tessellate(4, 4, Vec2::ONE);
        let flat = wall.st_normal_curvature(&wall.st_derivatives());
        assert!(flat.iter().all(|k| k.abs().max_element() < 1e-5), "{flat:?}");
    }

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
