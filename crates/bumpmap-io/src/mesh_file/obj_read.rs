//! OBJ in (via `tobj`): faces triangulated, vertices unified over (position, texture
//! coordinate, normal) triples, v flipped into this crate's texture space (t = 1 − v;
//! [`ObjTexcoords`]). A face of fewer than three vertices, or texture coordinates on only some
//! faces, is an error naming the line (not dropped); material libraries are never opened.

use std::path::Path;

use bumpmap_math::mesh::{MAX_ELEMENTS, Mesh, MeshError};
use glam::{Vec2, Vec3};

use super::{LoadedMesh, ObjTexcoords, mesh_err};
use crate::error::IoError;

/// What `tobj` would pass over in silence: faces of one or two vertices, faces without texture
/// coordinates in a file whose other faces have them, and indices that name no element (tobj
/// wraps them around, so −6148914691236517207 became an index of some other vertex). Each is an
/// error, named by line.
fn check_obj_faces(path: &Path, text: &str) -> Result<(), IoError> {
    let mut with_uv: Option<usize> = None;
    let mut without_uv: Option<usize> = None;
    // [v, vt, vn]: how many the file has, and how many are defined so far (a negative index
    // counts back from the last one defined before the face).
    let kinds = ["v", "vt", "vn"];
    let mut total = [0i64; 3];
    for line in text.lines() {
        if let Some(k) = line.split_whitespace().next().and_then(|w| kinds.iter().position(|&x| x == w)) {
            total[k] += 1;
        }
    }
    let mut so_far = [0i64; 3];
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let first = words.next();
        if let Some(k) = first.and_then(|w| kinds.iter().position(|&x| x == w)) {
            so_far[k] += 1;
            continue;
        }
        if first != Some("f") {
            continue;
        }
        let refs: Vec<&str> = words.collect();
        if refs.len() < 3 {
            return Err(mesh_err(
                path,
                format!("line {}: a face needs at least 3 vertices, this one has {}", i + 1, refs.len()),
            ));
        }
        for r in &refs {
            let has_uv = r.split('/').nth(1).is_some_and(|t| !t.is_empty());
            *(if has_uv { &mut with_uv } else { &mut without_uv }) = Some(i + 1);
        }
        if let (Some(a), Some(b)) = (with_uv, without_uv) {
            return Err(mesh_err(
                path,
                format!(
                    "only some faces have texture coordinates (line {a} has, line {b} has not); give every face a vt, or none"
                ),
            ));
        }
        for r in &refs {
            for (k, index) in r.split('/').enumerate().take(3).filter(|(_, t)| !t.is_empty()) {
                let what = ["position", "texture coordinate", "normal"][k];
                let n: i64 = index.parse().map_err(|e: std::num::ParseIntError| {
                    let why = match e.kind() {
                        std::num::IntErrorKind::PosOverflow | std::num::IntErrorKind::NegOverflow => {
                            format!("is beyond any count of the file's {}s", kinds[k])
                        }
                        _ => "is not a whole number".into(),
                    };
                    mesh_err(path, format!("line {}: {what} index '{index}' {why}", i + 1))
                })?;
                let ok = (1..=total[k]).contains(&n) || (-so_far[k]..=-1).contains(&n);
                if !ok {
                    return Err(mesh_err(
                        path,
                        format!(
                            "line {}: {what} index {n} names none of the file's {} {}s (1..={}, or -1..=-{} counting back)",
                            i + 1,
                            total[k],
                            kinds[k],
                            total[k],
                            so_far[k]
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

pub(crate) fn parse_obj(path: &Path, bytes: &[u8], texcoords: ObjTexcoords) -> Result<LoadedMesh, IoError> {
    let text = std::str::from_utf8(bytes).map_err(|e| mesh_err(path, format!("not a text OBJ file: {e}")))?;
    check_obj_faces(path, text)?;
    let options = tobj::LoadOptions { single_index: true, triangulate: true, ignore_points: true, ignore_lines: true };
    // Materials are not read: no file besides the OBJ itself is opened.
    let (models, _materials) =
        tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &options, |_| Err(tobj::LoadError::OpenFileFailed))
            .map_err(|e| mesh_err(path, format!("not a readable OBJ file: {e}")))?;
    let mut mesh = Mesh::default();
    let mut had_normals = true;
    let mut has_texcoords = true;
    let mut objects = Vec::new();
    for model in &models {
        let m = &model.mesh;
        let base = mesh.positions.len() as u32;
        let n = m.positions.len() / 3;
        if n + mesh.positions.len() > MAX_ELEMENTS || m.indices.len() / 3 + mesh.indices.len() > MAX_ELEMENTS {
            return Err(mesh_err(
                path,
                MeshError::TooLarge {
                    what: "vertices or triangles",
                    count: (n + m.indices.len() / 3) as u64,
                    max: MAX_ELEMENTS,
                },
            ));
        }
        mesh.positions.extend(m.positions.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])));
        had_normals &= m.normals.len() == 3 * n;
        has_texcoords &= m.texcoords.len() == 2 * n;
        mesh.normals.extend(m.normals.chunks_exact(3).map(|p| Vec3::new(p[0], p[1], p[2])));
        mesh.texcoords.extend(m.texcoords.chunks_exact(2).map(|p| match texcoords {
            ObjTexcoords::FlipV => Vec2::new(p[0], 1.0 - p[1]),
            ObjTexcoords::Keep => Vec2::new(p[0], p[1]),
        }));
        let first = mesh.indices.len();
        mesh.indices.extend(m.indices.chunks_exact(3).map(|t| [base + t[0], base + t[1], base + t[2]]));
        objects.push((model.name.clone(), first..mesh.indices.len()));
    }
    if !had_normals {
        mesh.normals.clear();
    }
    if !has_texcoords {
        mesh.texcoords.clear();
    }
    Ok(LoadedMesh {
        mesh,
        had_normals,
        had_tangents: false,
        sources: vec![path.to_path_buf()],
        objects,
        ..Default::default()
    })
}
