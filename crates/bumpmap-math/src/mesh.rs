//! Indexed triangle meshes with per-vertex tangent frames: what a surface tessellates into and
//! what a mesh file loads as. Pure data; tangent generation lives in `tangent.rs`.

use glam::{Vec2, Vec3, Vec4};

/// An indexed triangle mesh. Every per-vertex array has `positions.len()` entries (or is empty
/// where noted). Triangles wind counter-clockwise when seen from the side the normal faces.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub texcoords: Vec<Vec2>,
    /// `xyz` = unit tangent T (along increasing s), `w` = ±1 handedness: `B = w · (N × T)`.
    /// Empty until generated or loaded.
    pub tangents: Vec<Vec4>,
    pub indices: Vec<[u32; 3]>,
}

impl Mesh {
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// The bitangent of vertex `i`: `w · (N × T)`. Panics without tangents.
    pub fn bitangent(&self, i: usize) -> Vec3 {
        let t = self.tangents[i];
        t.w * self.normals[i].cross(t.truncate())
    }
}
