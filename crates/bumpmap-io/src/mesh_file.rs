//! Mesh files: OBJ (via `tobj`) and glTF 2.0 / GLB (via `gltf`) in; glTF or GLB with a TANGENT
//! attribute out.
//!
//! OBJ faces are triangulated and vertices unified over (position, texture coordinate, normal)
//! triples. glTF primitives of every mesh are merged in file order, without node transforms;
//! only triangle lists are read. A file without normals gets area-weighted vertex normals (the
//! documented fallback); one without texture coordinates loads, but tangent generation then
//! refuses it. Counts are checked against `MAX_ELEMENTS` before any data is read.

use std::io::Write;
use std::path::{Path, PathBuf};

use bumpmap_math::mesh::{MAX_ELEMENTS, Mesh, MeshError};
use glam::{Vec2, Vec3, Vec4};

use crate::atomic::FileSet;
use crate::error::IoError;

/// A loaded mesh and what the file itself supplied.
#[derive(Clone, Debug)]
pub struct LoadedMesh {
    pub mesh: Mesh,
    pub had_normals: bool,
    pub had_tangents: bool,
    /// Every file read: the mesh file and, for glTF, its buffer files. An output must replace
    /// none of them.
    pub sources: Vec<PathBuf>,
}

fn mesh_err(path: &Path, reason: impl std::fmt::Display) -> IoError {
    IoError::Mesh { path: path.to_path_buf(), reason: reason.to_string() }
}

/// Loads an `.obj`, `.gltf` or `.glb` file.
pub fn load_mesh(path: &Path) -> Result<LoadedMesh, IoError> {
    if let Err(source) = std::fs::metadata(path) {
        return Err(IoError::Read { path: path.to_path_buf(), source });
    }
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    let mut loaded = match ext.as_str() {
        "obj" => load_obj(path)?,
        "gltf" | "glb" => load_gltf(path)?,
        _ => return Err(mesh_err(path, "unknown mesh format (use .obj, .gltf or .glb)")),
    };
    if !loaded.had_normals {
        loaded.mesh.compute_normals();
    }
    loaded.mesh.validate().map_err(|e| mesh_err(path, e))?;
    Ok(loaded)
}

fn load_obj(path: &Path) -> Result<LoadedMesh, IoError> {
    let options = tobj::LoadOptions { single_index: true, triangulate: true, ignore_points: true, ignore_lines: true };
    let (models, _materials) =
        tobj::load_obj(path, &options).map_err(|e| mesh_err(path, format!("not a readable OBJ file: {e}")))?;
    let mut mesh = Mesh::default();
    let mut had_normals = true;
    let mut has_texcoords = true;
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
        mesh.texcoords.extend(m.texcoords.chunks_exact(2).map(|p| Vec2::new(p[0], p[1])));
        mesh.indices.extend(m.indices.chunks_exact(3).map(|t| [base + t[0], base + t[1], base + t[2]]));
    }
    if !had_normals {
        mesh.normals.clear();
    }
    if !has_texcoords {
        mesh.texcoords.clear();
    }
    Ok(LoadedMesh { mesh, had_normals, had_tangents: false, sources: vec![path.to_path_buf()] })
}

fn load_gltf(path: &Path) -> Result<LoadedMesh, IoError> {
    let crate::gltf_read::GltfFile { document, buffers, files } = crate::gltf_read::read(path)?;
    for accessor in document.accessors() {
        if accessor.count() > MAX_ELEMENTS {
            return Err(mesh_err(
                path,
                MeshError::TooLarge { what: "accessor count", count: accessor.count() as u64, max: MAX_ELEMENTS },
            ));
        }
    }
    let mut mesh = Mesh::default();
    let (mut had_normals, mut had_tangents, mut has_texcoords) = (true, true, true);
    for gmesh in document.meshes() {
        for prim in gmesh.primitives() {
            if prim.mode() != gltf::mesh::Mode::Triangles {
                return Err(mesh_err(
                    path,
                    format!(
                        "mesh '{}' has a {:?} primitive; only triangle lists are supported",
                        gmesh.name().unwrap_or("?"),
                        prim.mode()
                    ),
                ));
            }
            let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d[..]));
            let positions: Vec<Vec3> = reader
                .read_positions()
                .ok_or_else(|| mesh_err(path, "a primitive has no POSITION"))?
                .map(Vec3::from)
                .collect();
            let n = positions.len();
            let base = mesh.positions.len() as u32;
            let normals: Vec<Vec3> = reader.read_normals().map(|r| r.map(Vec3::from).collect()).unwrap_or_default();
            let texcoords: Vec<Vec2> =
                reader.read_tex_coords(0).map(|r| r.into_f32().map(Vec2::from).collect()).unwrap_or_default();
            let tangents: Vec<Vec4> = reader.read_tangents().map(|r| r.map(Vec4::from).collect()).unwrap_or_default();
            let indices: Vec<u32> = match reader.read_indices() {
                Some(r) => r.into_u32().collect(),
                None => (0..n as u32).collect(),
            };
            if !indices.len().is_multiple_of(3) {
                return Err(mesh_err(path, format!("{} indices is not a whole number of triangles", indices.len())));
            }
            if let Some(&bad) = indices.iter().find(|&&i| i as usize >= n) {
                return Err(mesh_err(path, format!("index {bad} is out of range for a primitive of {n} vertices")));
            }
            had_normals &= normals.len() == n;
            has_texcoords &= texcoords.len() == n;
            had_tangents &= tangents.len() == n;
            mesh.positions.extend(positions);
            mesh.normals.extend(normals);
            mesh.texcoords.extend(texcoords);
            mesh.tangents.extend(tangents);
            mesh.indices.extend(indices.chunks_exact(3).map(|t| [base + t[0], base + t[1], base + t[2]]));
        }
    }
    if !had_normals {
        mesh.normals.clear();
    }
    if !has_texcoords {
        mesh.texcoords.clear();
    }
    if !had_tangents {
        mesh.tangents.clear();
    }
    let mut sources = vec![path.to_path_buf()];
    sources.extend(files);
    Ok(LoadedMesh { mesh, had_normals, had_tangents, sources })
}

/// Writes `mesh` (positions, normals, texture coordinates, tangents, indices) as glTF 2.0: a
/// `.glb`, or a `.gltf` with its buffer in a `.bin` file beside it. Both written atomically.
pub fn save_gltf(path: &Path, mesh: &Mesh) -> Result<(), IoError> {
    let mut set = FileSet::new(&[]);
    save_gltf_into(&mut set, path, mesh)?;
    set.commit().map(|_| ())
}

/// [`save_gltf`] into a [`FileSet`]: the `.gltf` and its `.bin`, or the `.glb`.
pub fn save_gltf_into(set: &mut FileSet, path: &Path, mesh: &Mesh) -> Result<(), IoError> {
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    if ext != "gltf" && ext != "glb" {
        return Err(IoError::UnsupportedOutput { path: path.to_path_buf(), expected: ".gltf or .glb" });
    }
    let n = mesh.positions.len();
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut push = |bytes: Vec<u8>, target: u32| {
        let offset = bin.len();
        bin.extend_from_slice(&bytes);
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        views.push(format!(r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{},"target":{target}}}"#, bytes.len()));
    };
    let floats = |v: &mut dyn Iterator<Item = f32>| v.flat_map(f32::to_le_bytes).collect::<Vec<u8>>();
    push(floats(&mut mesh.positions.iter().flat_map(|p| p.to_array())), 34962);
    let mut attributes = vec![r#""POSITION":0"#.to_string()];
    let (lo, hi) = mesh.positions.iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let mut accessors = vec![format!(
        r#"{{"bufferView":0,"componentType":5126,"count":{n},"type":"VEC3","min":[{},{},{}],"max":[{},{},{}]}}"#,
        lo.x, lo.y, lo.z, hi.x, hi.y, hi.z
    )];
    let mut add = |name: &str, kind: &str, bytes: Vec<u8>, push: &mut dyn FnMut(Vec<u8>, u32)| {
        let i = accessors.len();
        push(bytes, 34962);
        attributes.push(format!(r#""{name}":{i}"#));
        accessors.push(format!(r#"{{"bufferView":{i},"componentType":5126,"count":{n},"type":"{kind}"}}"#));
    };
    if !mesh.normals.is_empty() {
        add("NORMAL", "VEC3", floats(&mut mesh.normals.iter().flat_map(|v| v.to_array())), &mut push);
    }
    if !mesh.texcoords.is_empty() {
        add("TEXCOORD_0", "VEC2", floats(&mut mesh.texcoords.iter().flat_map(|v| v.to_array())), &mut push);
    }
    if !mesh.tangents.is_empty() {
        add("TANGENT", "VEC4", floats(&mut mesh.tangents.iter().flat_map(|v| v.to_array())), &mut push);
    }
    let index_view = accessors.len();
    push(mesh.indices.iter().flatten().flat_map(|i| i.to_le_bytes()).collect(), 34963);
    accessors.push(format!(
        r#"{{"bufferView":{index_view},"componentType":5125,"count":{},"type":"SCALAR"}}"#,
        3 * mesh.indices.len()
    ));
    let bin_name = format!("{}.bin", path.file_stem().unwrap_or_default().to_string_lossy());
    let uri = if ext == "gltf" { format!(r#","uri":"{bin_name}""#) } else { String::new() };
    let json = format!(
        r#"{{"asset":{{"version":"2.0","generator":"bumpmap"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"meshes":[{{"primitives":[{{"attributes":{{{}}},"indices":{index_view}}}]}}],"buffers":[{{"byteLength":{}{uri}}}],"bufferViews":[{}],"accessors":[{}]}}"#,
        attributes.join(","),
        bin.len(),
        views.join(","),
        accessors.join(",")
    );
    if ext == "gltf" {
        set.write(&path.with_file_name(&bin_name), |w| w.write_all(&bin))?;
        return set.write(path, |w| w.write_all(json.as_bytes()));
    }
    let mut json = json.into_bytes();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    set.write(path, |w| {
        w.write_all(b"glTF")?;
        w.write_all(&2u32.to_le_bytes())?;
        w.write_all(&(total as u32).to_le_bytes())?;
        w.write_all(&(json.len() as u32).to_le_bytes())?;
        w.write_all(b"JSON")?;
        w.write_all(&json)?;
        w.write_all(&(bin.len() as u32).to_le_bytes())?;
        w.write_all(b"BIN\0")?;
        w.write_all(&bin)
    })
}
