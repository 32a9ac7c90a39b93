//! Tangent frames for meshes (Cg Tutorial §8.4): ours, and MikkTSpace's.
//!
//! Ours: each triangle's ∂P/∂s and ∂P/∂t from its texture coordinates; triangles of zero area in
//! texture space are detected and contribute nothing; mirrored triangles (negative area in
//! texture space) are detected and carry handedness w = −1 as glTF does. At each vertex the
//! triangles' tangents, projected into the plane of the vertex normal and weighted by the
//! triangle's corner angle, are blended when they agree — same handedness and within an angle
//! threshold — and the vertex is split when they do not (mirror seams, hard UV creases). A
//! vertex left with no usable triangle gets a tangent perpendicular to its normal.
//!
//! MikkTSpace: the reference algorithm (through `bevy_mikktspace`, a faithful port), which
//! Blender, Substance and glTF viewers bake and shade with; corners that receive different
//! tangents are split into separate vertices.
//!
//! This file holds the interface and ours; `mikktspace.rs` the MikkTSpace mode; `corners.rs`
//! the vertex → corners grouping both use; `decode.rs` how a renderer reads a map in the frames.

use std::sync::atomic::{AtomicU8, Ordering};

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use crate::mesh::{Mesh, MeshError};

mod corners;
mod decode;
mod faces;
mod mikktspace;
#[cfg(test)]
mod tests;

use corners::CornersByVertex;
pub use decode::{TangentDecode, decode_per_pixel};
use faces::face_frames;
pub use mikktspace::{MAX_CORNERS_AT_ONE_POSITION, mikktspace_corner_tangents, mikktspace_in_pieces};

/// Which algorithm makes the tangents.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum TangentMode {
    /// Per-triangle ∂P/∂s blended at vertices, split at mirror seams (Cg Tutorial §8.4).
    #[default]
    Ours,
    /// The reference MikkTSpace algorithm (via `bevy_mikktspace`).
    MikkTSpace,
}

crate::named!(TangentMode {
    Ours => "ours": "Per-triangle ∂P/∂s blended at vertices, split at mirror seams (Cg Tutorial §8.4); parallel",
    MikkTSpace => "mikktspace": "The reference MikkTSpace algorithm (what Blender, Substance and glTF viewers use)",
});

/// Options of [`generate_tangents`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentOptions {
    /// Which algorithm.
    pub mode: TangentMode,
    /// Tangents further apart than this (degrees) split a vertex (ours only).
    pub split_angle_degrees: f32,
}

impl Default for TangentOptions {
    fn default() -> Self {
        Self { mode: TangentMode::Ours, split_angle_degrees: 60.0 }
    }
}

impl TangentOptions {
    /// Refuses a split angle outside [0, 180] degrees ([`MeshError::SplitAngle`]):
    /// [`generate_tangents`] checks it first, and a caller may check it before reading a mesh.
    pub fn check(&self) -> Result<(), MeshError> {
        let angle = self.split_angle_degrees;
        if !(0.0..=180.0).contains(&angle) {
            return Err(MeshError::SplitAngle(angle));
        }
        Ok(())
    }
}

/// What tangent generation found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TangentReport {
    /// Triangles of zero area in texture space (no usable ∂P/∂s).
    pub degenerate_uv: usize,
    /// Triangles of zero area in space.
    pub degenerate_geometry: usize,
    /// Triangles whose texture space is mirrored (w = −1 in this crate's (s, t)). For a mesh read
    /// from a file, whose t runs down the image, these are the triangles *not* mirrored as the
    /// image is displayed; `bumpmap_io::mesh_file::mirrored_as_displayed` counts those.
    pub mirrored: usize,
    /// Vertices added by splitting.
    pub vertices_split: usize,
}

/// Generates tangents, returning the mesh (possibly with split vertices) and a report.
/// Needs normals and texture coordinates; fails on invalid meshes.
pub fn generate_tangents(mesh: &Mesh, options: &TangentOptions) -> Result<(Mesh, TangentReport), MeshError> {
    options.check()?;
    mesh.validate()?;
    if mesh.texcoords.is_empty() {
        return Err(MeshError::NoTexcoords);
    }
    if mesh.normals.is_empty() {
        return Err(MeshError::NoNormals);
    }
    match options.mode {
        TangentMode::Ours => Ok(ours(mesh, options)),
        TangentMode::MikkTSpace => mikktspace::mikktspace(mesh),
    }
}

/// A unit vector perpendicular to `n` (for vertices no triangle gives a tangent to).
fn any_perpendicular(n: Vec3) -> Vec3 {
    let axis = if n.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    (axis - n * n.dot(axis)).normalize_or(Vec3::X)
}

fn ours(mesh: &Mesh, options: &TangentOptions) -> (Mesh, TangentReport) {
    let faces = face_frames(mesh);
    let mut report = faces::count(&faces);
    // Vertex → corners (a search for each vertex's corners instead made a vertex shared by k
    // triangles cost k², minutes for one OBJ face of 10⁶ vertices).
    let nv = mesh.vertex_count();
    let by_vertex = CornersByVertex::new(&mesh.indices, nv, |v| v as usize);
    // Per vertex: cluster its corners. Each corner learns its cluster; cluster 0's tangent is
    // the vertex's own, the others' (rare: seams) are listed to become new vertices.
    let cos_split = options.split_angle_degrees.to_radians().cos();
    const CHUNK: usize = 2048;
    // Each corner's cluster, by corner: written by the vertex's worker, each corner once.
    let cluster_of: Vec<AtomicU8> = (0..by_vertex.corners.len()).map(|_| AtomicU8::new(0)).collect();
    let mut tangents = vec![Vec4::ZERO; nv];
    let mut slices = Vec::new();
    let mut rest = tangents.as_mut_slice();
    for c in 0..nv.div_ceil(CHUNK) {
        let (lo, hi) = (c * CHUNK, ((c + 1) * CHUNK).min(nv));
        let (own, tail) = rest.split_at_mut(hi - lo);
        rest = tail;
        slices.push((lo..hi, own));
    }
    let extra: Vec<Vec<(u32, Vec4)>> = slices
        .into_par_iter()
        .map(|(range, own)| {
            let mut extra = Vec::new();
            let mut sums: Vec<(Vec3, f32)> = Vec::new();
            for v in range.clone() {
                let n = mesh.normals[v];
                sums.clear();
                for &corner in by_vertex.row(v) {
                    let corner = corner as usize;
                    let (ti, k) = (corner / 3, corner % 3);
                    let f = &faces[ti];
                    let projected =
                        f.ok.then(|| (f.tangent - n * n.dot(f.tangent)).normalize_or_zero())
                            .filter(|t| *t != Vec3::ZERO);
                    let id = match projected {
                        Some(t) => {
                            let weight = f.angles[k].max(1e-6);
                            let found = sums.iter().position(|(s, w)| *w == f.w && s.dot(t) >= cos_split * s.length());
                            match found {
                                Some(j) => {
                                    sums[j].0 += t * weight;
                                    j
                                }
                                None if sums.len() < 254 => {
                                    sums.push((t * weight, f.w));
                                    sums.len() - 1
                                }
                                None => 0,
                            }
                        }
                        // Unusable triangles join the first cluster.
                        None => 0,
                    };
                    cluster_of[corner].store(id as u8, Ordering::Relaxed);
                }
                if sums.is_empty() {
                    sums.push((any_perpendicular(n), 1.0));
                }
                for (j, (s, w)) in sums.iter().enumerate() {
                    let t = s.try_normalize().unwrap_or_else(|| any_perpendicular(n)).extend(*w);
                    if j == 0 {
                        own[v - range.start] = t;
                    } else {
                        extra.push((v as u32, t));
                    }
                }
            }
            extra
        })
        .collect();
    let cluster_of: Vec<u8> = cluster_of.into_iter().map(AtomicU8::into_inner).collect();
    // Cluster 0 keeps the vertex; the others become new vertices after the mesh's, in vertex
    // order and, for one vertex, in cluster order.
    report.vertices_split = extra.iter().map(Vec::len).sum();
    let total = nv + report.vertices_split;
    fn copy<T: Copy + Send + Sync>(from: &[T], capacity: usize) -> Vec<T> {
        let mut to = Vec::with_capacity(capacity);
        to.par_extend(from.par_iter().copied());
        to
    }
    let (mut positions, mut normals, mut texcoords) =
        (copy(&mesh.positions, total), copy(&mesh.normals, total), copy(&mesh.texcoords, total));
    let mut colors = copy(&mesh.colors, if mesh.colors.is_empty() { 0 } else { total });
    tangents.reserve_exact(report.vertices_split);
    let mut first_new = vec![0u32; nv];
    for &(v, t) in extra.iter().flatten() {
        let v = v as usize;
        if first_new[v] == 0 {
            first_new[v] = positions.len() as u32;
        }
        positions.push(mesh.positions[v]);
        normals.push(mesh.normals[v]);
        texcoords.push(mesh.texcoords[v]);
        if !mesh.colors.is_empty() {
            colors.push(mesh.colors[v]);
        }
        tangents.push(t);
    }
    let indices = mesh
        .indices
        .par_iter()
        .enumerate()
        .with_min_len(4096)
        .map(|(ti, t)| {
            std::array::from_fn(|k| match cluster_of[3 * ti + k] as u32 {
                0 => t[k],
                cluster => first_new[t[k] as usize] + cluster - 1,
            })
        })
        .collect();
    (Mesh { positions, normals, texcoords, tangents, colors, indices }, report)
}
