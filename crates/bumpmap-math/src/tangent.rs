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
//! Longer than most files (~570 lines): both modes, the splitting at seams and the parallel
//! piecewise MikkTSpace run share the per-corner bookkeeping; the tests take a third of it.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use crate::mesh::{Mesh, MeshError};

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

/// One triangle's contribution: unit tangent in the triangle, handedness, and usable or not.
#[derive(Clone, Copy)]
struct Face {
    tangent: Vec3,
    w: f32,
    ok: bool,
    geometric: bool,
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
        TangentMode::MikkTSpace => mikktspace(mesh),
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
        return Face { tangent: Vec3::ZERO, w: 1.0, ok: false, geometric };
    }
    // ∂P/∂s = (e1·Δt2 − e2·Δt1) / det; ∂P/∂t = (e2·Δs1 − e1·Δs2) / det.
    let dp_ds = (e1 * d2.y - e2 * d1.y) / det;
    let dp_dt = (e2 * d1.x - e1 * d2.x) / det;
    let w = if area.cross(dp_ds).dot(dp_dt) >= 0.0 { 1.0 } else { -1.0 };
    match dp_ds.try_normalize() {
        Some(t) => Face { tangent: t, w, ok: true, geometric },
        None => Face { tangent: Vec3::ZERO, w, ok: false, geometric },
    }
}

/// The corner angle of triangle `tri` at its corner `k`.
fn corner_angle(mesh: &Mesh, tri: [u32; 3], k: usize) -> f32 {
    let p = |j: usize| mesh.positions[tri[(k + j) % 3] as usize];
    let (a, b) = (p(1) - p(0), p(2) - p(0));
    a.try_normalize().zip(b.try_normalize()).map_or(0.0, |(a, b)| a.dot(b).clamp(-1.0, 1.0).acos())
}

/// A unit vector perpendicular to `n` (for vertices no triangle gives a tangent to).
fn any_perpendicular(n: Vec3) -> Vec3 {
    let axis = if n.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    (axis - n * n.dot(axis)).normalize_or(Vec3::X)
}

fn ours(mesh: &Mesh, options: &TangentOptions) -> (Mesh, TangentReport) {
    let faces: Vec<Face> = mesh.indices.par_iter().map(|&t| face_frame(mesh, t)).collect();
    let mut report = TangentReport {
        degenerate_uv: faces.iter().filter(|f| !f.ok && f.geometric).count(),
        degenerate_geometry: faces.iter().filter(|f| !f.geometric).count(),
        mirrored: faces.iter().filter(|f| f.ok && f.w < 0.0).count(),
        vertices_split: 0,
    };
    // Vertex → corners (compressed rows): corner c = 3·triangle + k.
    let nv = mesh.vertex_count();
    let mut start = vec![0u32; nv + 1];
    for t in &mesh.indices {
        for &v in t {
            start[v as usize + 1] += 1;
        }
    }
    for i in 0..nv {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut corners = vec![0u32; 3 * mesh.indices.len()];
    // And back: corner → its place in its vertex's row (a search of the row instead made a
    // vertex shared by k triangles cost k², minutes for one OBJ face of 10⁶ vertices).
    let mut slot_of = vec![0u32; 3 * mesh.indices.len()];
    for (ti, t) in mesh.indices.iter().enumerate() {
        for (k, &v) in t.iter().enumerate() {
            corners[fill[v as usize] as usize] = (3 * ti + k) as u32;
            slot_of[3 * ti + k] = fill[v as usize];
            fill[v as usize] += 1;
        }
    }
    // Per vertex: cluster its corners; each corner learns its cluster, each cluster its tangent.
    let cos_split = options.split_angle_degrees.to_radians().cos();
    const CHUNK: usize = 2048;
    let mut cluster_of = vec![0u8; corners.len()];
    let mut slices = Vec::new();
    let mut rest = cluster_of.as_mut_slice();
    for c in 0..nv.div_ceil(CHUNK) {
        let (lo, hi) = (c * CHUNK, ((c + 1) * CHUNK).min(nv));
        let (head, tail) = rest.split_at_mut((start[hi] - start[lo]) as usize);
        slices.push((lo..hi, head));
        rest = tail;
    }
    let clusters: Vec<Vec<(u32, Vec4)>> = slices
        .into_par_iter()
        .map(|(range, ids)| {
            let base = start[range.start] as usize;
            let mut out = Vec::with_capacity(range.len());
            let mut sums: Vec<(Vec3, f32)> = Vec::new();
            for v in range {
                let n = mesh.normals[v];
                sums.clear();
                for ci in start[v] as usize..start[v + 1] as usize {
                    let corner = corners[ci] as usize;
                    let (ti, k) = (corner / 3, corner % 3);
                    let f = &faces[ti];
                    let projected =
                        f.ok.then(|| (f.tangent - n * n.dot(f.tangent)).normalize_or_zero())
                            .filter(|t| *t != Vec3::ZERO);
                    let id = match projected {
                        Some(t) => {
                            let weight = corner_angle(mesh, mesh.indices[ti], k).max(1e-6);
                            let found =
                                sums.iter().position(|(s, w)| *w == f.w && s.normalize_or_zero().dot(t) >= cos_split);
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
                        // Unusable triangles (marked 255) join the first cluster below.
                        None => 255,
                    };
                    ids[ci - base] = id.min(255) as u8;
                }
                if sums.is_empty() {
                    sums.push((any_perpendicular(n), 1.0));
                }
                for (j, (s, w)) in sums.iter().enumerate() {
                    let t = s.try_normalize().unwrap_or_else(|| any_perpendicular(n));
                    out.push((j as u32, t.extend(*w)));
                }
                // Corners of unusable triangles (marked 255) take the first cluster.
                for ci in start[v] as usize..start[v + 1] as usize {
                    if ids[ci - base] == 255 {
                        ids[ci - base] = 0;
                    }
                }
            }
            out
        })
        .collect();
    // Assign vertex indices: cluster 0 keeps the vertex, others become new vertices.
    let mut out = mesh.clone();
    out.tangents = vec![Vec4::ZERO; nv];
    let mut first_new = vec![0u32; nv];
    let mut v = 0usize;
    for chunk in &clusters {
        for &(j, t) in chunk {
            // Clusters arrive vertex by vertex; cluster 0 starts the next vertex.
            if j == 0 {
                out.tangents[v] = t;
                first_new[v] = u32::MAX;
                v += 1;
            } else {
                let vertex = v - 1;
                if first_new[vertex] == u32::MAX {
                    first_new[vertex] = out.positions.len() as u32;
                }
                out.positions.push(mesh.positions[vertex]);
                out.normals.push(mesh.normals[vertex]);
                out.texcoords.push(mesh.texcoords[vertex]);
                out.tangents.push(t);
                report.vertices_split += 1;
            }
        }
    }
    for (ti, t) in out.indices.iter_mut().enumerate() {
        for (k, idx) in t.iter_mut().enumerate() {
            let v = *idx as usize;
            let cluster = cluster_of[slot_of[3 * ti + k] as usize] as u32;
            if cluster > 0 {
                *idx = first_new[v] + cluster - 1;
            }
        }
    }
    (out, report)
}

/// The faces of a mesh (all, or a subset in their original order) as MikkTSpace's callbacks
/// see them, collecting one tangent per corner.
struct MikkGeometry<'a> {
    mesh: &'a Mesh,
    faces: &'a [u32],
    corner_tangents: Vec<Vec4>,
}

impl MikkGeometry<'_> {
    #[inline]
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.indices[self.faces[face] as usize][vert] as usize
    }
}

impl bevy_mikktspace::Geometry for MikkGeometry<'_> {
    fn num_faces(&self) -> usize {
        self.faces.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.normals[self.vertex(face, vert)].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.mesh.texcoords[self.vertex(face, vert)].to_array()
    }

    fn set_tangent(&mut self, tangent_space: Option<bevy_mikktspace::TangentSpace>, face: usize, vert: usize) {
        // MikkTSpace leaves some corners of degenerate faces without a value; the C library
        // then writes its default, which this reproduces.
        let t = tangent_space.unwrap_or_default().tangent_encoded();
        self.corner_tangents[3 * face + vert] = Vec4::from_array(t);
    }
}

/// The most triangle corners at one position MikkTSpace is given. Its time grows with the
/// square of that count (a fan of 10,000 triangles around one vertex takes 3 s on two cores,
/// 20,000 take 12 s, 60,000 over a minute) and its sort recurses about once per such corner (a
/// fan of 60,000 overflowed an 8 MiB stack): past this count the mesh is refused, and below it
/// MikkTSpace runs on a stack sized for it. Real meshes have tens, a sphere's pole hundreds.
pub const MAX_CORNERS_AT_ONE_POSITION: usize = 10_000;

/// Stack MikkTSpace needs per corner at one position (measured: ~300 bytes a level; doubled).
const MIKK_STACK_PER_CORNER: usize = 768;

fn run_mikktspace(mesh: &Mesh, faces: &[u32]) -> Result<Vec<Vec4>, MeshError> {
    // The most corners that share one position in these faces.
    let mut at: std::collections::HashMap<[u32; 3], usize> = std::collections::HashMap::new();
    let mut most = 0;
    for &f in faces {
        for &v in &mesh.indices[f as usize] {
            let n = at.entry(mesh.positions[v as usize].to_array().map(f32::to_bits)).or_default();
            *n += 1;
            most = most.max(*n);
        }
    }
    if most > MAX_CORNERS_AT_ONE_POSITION {
        return Err(MeshError::MikkTSpace(format!(
            "{most} triangle corners share one position; MikkTSpace's time grows with the square of that and it takes at most {MAX_CORNERS_AT_ONE_POSITION} (the other mode, ours, has no such limit)"
        )));
    }
    let stack = (16 << 20) + most * MIKK_STACK_PER_CORNER;
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .name("mikktspace".into())
            .stack_size(stack)
            .spawn_scoped(scope, || {
                let mut geometry = MikkGeometry { mesh, faces, corner_tangents: vec![Vec4::ZERO; 3 * faces.len()] };
                bevy_mikktspace::generate_tangents(&mut geometry).map_err(|e| MeshError::MikkTSpace(e.to_string()))?;
                Ok(geometry.corner_tangents)
            })
            .map_err(|e| MeshError::MikkTSpace(format!("cannot start a thread with a {stack}-byte stack: {e}")))?
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })
}

/// Rings of neighbouring faces each piece carries beyond its own.
const HALO_RINGS: usize = 3;

/// Meshes smaller than this run MikkTSpace in one piece.
const MIKK_PARALLEL_FACES: usize = 100_000;

/// MikkTSpace's tangent for every corner (face-major), as the reference C code produces them.
///
/// Large meshes run in parallel pieces: each piece is a run of faces plus the faces within a few
/// rings of it (vertices compared by value, as MikkTSpace welds them). A corner's tangent depends
/// on the faces around its vertex, met in the same order (and, for degenerate faces, on a
/// neighbour's), so each piece's own corners come out as from the whole mesh: bit for bit on
/// every test mesh, degenerate ones included.
pub fn mikktspace_corner_tangents(mesh: &Mesh) -> Result<Vec<Vec4>, MeshError> {
    let pieces = if mesh.indices.len() >= MIKK_PARALLEL_FACES {
        (mesh.indices.len() / 50_000).max(2 * rayon::current_num_threads())
    } else {
        1
    };
    mikktspace_in_pieces(mesh, pieces)
}

/// [`mikktspace_corner_tangents`] with an explicit number of pieces (1 = the whole mesh).
pub fn mikktspace_in_pieces(mesh: &Mesh, pieces: usize) -> Result<Vec<Vec4>, MeshError> {
    let nf = mesh.indices.len();
    let all: Vec<u32> = (0..nf as u32).collect();
    if pieces <= 1 || nf < 2 * pieces {
        return run_mikktspace(mesh, &all);
    }
    // Canonical vertex ids: equal position, normal and texture coordinate are one vertex.
    let mut canonical = vec![0u32; mesh.vertex_count()];
    let mut seen: std::collections::HashMap<[u32; 8], u32> =
        std::collections::HashMap::with_capacity(mesh.vertex_count());
    for (v, c) in canonical.iter_mut().enumerate() {
        let (p, n, t) = (mesh.positions[v], mesh.normals[v], mesh.texcoords[v]);
        let key = [p.x, p.y, p.z, n.x, n.y, n.z, t.x, t.y].map(f32::to_bits);
        let next = seen.len() as u32;
        *c = *seen.entry(key).or_insert(next);
    }
    // Canonical vertex → faces (compressed rows, faces in order).
    let nc = seen.len();
    let mut start = vec![0u32; nc + 1];
    for t in &mesh.indices {
        for &v in t {
            start[canonical[v as usize] as usize + 1] += 1;
        }
    }
    for i in 0..nc {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut faces_of = vec![0u32; 3 * nf];
    for (f, t) in mesh.indices.iter().enumerate() {
        for &v in t {
            let c = canonical[v as usize] as usize;
            faces_of[fill[c] as usize] = f as u32;
            fill[c] += 1;
        }
    }
    /// A piece's own faces, the faces it ran (own and halo, in order) and their corner tangents.
    type Piece = (std::ops::Range<usize>, Vec<u32>, Vec<Vec4>);
    let results: Vec<Result<Piece, MeshError>> = (0..pieces)
        .into_par_iter()
        .map(|k| {
            let own = k * nf / pieces..(k + 1) * nf / pieces;
            // Rings of faces around the piece's vertices, then around theirs: one ring decides
            // a corner; the others cover degenerate faces that borrow a tangent from a
            // neighbour (one ring was not enough on `obliterated.obj`; two were; three for margin).
            let mut taken = vec![false; nf];
            taken[own.clone()].fill(true);
            let mut frontier: Vec<u32> = own.clone().map(|f| f as u32).collect();
            for _ in 0..HALO_RINGS {
                let mut next = Vec::new();
                for &f in &frontier {
                    for &v in &mesh.indices[f as usize] {
                        let c = canonical[v as usize] as usize;
                        for &g in &faces_of[start[c] as usize..start[c + 1] as usize] {
                            if !taken[g as usize] {
                                taken[g as usize] = true;
                                next.push(g);
                            }
                        }
                    }
                }
                frontier = next;
            }
            // In the original order, which MikkTSpace's sums follow.
            let faces: Vec<u32> = (0..nf as u32).filter(|&f| taken[f as usize]).collect();
            let tangents = run_mikktspace(mesh, &faces)?;
            Ok((own, faces, tangents))
        })
        .collect();
    let mut out = vec![Vec4::ZERO; 3 * nf];
    for r in results {
        let (own, faces, tangents) = r?;
        for (i, &f) in faces.iter().enumerate() {
            if own.contains(&(f as usize)) {
                out[3 * f as usize..3 * f as usize + 3].copy_from_slice(&tangents[3 * i..3 * i + 3]);
            }
        }
    }
    Ok(out)
}

fn mikktspace(mesh: &Mesh) -> Result<(Mesh, TangentReport), MeshError> {
    let corner_tangents = mikktspace_corner_tangents(mesh)?;
    let faces: Vec<Face> = mesh.indices.par_iter().map(|&t| face_frame(mesh, t)).collect();
    let mut report = TangentReport {
        degenerate_uv: faces.iter().filter(|f| !f.ok && f.geometric).count(),
        degenerate_geometry: faces.iter().filter(|f| !f.geometric).count(),
        mirrored: 0,
        vertices_split: 0,
    };
    report.mirrored = (0..mesh.indices.len()).filter(|&f| corner_tangents[3 * f].w < 0.0).count();
    // A vertex keeps the first tangent written to it; a corner with another tangent gets a copy.
    let mut out = mesh.clone();
    let nv = mesh.vertex_count();
    out.tangents = vec![Vec4::ZERO; nv];
    let mut assigned = vec![false; nv];
    let mut copies: std::collections::HashMap<(u32, [u32; 4]), u32> = std::collections::HashMap::new();
    for (f, tri) in out.indices.iter_mut().enumerate() {
        for (k, idx) in tri.iter_mut().enumerate() {
            let t = corner_tangents[3 * f + k];
            let v = *idx as usize;
            if !assigned[v] {
                assigned[v] = true;
                out.tangents[v] = t;
            } else if out.tangents[v] != t {
                let key = (*idx, t.to_array().map(f32::to_bits));
                *idx = *copies.entry(key).or_insert_with(|| {
                    out.positions.push(mesh.positions[v]);
                    out.normals.push(mesh.normals[v]);
                    out.texcoords.push(mesh.texcoords[v]);
                    out.tangents.push(t);
                    report.vertices_split += 1;
                    (out.positions.len() - 1) as u32
                });
            }
        }
    }
    // Vertices no triangle uses still need a tangent.
    for v in 0..nv {
        if !assigned[v] {
            out.tangents[v] = any_perpendicular(mesh.normals[v]).extend(1.0);
        }
    }
    Ok((out, report))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lighting::{Light, ObjectLighting, TangentFrame, Viewer};
    use crate::surface::{BicubicPatch, Surface};
    use glam::{Mat4, Vec2};

    /// Two unit quads side by side in the x–y plane, the left one's texture mirrored in s: the
    /// seam at x = 0 has s = 1 on both sides, so its vertices are shared in the input.
    fn mirrored_pair() -> Mesh {
        let mut m = Mesh::default();
        for (x, s) in [(-1.0, 0.0), (0.0, 1.0), (1.0, 0.0)] {
            for y in [0.0, 1.0] {
                m.positions.push(Vec3::new(x, y, 0.0));
                m.normals.push(Vec3::Z);
                m.texcoords.push(Vec2::new(s, y));
            }
        }
        // Vertices: 0 (−1,0) 1 (−1,1) 2 (0,0) 3 (0,1) 4 (1,0) 5 (1,1); counter-clockwise.
        m.indices = vec![[0, 2, 3], [0, 3, 1], [2, 4, 5], [2, 5, 3]];
        m
    }

    #[test]
    fn mirrored_seam_splits_and_lights_both_sides_alike() {
        let (mesh, report) = generate_tangents(&mirrored_pair(), &TangentOptions::default()).unwrap();
        assert_eq!(report.mirrored, 2, "the right quad's s runs against x");
        assert_eq!(report.vertices_split, 2, "both seam vertices split");
        let frame = |v: usize| {
            let t = mesh.tangents[v];
            TangentFrame { t: t.truncate(), b: mesh.bitangent(v), n: mesh.normals[v] }
        };
        // Each triangle's corners agree on handedness: +1 left, −1 right.
        for (tri, w) in [(0, 1.0), (1, 1.0), (2, -1.0), (3, -1.0)] {
            for &v in &mesh.indices[tri] {
                assert_eq!(mesh.tangents[v as usize].w, w, "triangle {tri} vertex {v}");
            }
        }
        // Mirror-image points lit by mirror-image lights see the same tangent-space light.
        let lit =
            |light: Vec3| ObjectLighting::new(Mat4::IDENTITY, Light::Positional(light), Viewer::Infinite(Vec3::Z));
        let (left, _) = lit(Vec3::new(-0.5 - 0.3, 0.7, 1.0)).tangent_space(Vec3::new(-0.5, 0.5, 0.0), &frame(0));
        let (right, _) = lit(Vec3::new(0.5 + 0.3, 0.7, 1.0)).tangent_space(Vec3::new(0.5, 0.5, 0.0), &frame(4));
        assert!((left - right).length() < 1e-6, "{left} vs {right}");
        assert!(left.x < 0.0, "the light lies toward decreasing s on both sides");
    }

    #[test]
    fn flat_grid_gets_the_analytic_frame_without_splits() {
        let mesh = Surface::Wall { width: 2.0, height: 1.0 }.tessellate(6, 3, Vec2::new(3.0, 1.0));
        let mut bare = mesh.clone();
        bare.tangents.clear();
        let (out, report) = generate_tangents(&bare, &TangentOptions::default()).unwrap();
        assert_eq!(report, TangentReport::default());
        for t in &out.tangents {
            assert!((t.truncate() - Vec3::X).length() < 1e-6 && t.w == 1.0, "{t}");
        }
    }

    #[test]
    fn degenerate_uv_triangles_are_reported_and_framed() {
        let mut m = mirrored_pair();
        // Collapse the texture coordinates of the left quad onto a point.
        for i in [0, 1] {
            m.texcoords[i] = Vec2::new(1.0, 0.5);
        }
        m.texcoords[3] = Vec2::new(1.0, 0.5);
        m.texcoords[2] = Vec2::new(1.0, 0.5);
        let (out, report) = generate_tangents(&m, &TangentOptions::default()).unwrap();
        // Three triangles touch only collapsed coordinates (the left quad, and the right quad's
        // triangle with two seam vertices); the fourth still spans texture space.
        assert_eq!(report.degenerate_uv, 3);
        for (t, n) in out.tangents.iter().zip(&out.normals) {
            assert!(
                t.is_finite() && (t.truncate().length() - 1.0).abs() < 1e-5 && t.truncate().dot(*n).abs() < 1e-5,
                "{t}"
            );
        }
    }

    #[test]
    fn tessellated_surfaces_match_their_analytic_tangents() {
        for surface in
            [Surface::default_torus(), Surface::Sphere { radius: 1.0 }, Surface::Patch(BicubicPatch::stretched())]
        {
            let analytic = surface.tessellate(32, 16, Vec2::new(2.0, 1.0));
            let mut bare = analytic.clone();
            bare.tangents.clear();
            for mode in [TangentMode::Ours, TangentMode::MikkTSpace] {
                let (out, _) = generate_tangents(&bare, &TangentOptions { mode, ..Default::default() }).unwrap();
                assert_eq!(out.vertex_count(), analytic.vertex_count(), "{surface:?} {mode:?}: no splits");
                let worst = out
                    .tangents
                    .iter()
                    .zip(&analytic.tangents)
                    .skip(33) // the sphere's south-pole row has no defined ∂P/∂u
                    .take(out.vertex_count() - 66)
                    .map(|(a, b)| a.truncate().angle_between(b.truncate()).to_degrees())
                    .fold(0.0f32, f32::max);
                // Finite differences over one 1/32-turn facet: a few degrees at most.
                assert!(worst < 8.0, "{surface:?} {mode:?}: worst {worst}°");
            }
        }
    }

    #[test]
    fn bad_meshes_are_errors() {
        let mut m = mirrored_pair();
        m.indices.push([0, 1, 9]);
        assert!(matches!(
            generate_tangents(&m, &TangentOptions::default()),
            Err(MeshError::IndexOutOfRange { index: 9, .. })
        ));
        let mut m = mirrored_pair();
        m.positions[2].x = f32::NAN;
        assert!(matches!(generate_tangents(&m, &TangentOptions::default()), Err(MeshError::NonFinite { .. })));
        let mut m = mirrored_pair();
        m.texcoords.clear();
        assert_eq!(generate_tangents(&m, &TangentOptions::default()).unwrap_err(), MeshError::NoTexcoords);
    }

    /// A disc of `n` triangles around one vertex, texture mapped flat.
    fn fan(n: usize) -> Mesh {
        let mut m = Mesh::default();
        m.positions.push(Vec3::ZERO);
        m.texcoords.push(glam::Vec2::splat(0.5));
        for i in 0..=n {
            let a = std::f32::consts::TAU * i as f32 / n as f32;
            m.positions.push(Vec3::new(a.cos(), a.sin(), 0.0));
            m.texcoords.push(glam::Vec2::new(0.5 + 0.5 * a.cos(), 0.5 - 0.5 * a.sin()));
        }
        m.indices = (0..n as u32).map(|i| [0, i + 1, i + 2]).collect();
        m.normals = vec![Vec3::Z; m.positions.len()];
        m
    }

    #[test]
    fn fans_around_one_vertex_are_framed_or_refused_not_overflowed() {
        // Ours: every corner at the centre in one cluster, found without searching its row.
        let (out, report) = generate_tangents(&fan(50_000), &TangentOptions::default()).unwrap();
        assert_eq!(report.vertices_split, 0);
        // Each sliver spans 6e-5 of the texture: single precision frames it to about 1e-3.
        let worst = out.tangents.iter().map(|t| t.truncate().distance(Vec3::X)).fold(0.0f32, f32::max);
        assert!(worst < 1e-2, "the flat map's +s is +x: off by {worst}");
        // MikkTSpace: a fan it can take runs on a stack sized for it (8,000 corners at the centre
        // recurse deeper than a rayon worker's 2 MiB allow)…
        let mikk = TangentOptions { mode: TangentMode::MikkTSpace, ..Default::default() };
        let (out, _) = generate_tangents(&fan(8_000), &mikk).unwrap();
        let worst = out.tangents.iter().map(|t| t.truncate().distance(Vec3::X)).fold(0.0f32, f32::max);
        assert!(worst < 1e-2, "MikkTSpace off by {worst}");
        // …and past its limit the mesh is refused, saying why.
        let e = generate_tangents(&fan(MAX_CORNERS_AT_ONE_POSITION + 1), &mikk).unwrap_err().to_string();
        assert!(e.contains("10001 triangle corners share one position"), "{e}");
    }
}
