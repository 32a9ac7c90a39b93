//! The MikkTSpace mode: the reference algorithm through `bevy_mikktspace`, run in parallel
//! pieces on large meshes, and the vertices split where corners receive different tangents.
//! It does not weld or split by its own rules: which corners share a tangent is MikkTSpace's
//! decision, reproduced bit for bit.

use glam::Vec4;
use rayon::prelude::*;

use super::corners::CornersByVertex;
use super::faces::face_frames;
use super::{TangentReport, any_perpendicular};
use crate::mesh::{Mesh, MeshError};

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
    let mut at: foldhash::HashMap<[u32; 3], usize> = foldhash::HashMap::default();
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
    let mut seen: foldhash::HashMap<[u32; 8], u32> =
        foldhash::HashMap::with_capacity_and_hasher(mesh.vertex_count(), Default::default());
    for (v, c) in canonical.iter_mut().enumerate() {
        let (p, n, t) = (mesh.positions[v], mesh.normals[v], mesh.texcoords[v]);
        let key = [p.x, p.y, p.z, n.x, n.y, n.z, t.x, t.y].map(f32::to_bits);
        let next = seen.len() as u32;
        *c = *seen.entry(key).or_insert(next);
    }
    // Canonical vertex → faces (in order).
    let by_vertex = CornersByVertex::new(&mesh.indices, seen.len(), |v| canonical[v as usize] as usize);
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
                        for &corner in by_vertex.row(canonical[v as usize] as usize) {
                            let g = corner / 3;
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

pub(super) fn mikktspace(mesh: &Mesh) -> Result<(Mesh, TangentReport), MeshError> {
    let corner_tangents = mikktspace_corner_tangents(mesh)?;
    let faces = face_frames(mesh);
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
    let mut copies: foldhash::HashMap<(u32, [u32; 4]), u32> = foldhash::HashMap::default();
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
