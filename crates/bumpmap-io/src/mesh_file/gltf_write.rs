//! glTF 2.0 out: a mesh with its TANGENT attribute as a `.glb`, or a `.gltf` with its `.bin`
//! beside it, written into a [`FileSet`] (all files or none). Normals and tangents glTF would
//! call invalid are repaired and counted; an optional PNG normal map travels inside the buffer
//! as the material's `normalTexture`.

use std::io::Write;
use std::path::Path;

use bumpmap_math::mesh::Mesh;
use glam::{Vec3, Vec4};

use super::gltf_handedness;
use crate::atomic::FileSet;
use crate::error::IoError;

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

/// The normals and tangents a glTF file gets for `mesh` (what [`save_gltf`] writes): unit
/// length, tangents perpendicular to the normals, and what had to be rebuilt. Tangents keep
/// this crate's `w` ([`gltf_handedness`] gives glTF's).
pub fn gltf_normals_and_tangents(mesh: &Mesh) -> (Vec<Vec3>, Vec<Vec4>, GltfRepairs) {
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
    let (normals, tangents, repairs) = gltf_normals_and_tangents(mesh);
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
    if !mesh.colors.is_empty() {
        add("COLOR_0", "VEC4", floats(&mut mesh.colors.iter().flat_map(|c| c.to_array())), &mut push);
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
