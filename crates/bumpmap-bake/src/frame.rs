//! LOW at one sample: the point, the way its ray goes, and the tangent frame there, all
//! interpolated from LOW's vertices by the sample's barycentric weights as the renderer
//! interpolates them; and the averaged normals the default rays follow.
//!
//! What this module does not do: cast rays (the baker does).

use std::collections::HashMap;

use bumpmap_math::mesh::Mesh;
use glam::Vec3;

use crate::encode::{TangentDecode, encode_in_frame};
use crate::texels::Covered;

/// Each vertex's averaged normal: the area-weighted normals of every triangle touching any
/// vertex at its position (vertices split for hard edges or UV seams share one).
pub(crate) fn averaged_normals(mesh: &Mesh) -> Vec<Vec3> {
    let key = |p: Vec3| p.to_array().map(f32::to_bits);
    let mut sums: HashMap<[u32; 3], Vec3> = HashMap::new();
    for t in &mesh.indices {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let n = (b - a).cross(c - a);
        for p in [a, b, c] {
            *sums.entry(key(p)).or_default() += n;
        }
    }
    mesh.positions
        .iter()
        .zip(&mesh.normals)
        .map(|(p, own)| sums.get(&key(*p)).and_then(|n| n.try_normalize()).unwrap_or(*own))
        .collect()
}

/// LOW at one sample: the point, the ray's direction and the tangent frame as interpolated.
pub(crate) struct Frame {
    /// The point on LOW.
    pub p: Vec3,
    /// Outward: the ray goes the other way.
    pub d: Vec3,
    t: Vec3,
    n: Vec3,
    /// B as the decode forms it.
    b: Vec3,
}

/// Where a sample's ray starts on a cage given point by point: the cage's point interpolated as
/// LOW's is, the ray from there through LOW's point, and the distance between them (`None`
/// where they meet: the ray then follows the frame's own direction from LOW's point).
pub(crate) fn cage_ray(cage: &[Vec3], low: &Mesh, at: Covered, p: Vec3) -> Option<(Vec3, f32)> {
    let ids = low.indices[at.triangle as usize].map(|i| i as usize);
    let on_cage: Vec3 = ids.iter().zip(at.weights).map(|(&i, w)| cage[i] * w).sum();
    let out = on_cage - p;
    let distance = out.length();
    (distance > 1e-9 * (1.0 + p.length())).then(|| (out / distance, distance))
}

impl Frame {
    /// The frame at `at`, its rays along `rays` (one a vertex), B as `decode` forms it.
    pub fn at(low: &Mesh, rays: &[Vec3], at: Covered, decode: TangentDecode) -> Frame {
        let [i, j, k] = low.indices[at.triangle as usize].map(|i| i as usize);
        let [a, b, c] = at.weights;
        let mix = |v: &[Vec3]| v[i] * a + v[j] * b + v[k] * c;
        let (ti, tj, tk) = (low.tangents[i], low.tangents[j], low.tangents[k]);
        let n = mix(&low.normals);
        let t = ti.truncate() * a + tj.truncate() * b + tk.truncate() * c;
        let b = match decode {
            // The handedness interpolated: its sign is MikkTSpace's per-triangle sign.
            TangentDecode::MikkTSpace => (ti.w * a + tj.w * b + tk.w * c).signum() * n.cross(t),
            // B as each vertex has it (`w · N × T`), interpolated.
            TangentDecode::PerVertex => low.bitangent(i) * a + low.bitangent(j) * b + low.bitangent(k) * c,
        };
        Frame { p: mix(&low.positions), d: mix(rays).normalize_or(n.normalize_or(Vec3::Z)), t, n, b }
    }

    /// `normal` in this frame, as the decode it was made for will read it back.
    pub fn encode(&self, normal: Vec3) -> Vec3 {
        encode_in_frame(normal, self.t, self.b, self.n).unwrap_or(Vec3::Z)
    }
}
