//! Cutting a mesh into parts and giving a part back faces: what a glTF primitive with its own
//! material, and a double-sided one (glTF 2.0 §3.9.6), need of the geometry; and how a part's
//! surface covers what is behind it ([`AlphaMode`]).

use std::collections::HashMap;

use super::Mesh;

/// How a part's alpha (its base colour's) shows: glTF 2.0 §3.9.4's `alphaMode`, with
/// `alphaCutoff` for MASK. The file reader and the renderers share this one definition.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum AlphaMode {
    /// `OPAQUE`: alpha ignored; the surface hides what is behind it.
    #[default]
    Opaque,
    /// `MASK`: cut out where the alpha is below `cutoff`, opaque elsewhere.
    Mask {
        /// `alphaCutoff`, in [0, 1] (glTF's default 0.5).
        cutoff: f32,
    },
    /// `BLEND`: `alpha · surface + (1 − alpha) · behind`, drawn after the opaque parts, the
    /// farthest first.
    Blend,
}

impl Mesh {
    /// A mesh of `triangles` (indices into this mesh) and only the vertices they use, every
    /// per-vertex array cut alike, the vertices in the order the triangles first use them.
    ///
    /// ```
    /// use bumpmap_math::mesh::wavy_grid;
    /// let grid = wavy_grid(4, 2);
    /// let half = grid.submesh(&grid.indices[..8]);
    /// assert_eq!(half.triangle_count(), 8);
    /// assert!(half.vertex_count() < grid.vertex_count());
    /// assert_eq!(half.positions[half.indices[3][1] as usize], grid.positions[grid.indices[3][1] as usize]);
    /// ```
    pub fn submesh(&self, triangles: &[[u32; 3]]) -> Mesh {
        let mut new_index: HashMap<u32, u32> = HashMap::with_capacity(triangles.len() * 3 / 2);
        let mut order = Vec::with_capacity(triangles.len() * 3 / 2);
        let indices = triangles
            .iter()
            .map(|t| {
                t.map(|v| {
                    *new_index.entry(v).or_insert_with(|| {
                        order.push(v as usize);
                        (order.len() - 1) as u32
                    })
                })
            })
            .collect();
        fn cut<T: Copy>(all: &[T], order: &[usize]) -> Vec<T> {
            if all.is_empty() { Vec::new() } else { order.iter().map(|&i| all[i]).collect() }
        }
        Mesh {
            positions: cut(&self.positions, &order),
            normals: cut(&self.normals, &order),
            texcoords: cut(&self.texcoords, &order),
            tangents: cut(&self.tangents, &order),
            colors: cut(&self.colors, &order),
            indices,
        }
    }

    /// Adds a back face for every triangle: the same corners wound the other way, on copies of
    /// the vertices whose normal, tangent and bitangent are reversed (`N → −N`, `T → −T`,
    /// `w → −w`, so `B = w·(N × T)` turns too). A perturbed normal `T·x + B·y + N·z` is then
    /// exactly reversed on the back, which is how a double-sided glTF material is lit (glTF 2.0
    /// §3.9.6; three.js reverses the whole frame the same way). With back faces culled, each
    /// side draws only its own.
    pub fn add_back_faces(&mut self) {
        let n = self.positions.len() as u32;
        self.positions.extend_from_within(..);
        let normals = self.normals.len();
        self.normals.extend_from_within(..);
        for v in &mut self.normals[normals..] {
            *v = -*v;
        }
        self.texcoords.extend_from_within(..);
        let tangents = self.tangents.len();
        self.tangents.extend_from_within(..);
        for t in &mut self.tangents[tangents..] {
            *t = -*t;
        }
        self.colors.extend_from_within(..);
        let triangles = self.indices.len();
        self.indices.extend_from_within(..);
        for t in &mut self.indices[triangles..] {
            *t = [t[0] + n, t[2] + n, t[1] + n];
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use crate::mesh::{Mesh, wavy_grid};
    use crate::tangent::{TangentOptions, generate_tangents};

    fn grid(nx: usize, ny: usize) -> Mesh {
        generate_tangents(&wavy_grid(nx, ny), &TangentOptions::default()).unwrap().0
    }

    #[test]
    fn a_back_face_reverses_the_perturbed_normal_and_the_winding() {
        let mut mesh = grid(3, 2);
        let (nv, nt) = (mesh.vertex_count(), mesh.triangle_count());
        let front = mesh.clone();
        mesh.add_back_faces();
        assert_eq!((mesh.vertex_count(), mesh.triangle_count()), (2 * nv, 2 * nt));
        mesh.validate().unwrap();
        let perturbed = |m: &Mesh, i: usize, x: f32, y: f32, z: f32| {
            m.tangents[i].truncate() * x + m.bitangent(i) * y + m.normals[i] * z
        };
        for i in 0..nv {
            let (f, b) = (perturbed(&front, i, 0.3, -0.4, 0.87), perturbed(&mesh, nv + i, 0.3, -0.4, 0.87));
            assert!((f + b).length() < 1e-6, "vertex {i}: front {f}, back {b}");
            assert_eq!(mesh.texcoords[nv + i], front.texcoords[i]);
        }
        // Wound the other way: the geometric normal of each copy faces away from the front's.
        let face = |m: &Mesh, t: [u32; 3]| {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            (b - a).cross(c - a)
        };
        for t in 0..nt {
            let (f, b) = (face(&mesh, mesh.indices[t]), face(&mesh, mesh.indices[nt + t]));
            assert!(f.dot(b) < 0.0 && (f + b).length() < 1e-5 * f.length().max(1.0), "triangle {t}");
        }
    }

    #[test]
    fn a_submesh_keeps_each_triangles_corners() {
        let mut mesh = grid(4, 3);
        mesh.texcoords[5] = Vec2::new(9.0, 9.0);
        let picked: Vec<[u32; 3]> = mesh.indices.iter().copied().skip(3).step_by(2).collect();
        let sub = mesh.submesh(&picked);
        sub.validate().unwrap();
        for (s, t) in sub.indices.iter().zip(&picked) {
            for k in 0..3 {
                let (a, b) = (s[k] as usize, t[k] as usize);
                assert_eq!(
                    (sub.positions[a], sub.normals[a], sub.texcoords[a], sub.tangents[a]),
                    (mesh.positions[b], mesh.normals[b], mesh.texcoords[b], mesh.tangents[b])
                );
            }
        }
        let used: std::collections::HashSet<u32> = picked.iter().flatten().copied().collect();
        assert_eq!(sub.vertex_count(), used.len(), "only the vertices used");
        let empty = Mesh { tangents: Vec::new(), ..mesh.clone() }.submesh(&picked);
        assert!(empty.tangents.is_empty() && empty.positions.len() == used.len());
    }
}
