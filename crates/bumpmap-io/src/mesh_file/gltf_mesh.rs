//! A glTF document's meshes as one mesh of parts: the scene's nodes place each instance (its
//! own copy, in world space; a mirroring transform turns the winding and the tangents'
//! handedness), and every triangle primitive of every instance becomes a [`MeshPart`] with its
//! own material. Triangle strips and fans become lists; points and lines are left out with a
//! note. Each part's texture coordinates are the set its material's textures read, through
//! their `KHR_texture_transform` (`gltf_material`); a part without that set gets zeros.
//!
//! What this module does not do: check the container, buffers and accessors (`gltf_read` did),
//! or interpret a texture's texels (green up, unit length: `bumpmap_math::imported`).

use std::path::Path;

use bumpmap_math::mesh::{MAX_ELEMENTS, Mesh, MeshError};
use glam::{Vec2, Vec3, Vec4};

use super::gltf_material::{self, MaterialReads, TextureRead};
use super::{LoadedMesh, MeshOptions, MeshPart, gltf_handedness, mesh_err};
use crate::error::IoError;

/// The meshes to read and the world transform of each: the default scene's nodes (or the
/// first scene's; or, with no scene, every node that is no other's child), each mesh once per
/// node that holds it, and the node's name (its mesh's where it has none, else `node N`). A
/// file with no nodes gives its meshes in local space, each named as a mesh (`mesh N`).
fn instances(path: &Path, doc: &gltf::Document) -> Result<Vec<(usize, glam::Mat4, String)>, IoError> {
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    if nodes.is_empty() {
        let name = |m: &gltf::Mesh| m.name().map_or_else(|| format!("mesh {}", m.index()), str::to_string);
        return Ok(doc.meshes().map(|m| (m.index(), glam::Mat4::IDENTITY, name(&m))).collect());
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
    // Depth-first, each node visited once: glTF's nodes form disjoint strict trees (glTF 2.0
    // §3.5.3), so a node reached twice (a cycle, a child listed twice, a child of two parents)
    // is an error, not work that doubles with every level of a shared graph.
    let mut stack: Vec<(usize, glam::Mat4)> = roots.iter().rev().map(|&i| (i, glam::Mat4::IDENTITY)).collect();
    let mut visited = vec![false; nodes.len()];
    while let Some((i, parent)) = stack.pop() {
        if std::mem::replace(&mut visited[i], true) {
            return Err(mesh_err(
                path,
                format!(
                    "node {i} is reached twice (a cycle, a child listed twice or a child of two parents); glTF nodes form trees"
                ),
            ));
        }
        let node = &nodes[i];
        let local = glam::Mat4::from_cols_array_2d(&node.transform().matrix());
        if !local.is_finite() {
            return Err(mesh_err(
                path,
                format!(
                    "node {i}{} has a transform that is not finite ({:?})",
                    node.name().map_or(String::new(), |n| format!(" ('{n}')")),
                    node.transform().decomposed()
                ),
            ));
        }
        let world = parent * local;
        if let Some(mesh) = node.mesh() {
            let name = node.name().or(mesh.name()).map_or_else(|| format!("node {i}"), str::to_string);
            out.push((mesh.index(), world, name));
        }
        for c in node.children().collect::<Vec<_>>().into_iter().rev() {
            stack.push((c.index(), world));
        }
    }
    Ok(out)
}

pub(crate) fn from_gltf(
    path: &Path,
    mut file: crate::gltf_read::GltfFile,
    options: &MeshOptions,
) -> Result<LoadedMesh, IoError> {
    let document = file.document.clone();
    let instances = instances(path, &document)?;
    for accessor in document.accessors() {
        if accessor.count() > MAX_ELEMENTS {
            return Err(mesh_err(
                path,
                MeshError::TooLarge { what: "accessor count", count: accessor.count() as u64, max: MAX_ELEMENTS },
            ));
        }
        // A stride shorter than the element would make elements overlap (glTF 2.0 §3.6.2.4
        // wants it at least the element's size); the reader is not prepared for that.
        if let Some(stride) = accessor.view().and_then(|v| v.stride())
            && stride < accessor.size()
        {
            return Err(mesh_err(
                path,
                format!(
                    "accessor {} reads {}-byte elements through a bufferView whose byteStride is {stride}; it must be at least the element's size",
                    accessor.index(),
                    accessor.size()
                ),
            ));
        }
    }
    let meshes: Vec<gltf::Mesh> = document.meshes().collect();
    let (plans, mut notes) = material_plans(path, &document, &meshes, &instances, options)?;
    let mut mesh = Mesh::default();
    let mut parts = Vec::new();
    let (mut had_normals, mut had_tangents, mut any_texcoords) = (true, true, false);
    let mut turned = false;
    let mut left_out: Vec<(gltf::mesh::Mode, usize)> = Vec::new();
    let buffers = std::mem::take(&mut file.buffers);
    let mut objects = Vec::new();
    for (mesh_index, world_from_local, name) in &instances {
        let (mesh_index, world_from_local) = (*mesh_index, *world_from_local);
        let first = mesh.indices.len();
        let gmesh = &meshes[mesh_index];
        // Normals by the inverse transpose; a mirroring transform (negative determinant)
        // turns the winding and the tangent frame's handedness around (glTF 2.0 §3.7.4).
        let linear = glam::Mat3::from_mat4(world_from_local);
        let normal_matrix = linear.inverse().transpose();
        let mirrored = linear.determinant() < 0.0;
        for prim in gmesh.primitives() {
            let mode = prim.mode();
            if !matches!(
                mode,
                gltf::mesh::Mode::Triangles | gltf::mesh::Mode::TriangleStrip | gltf::mesh::Mode::TriangleFan
            ) {
                match left_out.iter_mut().find(|(m, _)| *m == mode) {
                    Some((_, n)) => *n += 1,
                    None => left_out.push((mode, 1)),
                }
                continue;
            }
            let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d[..]));
            let positions: Vec<Vec3> = reader
                .read_positions()
                .ok_or_else(|| mesh_err(path, format!("mesh {mesh_index} has a primitive without POSITION")))?
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
            let material = prim.material().index().and_then(|i| plans.iter().position(|p| p.index == i));
            let read = material.map_or_else(TextureRead::default, |m| plans[m].read);
            turned |= read.transform.turns_or_mirrors();
            let texcoords: Vec<Vec2> = reader
                .read_tex_coords(read.set)
                .map(|r| r.into_f32().map(|uv| read.transform.apply(Vec2::from(uv))).collect())
                .unwrap_or_default();
            let tangents: Vec<Vec4> = reader
                .read_tangents()
                .map(|r| {
                    r.map(|t| {
                        // Not finite stays so, for the mesh's check to name it.
                        let xyz = linear * Vec3::new(t[0], t[1], t[2]);
                        let xyz = if xyz.is_finite() { xyz.normalize_or_zero() } else { xyz };
                        let w = gltf_handedness(t[3]);
                        xyz.extend(if mirrored { -w } else { w })
                    })
                    .collect()
                })
                .unwrap_or_default();
            // Linear RGB(A), normalized integers to [0, 1], RGB with alpha 1 (glTF 2.0 §3.7.2.1).
            let colors: Vec<Vec4> =
                reader.read_colors(0).map(|r| r.into_rgba_f32().map(Vec4::from).collect()).unwrap_or_default();
            if !colors.is_empty() && colors.len() != n {
                return Err(mesh_err(
                    path,
                    format!("mesh {mesh_index}: COLOR_0 has {} entries for {n} vertices", colors.len()),
                ));
            }
            let listed: Vec<u32> = match reader.read_indices() {
                Some(r) => r.into_u32().collect(),
                None => (0..n as u32).collect(),
            };
            let indices = triangle_list(mode, &listed);
            if mode == gltf::mesh::Mode::Triangles && !listed.len().is_multiple_of(3) {
                return Err(mesh_err(
                    path,
                    format!("mesh {mesh_index}: {} indices is not a whole number of triangles", listed.len()),
                ));
            }
            if let Some(&bad) = listed.iter().find(|&&i| i as usize >= n) {
                return Err(mesh_err(
                    path,
                    format!("mesh {mesh_index}: index {bad} is out of range for a primitive of {n} vertices"),
                ));
            }
            if indices.len() + mesh.indices.len() > MAX_ELEMENTS {
                return Err(mesh_err(
                    path,
                    MeshError::TooLarge {
                        what: "triangles (all instances)",
                        count: (indices.len() + mesh.indices.len()) as u64,
                        max: MAX_ELEMENTS,
                    },
                ));
            }
            let textured = texcoords.len() == n;
            any_texcoords |= textured;
            had_normals &= normals.len() == n;
            had_tangents &= tangents.len() == n;
            mesh.positions.extend(positions);
            mesh.normals.extend(normals);
            if textured {
                mesh.texcoords.extend(texcoords);
            } else {
                mesh.texcoords.extend(std::iter::repeat_n(Vec2::ZERO, n));
            }
            mesh.tangents.extend(tangents);
            // White for the vertices of primitives without colours, once one has them.
            if !colors.is_empty() {
                mesh.colors.resize(base as usize, Vec4::ONE);
                mesh.colors.extend(colors);
            } else if !mesh.colors.is_empty() {
                mesh.colors.resize(mesh.positions.len(), Vec4::ONE);
            }
            let start = mesh.indices.len();
            mesh.indices.extend(indices.into_iter().map(|t| {
                if mirrored { [base + t[0], base + t[2], base + t[1]] } else { [base + t[0], base + t[1], base + t[2]] }
            }));
            parts.push(MeshPart { triangles: start..mesh.indices.len(), material, textured });
        }
        objects.push((name.clone(), first..mesh.indices.len()));
    }
    for (mode, count) in &left_out {
        notes.push(format!("{count} {mode:?} primitive(s) left out: only triangles are drawn"));
    }
    if parts.is_empty() {
        return Err(mesh_err(
            path,
            if left_out.is_empty() {
                "the scene holds no mesh primitives: nothing to draw".to_string()
            } else {
                format!("the scene holds no triangles, only {}", notes.last().map_or("", String::as_str))
            },
        ));
    }
    if !had_normals {
        mesh.normals.clear();
    }
    if !any_texcoords {
        mesh.texcoords.clear();
    }
    if !had_tangents {
        mesh.tangents.clear();
    }
    if had_tangents && turned {
        // The file's tangents follow the untransformed coordinates' +s; new ones follow the
        // texture as it is drawn.
        mesh.tangents.clear();
        had_tangents = false;
        notes.push(
            "the file's TANGENT attributes are set aside: a KHR_texture_transform turns or mirrors the texture, so tangents are made from the transformed coordinates"
                .into(),
        );
    }
    let untextured = parts.iter().filter(|p| !p.textured).count();
    if any_texcoords && untextured > 0 {
        notes.push(format!(
            "{untextured} of {} primitive(s) lack the texture coordinates their material reads: drawn unbumped and untextured",
            parts.len()
        ));
    }
    for e in document.extensions_used().filter(|e| *e != "KHR_texture_transform") {
        notes.push(format!("extension {e} is not read"));
    }
    file.buffers = buffers;
    let materials: Vec<gltf::Material> = document.materials().collect();
    let mut read = Vec::with_capacity(plans.len());
    for plan in &plans {
        read.push(gltf_material::read(
            path,
            &mut file,
            &materials[plan.index],
            &plan.reads,
            plan.read.set,
            options,
            &mut notes,
        )?);
    }
    let mut sources = vec![path.to_path_buf()];
    sources.extend(file.files);
    Ok(LoadedMesh { mesh, had_normals, had_tangents, sources, materials: read, parts, objects, notes })
}

/// A glTF triangle primitive's indices as a list of triangles (glTF 2.0 §3.7.2.1): a strip's
/// triangle i is (i, i + 1 + i % 2, i + 2 − i % 2), a fan's (i + 1, i + 2, 0).
fn triangle_list(mode: gltf::mesh::Mode, listed: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        gltf::mesh::Mode::TriangleStrip => (0..listed.len().saturating_sub(2))
            .map(|i| [listed[i], listed[i + 1 + i % 2], listed[i + 2 - i % 2]])
            .collect(),
        gltf::mesh::Mode::TriangleFan => {
            (0..listed.len().saturating_sub(2)).map(|i| [listed[i + 1], listed[i + 2], listed[0]]).collect()
        }
        _ => listed.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

/// A material the parts draw with: its index in the file, its texture reads, and the set and
/// transform the mesh is read with for it.
struct MaterialPlan {
    index: usize,
    reads: MaterialReads,
    read: TextureRead,
}

/// The materials the instances' primitives use, in order of first use, each checked; and notes
/// on what they ask for that is not drawn (each note once).
fn material_plans(
    path: &Path,
    doc: &gltf::Document,
    meshes: &[gltf::Mesh],
    instances: &[(usize, glam::Mat4, String)],
    options: &MeshOptions,
) -> Result<(Vec<MaterialPlan>, Vec<String>), IoError> {
    let materials: Vec<gltf::Material> = doc.materials().collect();
    let mut plans: Vec<MaterialPlan> = Vec::new();
    let mut notes = Vec::new();
    // What is not drawn, each kind once, with every material that asked for it.
    let mut left_out: Vec<(&'static str, Vec<String>)> = Vec::new();
    for &(m, _, _) in instances {
        for prim in meshes[m].primitives() {
            let Some(index) = prim.material().index() else { continue };
            if plans.iter().any(|p| p.index == index) {
                continue;
            }
            let material = &materials[index];
            let name = gltf_material::material_name(material);
            for what in gltf_material::check(path, material)? {
                match left_out.iter_mut().find(|(w, _)| *w == what) {
                    Some((_, names)) => names.push(name.clone()),
                    None => left_out.push((what, vec![name.clone()])),
                }
            }
            let reads = gltf_material::reads(path, doc, material)?;
            let (read, note) = gltf_material::mesh_read(&reads, options, &name);
            notes.extend(note);
            plans.push(MaterialPlan { index, reads, read });
        }
    }
    notes.extend(left_out.into_iter().map(|(what, names)| {
        format!("{what}: not drawn by a Blinn–Phong bump renderer (materials {})", names.join(", "))
    }));
    Ok((plans, notes))
}
