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
//! the vertex → corners grouping both use.

use std::sync::atomic::{AtomicU8, Ordering};

use glam::{Vec3, Vec3A, Vec4};
use rayon::prelude::*;

use crate::mesh::{Mesh, MeshError};

mod corners;
mod mikktspace;
#[cfg(test)]
mod tests;

use corners::CornersByVertex;
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

/// What tangent generation found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TangentReport {
    /// Triangles of zero area in texture space (no usable ∂P/∂s).
    pub degenerate_uv: usize,
    /// Triangles of zero area in space.
    pub degenerate_geometry: usize,
    /// Triangles whose texture space is mirrored (w = −1).
    pub mirrored: usize,
    /// Vertices added by splitting.
    pub vertices_split: usize,
}

/// One triangle's contribution: unit tangent in the triangle, handedness, usable or not, and
/// (when usable) its corner angles, which weight its tangent at each vertex.
#[derive(Clone, Copy)]
struct Face {
    tangent: Vec3,
    w: f32,
    ok: bool,
    geometric: bool,
    angles: [f32; 3],
}

/// Generates tangents, returning the mesh (possibly with split vertices) and a report.
/// Needs normals and texture coordinates; fails on invalid meshes.
pub fn generate_tangents(mesh: &Mesh, options: &TangentOptions) -> Result<(Mesh, TangentReport), MeshError> {
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

fn face_frame(mesh: &Mesh, tri: [u32; 3]) -> Face {
    let [a, b, c] = tri.map(|i| i as usize);
    let (p0, p1, p2) = (mesh.positions[a], mesh.positions[b], mesh.positions[c]);
    let (t0, t1, t2) = (mesh.texcoords[a], mesh.texcoords[b], mesh.texcoords[c]);
    let (e1, e2) = (p1 - p0, p2 - p0);
    let (d1, d2) = (t1 - t0, t2 - t0);
    let area = e1.cross(e2);
    let det = d1.x * d2.y - d2.x * d1.y;
    // Zero area in texture space, relative to the UV edge lengths (scale-free).
    let uv_scale = d1.length_squared().max(d2.length_squared());
    // Zero area in space, relative to the edge lengths: a sliver whose sine of angle is below
    // 1e-6 (such as a pole's fan triangle, two of whose vertices coincide up to rounding).
    let geometric = area.length_squared() > 1e-12 * e1.length_squared() * e2.length_squared() && area.is_finite();
    if !(det.abs() > 1e-7 * uv_scale && uv_scale > 0.0 && geometric) {
        return Face { tangent: Vec3::ZERO, w: 1.0, ok: false, geometric, angles: [0.0; 3] };
    }
    // ∂P/∂s = (e1·Δt2 − e2·Δt1) / det; ∂P/∂t = (e2·Δs1 − e1·Δs2) / det. Only ∂P/∂s's
    // direction and the sign of (area × ∂P/∂s)·∂P/∂t are used, so the division is by the sign
    // of det alone (the product's sign needs neither: det² > 0).
    let dp_ds = (e1 * d2.y - e2 * d1.y) * det.signum();
    let dp_dt = e2 * d1.x - e1 * d2.x;
    let w = if area.cross(e1 * d2.y - e2 * d1.y).dot(dp_dt) >= 0.0 { 1.0 } else { -1.0 };
    match dp_ds.try_normalize() {
        Some(t) => Face { tangent: t, w, ok: true, geometric, angles: corner_angles([p0, p1, p2]) },
        None => Face { tangent: Vec3::ZERO, w, ok: false, geometric, angles: [0.0; 3] },
    }
}

/// The angles of a triangle at its corners 0, 1, 2 (0 at a corner with an edge of zero length),
/// the three at once.
fn corner_angles(p: [Vec3; 3]) -> [f32; 3] {
    // Edge k runs from corner k to corner k + 1; the angle at corner k lies between edge k
    // and edge k − 1 reversed: cos = −(e_k · e_{k−1}) / (|e_k| |e_{k−1}|).
    let e = [p[1] - p[0], p[2] - p[1], p[0] - p[2]];
    let dots = Vec3A::new(e[0].dot(e[2]), e[1].dot(e[0]), e[2].dot(e[1]));
    let len2 = Vec3A::new(e[0].length_squared(), e[1].length_squared(), e[2].length_squared());
    let lengths = sqrt(len2 * Vec3A::new(len2.z, len2.x, len2.y));
    let cos = -dots / lengths;
    // A zero-length edge (or one too long to square) leaves no angle.
    let defined = lengths.cmpgt(Vec3A::ZERO) & lengths.is_finite_mask();
    Vec3A::select(defined, acos(cos), Vec3A::ZERO).to_array()
}

/// √x lane by lane.
fn sqrt(x: Vec3A) -> Vec3A {
    Vec3A::from_array(x.to_array().map(f32::sqrt))
}

/// arccos of each lane for x in [−1, 1] (clamped; NaN stays NaN), within 2·10⁻⁸ of the exact
/// value before f32 rounding: Abramowitz & Stegun 4.4.46, √(1 − |x|) times a degree-7
/// polynomial (evaluated by Estrin's scheme, so its products overlap), reflected for x < 0.
/// Three lanes at once (a triangle's corners) and several times faster here than the C
/// library's `acosf`, which took a third of the time of making tangents. Multiplies and adds,
/// not `mul_add`: the same bits on every target, and no software fma.
fn acos(x: Vec3A) -> Vec3A {
    // a₀ is the table's 1.5707963050, one f32 below π/2, not π/2 itself.
    #[allow(clippy::approx_constant)]
    const A: [f32; 8] = [
        1.570_796_3,
        -0.214_598_8,
        0.088_978_99,
        -0.050_174_303,
        0.030_891_88,
        -0.017_088_126,
        0.006_670_09,
        -0.001_262_491_1,
    ];
    let a = x.abs().min(Vec3A::ONE);
    let pair = |k: usize| Vec3A::splat(A[k]) + Vec3A::splat(A[k + 1]) * a;
    let a2 = a * a;
    let low = pair(0) + pair(2) * a2;
    let high = pair(4) + pair(6) * a2;
    let poly = low + high * (a2 * a2);
    let r = sqrt(Vec3A::ONE - a) * poly;
    Vec3A::select(x.cmplt(Vec3A::ZERO), Vec3A::splat(std::f32::consts::PI) - r, r)
}

/// A unit vector perpendicular to `n` (for vertices no triangle gives a tangent to).
fn any_perpendicular(n: Vec3) -> Vec3 {
    let axis = if n.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    (axis - n * n.dot(axis)).normalize_or(Vec3::X)
}

fn ours(mesh: &Mesh, options: &TangentOptions) -> (Mesh, TangentReport) {
    let faces: Vec<Face> = mesh.indices.par_iter().map(|&t| face_frame(mesh, t)).collect();
    let mut report = faces
        .par_iter()
        .fold(TangentReport::default, |mut r, f| {
            r.degenerate_uv += (!f.ok && f.geometric) as usize;
            r.degenerate_geometry += !f.geometric as usize;
            r.mirrored += (f.ok && f.w < 0.0) as usize;
            r
        })
        .reduce(TangentReport::default, |a, b| TangentReport {
            degenerate_uv: a.degenerate_uv + b.degenerate_uv,
            degenerate_geometry: a.degenerate_geometry + b.degenerate_geometry,
            mirrored: a.mirrored + b.mirrored,
            vertices_split: 0,
        });
    // Vertex → corners (a search for each vertex's corners instead made a vertex shared by k
    // triangles cost k², minutes for one OBJ face of 10⁶ vertices).
    let nv = mesh.vertex_count();
    let CornersByVertex { start, corners } = CornersByVertex::new(&mesh.indices, nv, |v| v as usize);
    // Per vertex: cluster its corners. Each corner learns its cluster; cluster 0's tangent is
    // the vertex's own, the others' (rare: seams) are listed to become new vertices.
    let cos_split = options.split_angle_degrees.to_radians().cos();
    const CHUNK: usize = 2048;
    // Each corner's cluster, by corner: written by the vertex's worker, each corner once.
    let cluster_of: Vec<AtomicU8> = (0..corners.len()).map(|_| AtomicU8::new(0)).collect();
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
                for &corner in &corners[start[v] as usize..start[v + 1] as usize] {
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
    (Mesh { positions, normals, texcoords, tangents, indices }, report)
}
