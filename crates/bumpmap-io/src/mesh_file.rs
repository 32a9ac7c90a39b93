//! Mesh files: OBJ (via `tobj`) and glTF 2.0 / GLB (via `gltf`) in; glTF or GLB with a TANGENT
//! attribute out.
//!
//! OBJ faces are triangulated and vertices unified over (position, texture coordinate, normal)
//! triples, with v flipped into this crate's texture space (t = 1 − v; [`ObjTexcoords`]); a
//! face of fewer than three vertices, or texture coordinates on only some faces, is
//! an error (not dropped); material libraries are not opened. glTF meshes are placed by the
//! scene's node transforms (each instance is its own copy, in world space) and merged into one
//! mesh; only triangle lists are read. glTF's texture coordinates are this crate's as they
//! are; its TANGENT handedness is ours negated ([`gltf_handedness`]), on the way in and out. A file without normals gets area-weighted vertex normals (the
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

/// How a mesh file is read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshOptions {
    /// Let a glTF's buffer URIs lead outside its folder (absolute paths, `..`). Off by default:
    /// a glTF from elsewhere must not make the tool read arbitrary files.
    pub allow_outside_paths: bool,
    /// How an OBJ's `vt` become texture coordinates.
    pub obj_texcoords: ObjTexcoords,
}

/// How an OBJ file's texture coordinates map to this crate's texture space (t = 0 at the
/// image's first row, its top as displayed — glTF's convention too).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ObjTexcoords {
    /// `t = 1 − v`: OBJ's v = 0 is the bottom of the image, as Blender, Maya and every OBJ
    /// exporter write it.
    #[default]
    FlipV,
    /// `t = v`, for OBJ files written with v = 0 at the image's top.
    Keep,
}

/// glTF's TANGENT handedness for this crate's `w`, and back (the map is its own inverse).
///
/// Here `w` makes `cross(N, T)·w` point along +t, down the image as displayed; glTF reads the
/// normal texture's +Y (up the image) along `cross(N, T)·w`, so its `w` is ours negated.
pub fn gltf_handedness(w: f32) -> f32 {
    -w
}

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (materials are not read).
    Obj,
    /// glTF 2.0, as JSON or as GLB (told apart by the GLB magic).
    Gltf,
}

impl MeshFormat {
    /// The format a file name's extension says, if any.
    pub fn from_path(path: &Path) -> Option<Self> {
        let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
        match ext.as_str() {
            "obj" => Some(Self::Obj),
            "gltf" | "glb" => Some(Self::Gltf),
            _ => None,
        }
    }
}

/// Loads an `.obj`, `.gltf` or `.glb` file with the default [`MeshOptions`].
pub fn load_mesh(path: &Path) -> Result<LoadedMesh, IoError> {
    load_mesh_with(path, &MeshOptions::default())
}

/// Loads an `.obj`, `.gltf` or `.glb` file.
pub fn load_mesh_with(path: &Path, options: &MeshOptions) -> Result<LoadedMesh, IoError> {
    if let Err(source) = std::fs::metadata(path) {
        return Err(IoError::Read { path: path.to_path_buf(), source });
    }
    let format =
        MeshFormat::from_path(path).ok_or_else(|| mesh_err(path, "unknown mesh format (use .obj, .gltf or .glb)"))?;
    let loaded = match format {
        MeshFormat::Obj => {
            let bytes = crate::gltf_read::read_file(path, path, crate::gltf_read::MAX_FILE_BYTES)?;
            parse_obj(path, &bytes, options.obj_texcoords)?
        }
        MeshFormat::Gltf => from_gltf(path, crate::gltf_read::read(path, options.allow_outside_paths)?)?,
    };
    finish(path, loaded)
}

/// A mesh file's bytes already in memory; `name` is the file errors name. A glTF read this
/// way has no folder, so only `data:` URIs and a GLB's own chunk supply its buffers. OBJ
/// texture coordinates are flipped as [`ObjTexcoords::FlipV`] says.
pub fn read_mesh(bytes: &[u8], name: &Path, format: MeshFormat) -> Result<LoadedMesh, IoError> {
    let loaded = match format {
        MeshFormat::Obj => parse_obj(name, bytes, ObjTexcoords::FlipV)?,
        MeshFormat::Gltf => {
            from_gltf(name, crate::gltf_read::parse(name, bytes, crate::gltf_read::BufferFiles::None)?)?
        }
    };
    finish(name, loaded)
}

fn finish(path: &Path, mut loaded: LoadedMesh) -> Result<LoadedMesh, IoError> {
    if !loaded.had_normals {
        loaded.mesh.compute_normals();
    }
    loaded.mesh.validate().map_err(|e| mesh_err(path, e))?;
    Ok(loaded)
}

/// What `tobj` would pass over in silence: faces of one or two vertices, and faces without
/// texture coordinates in a file whose other faces have them. Both are errors, named by line.
fn check_obj_faces(path: &Path, text: &str) -> Result<(), IoError> {
    let mut with_uv: Option<usize> = None;
    let mut without_uv: Option<usize> = None;
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() != Some("f") {
            continue;
        }
        let refs: Vec<&str> = words.collect();
        if refs.len() < 3 {
            return Err(mesh_err(
                path,
                format!("line {}: a face needs at least 3 vertices, this one has {}", i + 1, refs.len()),
            ));
        }
        for r in refs {
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
    }
    Ok(())
}

fn parse_obj(path: &Path, bytes: &[u8], texcoords: ObjTexcoords) -> Result<LoadedMesh, IoError> {
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

/// The meshes to read and the world transform of each: the default scene's nodes (or the
/// first scene's; or, with no scene, every node that is no other's child), each mesh once per
/// node that holds it. A file with no nodes gives its meshes in local space.
fn instances(path: &Path, doc: &gltf::Document) -> Result<Vec<(usize, glam::Mat4)>, IoError> {
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    if nodes.is_empty() {
        return Ok(doc.meshes().map(|m| (m.index(), glam::Mat4::IDENTITY)).collect());
    }
    let roots: Vec<usize> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().map(|n| n.index()).collect(),
        None => {
            let mut child = vec![false; nodes.len()];
            for n in &nodes {
                for c in n.children() {
                    child[c.index()] = true;
                }
            }
            (0..nodes.len()).filter(|&i| !child[i]).collect()
        }
    };
    let mut out = Vec::new();
    // Depth-first, each node visited at most once per path from a root; a node reached twice
    // on one path (a cycle, which glTF forbids) is an error rather than endless work.
    let mut stack: Vec<(usize, glam::Mat4, usize)> =
        roots.iter().rev().map(|&i| (i, glam::Mat4::IDENTITY, 0)).collect();
    let mut visits = 0usize;
    while let Some((i, parent, depth)) = stack.pop() {
        visits += 1;
        if depth > nodes.len() || visits > MAX_ELEMENTS {
            return Err(mesh_err(
                path,
                format!("the node hierarchy has a cycle (through node {i}); glTF nodes form trees"),
            ));
        }
        let node = &nodes[i];
        let world = parent * glam::Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            out.push((mesh.index(), world));
        }
        for c in node.children().collect::<Vec<_>>().into_iter().rev() {
            stack.push((c.index(), world, depth + 1));
        }
    }
    Ok(out)
}

fn from_gltf(path: &Path, file: crate::gltf_read::GltfFile) -> Result<LoadedMesh, IoError> {
    let crate::gltf_read::GltfFile { document, buffers, files } = file;
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
    let meshes: Vec<gltf::Mesh> = document.meshes().collect();
    for (mesh_index, world_from_local) in instances(path, &document)? {
        let gmesh = &meshes[mesh_index];
        // Normals by the inverse transpose; a mirroring transform (negative determinant)
        // turns the winding and the tangent frame's handedness around (glTF 2.0 §3.7.4).
        let linear = glam::Mat3::from_mat4(world_from_local);
        let normal_matrix = linear.inverse().transpose();
        let mirrored = linear.determinant() < 0.0;
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
                .map(|p| world_from_local.transform_point3(Vec3::from(p)))
                .collect();
            let n = positions.len();
            if n + mesh.positions.len() > MAX_ELEMENTS {
                return Err(mesh_err(
                    path,
                    MeshError::TooLarge {
                        what: "vertices (all instances)",
                        count: (n + mesh.positions.len()) as u64,
                        max: MAX_ELEMENTS,
                    },
                ));
            }
            let base = mesh.positions.len() as u32;
            let normals: Vec<Vec3> = reader
                .read_normals()
                .map(|r| r.map(|v| (normal_matrix * Vec3::from(v)).normalize_or_zero()).collect())
                .unwrap_or_default();
            let texcoords: Vec<Vec2> =
                reader.read_tex_coords(0).map(|r| r.into_f32().map(Vec2::from).collect()).unwrap_or_default();
            let tangents: Vec<Vec4> = reader
                .read_tangents()
                .map(|r| {
                    r.map(|t| {
                        let xyz = (linear * Vec3::new(t[0], t[1], t[2])).normalize_or_zero();
                        let w = gltf_handedness(t[3]);
                        xyz.extend(if mirrored { -w } else { w })
                    })
                    .collect()
                })
                .unwrap_or_default();
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
            if indices.len() / 3 + mesh.indices.len() > MAX_ELEMENTS {
                return Err(mesh_err(
                    path,
                    MeshError::TooLarge {
                        what: "triangles (all instances)",
                        count: (indices.len() / 3 + mesh.indices.len()) as u64,
                        max: MAX_ELEMENTS,
                    },
                ));
            }
            had_normals &= normals.len() == n;
            has_texcoords &= texcoords.len() == n;
            had_tangents &= tangents.len() == n;
            mesh.positions.extend(positions);
            mesh.normals.extend(normals);
            mesh.texcoords.extend(texcoords);
            mesh.tangents.extend(tangents);
            mesh.indices.extend(indices.chunks_exact(3).map(|t| {
                if mirrored { [base + t[0], base + t[2], base + t[1]] } else { [base + t[0], base + t[1], base + t[2]] }
            }));
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

/// What [`save_gltf`] had to repair so the file is valid glTF (NORMAL and TANGENT.xyz must be
/// unit vectors, TANGENT.w ±1): vectors that were zero, not finite or far from unit length.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GltfRepairs {
    /// Normals replaced by the normalized sum of the vertex's face normals (+Z if that is zero
    /// too: a vertex of degenerate triangles only).
    pub normals: usize,
    /// Tangents replaced by a unit vector perpendicular to the (repaired) normal, w = +1 here.
    pub tangents: usize,
}

/// The normals and tangents to write: unit length, tangents perpendicular to the normals.
fn repaired(mesh: &Mesh) -> (Vec<Vec3>, Vec<Vec4>, GltfRepairs) {
    // glTF's validator allows a length error of about 5e-4; renormalize everything, and
    // rebuild what cannot be renormalized.
    let unit = |v: Vec3| v.is_finite() && v.length_squared() > 1e-12;
    let mut repairs = GltfRepairs::default();
    let mut normals: Vec<Vec3> = mesh.normals.iter().map(|n| n.normalize_or_zero()).collect();
    if normals.iter().any(|&n| !unit(n)) {
        let mut from_faces = vec![Vec3::ZERO; mesh.positions.len()];
        for t in &mesh.indices {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let face = (b - a).cross(c - a);
            if face.is_finite() {
                for &i in t {
                    from_faces[i as usize] += face;
                }
            }
        }
        for (n, f) in normals.iter_mut().zip(from_faces) {
            if !unit(*n) {
                *n = if unit(f) { f.normalize() } else { Vec3::Z };
                repairs.normals += 1;
            }
        }
    }
    let tangents = mesh
        .tangents
        .iter()
        .zip(&normals)
        .map(|(t, &n)| {
            let xyz = t.truncate();
            let w = if t.w < 0.0 { -1.0 } else { 1.0 };
            let along = xyz - n * n.dot(xyz);
            if unit(along) && t.w.abs() == 1.0 {
                along.normalize().extend(w)
            } else {
                repairs.tangents += 1;
                n.any_orthonormal_vector().extend(w)
            }
        })
        .collect();
    (normals, tangents, repairs)
}

/// `name` as a URI path segment (RFC 3986): unreserved characters as they are, every other
/// byte of its UTF-8 as `%XX`, so `a b#1.bin` is written `a%20b%231.bin`.
fn uri_segment(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    for b in name.bytes() {
        if b.is_ascii_alphanumeric() || b"-._~".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// Writes `mesh` (positions, normals, texture coordinates, tangents, indices) as glTF 2.0: a
/// `.glb`, or a `.gltf` with its buffer in a `.bin` file beside it. Both written atomically.
pub fn save_gltf(path: &Path, mesh: &Mesh) -> Result<GltfRepairs, IoError> {
    let mut set = FileSet::new(&[]);
    let repairs = save_gltf_into(&mut set, path, mesh, None)?;
    set.commit()?;
    Ok(repairs)
}

/// [`save_gltf`] into a [`FileSet`]: the `.gltf` and its `.bin`, or the `.glb`. Normals and
/// tangents the format would call invalid are repaired and counted ([`GltfRepairs`]). With
/// `normal_texture` (a PNG file's bytes, in glTF's convention: green up, see
/// `bumpmap_math::YConvention::YUp`), the mesh gets a material whose `normalTexture` it is,
/// carried inside the buffer.
pub fn save_gltf_into(
    set: &mut FileSet,
    path: &Path,
    mesh: &Mesh,
    normal_texture: Option<&[u8]>,
) -> Result<GltfRepairs, IoError> {
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    if ext != "gltf" && ext != "glb" {
        return Err(IoError::UnsupportedOutput { path: path.to_path_buf(), expected: ".gltf or .glb" });
    }
    let (normals, tangents, repairs) = repaired(mesh);
    let n = mesh.positions.len();
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut push = |bytes: Vec<u8>, target: u32| {
        let offset = bin.len();
        bin.extend_from_slice(&bytes);
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let target = if target == 0 { String::new() } else { format!(r#","target":{target}"#) };
        views.push(format!(r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{}{target}}}"#, bytes.len()));
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
        add("NORMAL", "VEC3", floats(&mut normals.iter().flat_map(|v| v.to_array())), &mut push);
    }
    if !mesh.texcoords.is_empty() {
        add("TEXCOORD_0", "VEC2", floats(&mut mesh.texcoords.iter().flat_map(|v| v.to_array())), &mut push);
    }
    if !mesh.tangents.is_empty() {
        let tangents = &mut tangents.iter().flat_map(|t| t.truncate().extend(gltf_handedness(t.w)).to_array());
        add("TANGENT", "VEC4", floats(tangents), &mut push);
    }
    let index_view = accessors.len();
    push(mesh.indices.iter().flatten().flat_map(|i| i.to_le_bytes()).collect(), 34963);
    accessors.push(format!(
        r#"{{"bufferView":{index_view},"componentType":5125,"count":{},"type":"SCALAR"}}"#,
        3 * mesh.indices.len()
    ));
    let bin_name = format!("{}.bin", path.file_stem().unwrap_or_default().to_string_lossy());
    let uri = if ext == "gltf" { format!(r#","uri":"{}""#, uri_segment(&bin_name)) } else { String::new() };
    // A normal map travels inside the buffer, so the asset is one self-contained thing.
    let (material, textures) = match normal_texture {
        Some(png) => {
            let image_view = index_view + 1;
            push(png.to_vec(), 0);
            (
                r#","material":0"#.to_string(),
                format!(
                    r#","materials":[{{"name":"bumpmap","normalTexture":{{"index":0}},"pbrMetallicRoughness":{{"metallicFactor":0.0,"roughnessFactor":0.6}}}}],"textures":[{{"source":0,"sampler":0}}],"samplers":[{{"magFilter":9729,"minFilter":9987,"wrapS":10497,"wrapT":10497}}],"images":[{{"bufferView":{image_view},"mimeType":"image/png"}}]"#
                ),
            )
        }
        None => (String::new(), String::new()),
    };
    let json = format!(
        r#"{{"asset":{{"version":"2.0","generator":"bumpmap"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"meshes":[{{"primitives":[{{"attributes":{{{}}},"indices":{index_view}{material}}}]}}],"buffers":[{{"byteLength":{}{uri}}}],"bufferViews":[{}],"accessors":[{}]{textures}}}"#,
        attributes.join(","),
        bin.len(),
        views.join(","),
        accessors.join(",")
    );
    if ext == "gltf" {
        set.write(&path.with_file_name(&bin_name), |w| w.write_all(&bin))?;
        set.write(path, |w| w.write_all(json.as_bytes()))?;
        return Ok(repairs);
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
    })?;
    Ok(repairs)
}
