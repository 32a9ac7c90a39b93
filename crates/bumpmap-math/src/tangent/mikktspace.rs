//! The MikkTSpace mode: the reference algorithm through `bevy_mikktspace`, run in parallel
//! pieces on large meshes, and the vertices split where corners receive different tangents.
//! It does not weld or split by its own rules: which corners share a tangent is MikkTSpace's
//! decision, reproduced bit for bit.

use glam::Vec4;
use rayon::prelude::*;

use super::corners::CornersByVertex;
use super::faces::{self, face_frames};
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
    // Canonical vertex ids: equal position, normal and texture coordinate are one vertex, named
    // by its first index. By a parallel sort of the vertices' bits (a hash map's inserts, one
    // by one, took a seventh of the whole run on two threads).
    let nv = mesh.vertex_count();
    let mut keyed: Vec<([u32; 8], u32)> = (0..nv)
        .into_par_iter()
        .map(|v| {
            let (p, n, t) = (mesh.positions[v], mesh.normals[v], mesh.texcoords[v]);
            ([p.x, p.y, p.z, n.x, n.y, n.z, t.x, t.y].map(f32::to_bits), v as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    let mut canonical = vec![0u32; nv];
    let mut first = 0;
    for (i, &(key, v)) in keyed.iter().enumerate() {
        if key != keyed[first].0 {
            first = i;
        }
        canonical[v as usize] = keyed[first].1;
    }
    drop(keyed);
    // Canonical vertex → faces (in order).
    let by_vertex = CornersByVertex::new(&mesh.indices, nv, |v| canonical[v as usize] as usize);
    // Each piece writes its own faces' corners: consecutive runs of `out`.
    let mut out = vec![Vec4::ZERO; 3 * nf];
    let mut slices = Vec::with_capacity(pieces);
    let mut rest = out.as_mut_slice();
    for k in 0..pieces {
        let own = k * nf / pieces..(k + 1) * nf / pieces;
        let (head, tail) = rest.split_at_mut(3 * own.len());
        slices.push((own, head));
        rest = tail;
    }
    slices.into_par_iter().try_for_each(|(own, out)| {
        // Rings of faces around the piece's vertices, then around theirs: one ring decides a
        // corner; the others cover degenerate faces that borrow a tangent from a neighbour
        // (one ring was not enough on `obliterated.obj`; two were; three for margin).
        let mut taken = vec![false; nf];
        taken[own.clone()].fill(true);
        let mut frontier: Vec<u32> = own.clone().map(|f| f as u32).collect();
        let mut halo = Vec::new();
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
            halo.extend_from_slice(&next);
            frontier = next;
        }
        // In the original order, which MikkTSpace's sums follow: the halo before the piece,
        // the piece, the halo after it.
        halo.sort_unstable();
        let split = halo.partition_point(|&f| (f as usize) < own.start);
        let faces: Vec<u32> = halo[..split]
            .iter()
            .copied()
            .chain(own.start as u32..own.end as u32)
            .chain(halo[split..].iter().copied())
            .collect();
        let tangents = run_mikktspace(mesh, &faces)?;
        out.copy_from_slice(&tangents[3 * split..3 * (split + own.len())]);
        Ok::<_, MeshError>(())
    })?;
    Ok(out)
}

pub(super) fn mikktspace(mesh: &Mesh) -> Result<(Mesh, TangentReport), MeshError> {
    let corner_tangents = mikktspace_corner_tangents(mesh)?;
    // The degenerate counts from our frames; mirrored as MikkTSpace's handedness says.
    let mut report = faces::count(&face_frames(mesh));
    report.mirrored = (0..mesh.indices.len()).filter(|&f| corner_tangents[3 * f].w < 0.0).count();
    // A vertex keeps its first corner's tangent; a corner with another tangent gets a copy
    // (one per vertex and tangent). Which corners differ is found in parallel from each vertex's
    // first corner; the copies are made in corner order.
    let nv = mesh.vertex_count();
    let by_vertex = CornersByVertex::new(&mesh.indices, nv, |v| v as usize);
    let mut tangents: Vec<Vec4> = (0..nv)
        .into_par_iter()
        .map(|v| match by_vertex.row(v).first() {
            Some(&corner) => corner_tangents[corner as usize],
            // Vertices no triangle uses still need a tangent.
            None => any_perpendicular(mesh.normals[v]).extend(1.0),
        })
        .collect();
    let differing: Vec<u32> = (0..3 * mesh.indices.len() as u32)
        .into_par_iter()
        .filter(|&c| {
            let v = mesh.indices[c as usize / 3][c as usize % 3] as usize;
            by_vertex.row(v)[0] != c && corner_tangents[c as usize] != tangents[v]
        })
        .collect();
    let mut out = Mesh { tangents: Vec::new(), ..mesh.clone() };
    let mut copies: foldhash::HashMap<(u32, [u32; 4]), u32> = foldhash::HashMap::default();
    for c in differing {
        let (f, k) = (c as usize / 3, c as usize % 3);
        let (v, t) = (mesh.indices[f][k], corner_tangents[c as usize]);
        out.indices[f][k] = *copies.entry((v, t.to_array().map(f32::to_bits))).or_insert_with(|| {
            out.positions.push(mesh.positions[v as usize]);
            out.normals.push(mesh.normals[v as usize]);
            out.texcoords.push(mesh.texcoords[v as usize]);
            if !mesh.colors.is_empty() {
                out.colors.push(mesh.colors[v as usize]);
            }
            tangents.push(t);
            report.vertices_split += 1;
            (out.positions.len() - 1) as u32
        });
    }
    out.tangents = tangents;
    Ok((out, report))
}
