//! A glTF document's meshes as one mesh: the scene's nodes place each instance (its own copy,
//! in world space; a mirroring transform turns the winding and the tangents' handedness), only
//! triangle lists are read, and every primitive is merged. With [`MeshOptions`] asking for
//! them, the first primitive's material gives its normal and base-colour textures
//! ([`MeshMaterial`]); the mesh is then read with the normal texture's `TEXCOORD_n`.
//!
//! What this module does not do: check the container, buffers and accessors (`gltf_read` did),
//! or interpret a texture's texels (green up, unit length: `bumpmap_math::imported`).

use std::path::Path;

use bumpmap_math::mesh::{MAX_ELEMENTS, Mesh, MeshError};
use glam::{Vec2, Vec3, Vec4};

use crate::error::IoError;
use crate::mesh_file::{LoadedMesh, MaterialTexture, MeshMaterial, MeshOptions, gltf_handedness, mesh_err};

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
        let world = parent * glam::Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            out.push((mesh.index(), world));
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
    let (material, tex_coord, mut notes) = chosen_material(&document, &instances, options);
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
    let mut mesh = Mesh::default();
    let (mut had_normals, mut had_tangents, mut has_texcoords) = (true, true, true);
    let meshes: Vec<gltf::Mesh> = document.meshes().collect();
    let buffers = std::mem::take(&mut file.buffers);
    for &(mesh_index, world_from_local) in &instances {
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
                reader.read_tex_coords(tex_coord).map(|r| r.into_f32().map(Vec2::from).collect()).unwrap_or_default();
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
    if material.is_some() && !has_texcoords && tex_coord > 0 {
        return Err(mesh_err(
            path,
            format!("the material's textures read TEXCOORD_{tex_coord}, which not every primitive has"),
        ));
    }
    file.buffers = buffers;
    let material = match material {
        Some(m) => Some(read_material(path, &mut file, &m, tex_coord, options, &mut notes)?),
        None => None,
    };
    let mut sources = vec![path.to_path_buf()];
    sources.extend(file.files);
    Ok(LoadedMesh { mesh, had_normals, had_tangents, sources, material, notes })
}

/// The material the mesh is drawn with — the first primitive's, in the order the instances are
/// read — the texture-coordinate set to read (that of the normal texture if it is read, else
/// that of the base colour if it is read, else 0), and notes on what else the file asked for.
fn chosen_material<'a>(
    doc: &'a gltf::Document,
    instances: &[(usize, glam::Mat4)],
    options: &MeshOptions,
) -> (Option<gltf::Material<'a>>, u32, Vec<String>) {
    let mut notes = Vec::new();
    let meshes: Vec<gltf::Mesh> = doc.meshes().collect();
    let mut used: Vec<Option<usize>> = Vec::new();
    for &(m, _) in instances {
        for prim in meshes[m].primitives() {
            let index = prim.material().index();
            if !used.contains(&index) {
                used.push(index);
            }
        }
    }
    let chosen = used.first().copied().flatten().and_then(|i| doc.materials().nth(i));
    if used.len() > 1 {
        notes.push(format!(
            "the primitives use {} materials; all are drawn with the first's ({})",
            used.len(),
            chosen.as_ref().map_or("none".into(), material_name)
        ));
    }
    let Some(material) = chosen else { return (None, 0, notes) };
    let normal_set = material.normal_texture().filter(|_| options.read_normal_texture).map(|t| t.tex_coord());
    let color_set = material
        .pbr_metallic_roughness()
        .base_color_texture()
        .filter(|_| options.read_base_color_texture)
        .map(|t| t.tex_coord());
    let set = normal_set.or(color_set).unwrap_or(0);
    if let (Some(n), Some(c)) = (normal_set, color_set)
        && n != c
    {
        notes.push(format!(
            "the baseColorTexture reads TEXCOORD_{c} but the normalTexture TEXCOORD_{n}; both are drawn with TEXCOORD_{n}"
        ));
    }
    if doc.extensions_used().any(|e| e == "KHR_texture_transform") {
        notes.push("KHR_texture_transform is not applied: textures are drawn untransformed".into());
    }
    (Some(material), set, notes)
}

fn material_name(m: &gltf::Material) -> String {
    match (m.name(), m.index()) {
        (Some(n), _) => format!("'{n}'"),
        (None, Some(i)) => format!("material {i}"),
        (None, None) => "the default material".into(),
    }
}

/// Reads the textures `options` asks for of `material`.
fn read_material(
    path: &Path,
    file: &mut crate::gltf_read::GltfFile,
    material: &gltf::Material,
    tex_coord: u32,
    options: &MeshOptions,
    notes: &mut Vec<String>,
) -> Result<MeshMaterial, IoError> {
    let texture = |file: &mut crate::gltf_read::GltfFile, texture: gltf::Texture, what: &str, scale: f32| {
        let image = texture.source();
        let what = format!("{what} (image {})", image.index());
        // Errors name the glTF and the texture, then the image file's own error.
        let named = |e: IoError| match e {
            IoError::Mesh { .. } => e,
            other => mesh_err(path, format!("{what}: {other}")),
        };
        let (bytes, source) = file.image_bytes(path, &image, &what).map_err(named)?;
        let limits = crate::image_file::DecodeLimits::default();
        let decoded = crate::texture_read::read_texture(&bytes, &source, &limits).map_err(named)?;
        Ok::<_, IoError>(MaterialTexture { texture: decoded, scale, source })
    };
    let normal = match material.normal_texture() {
        Some(n) if options.read_normal_texture => Some(texture(file, n.texture(), "normalTexture", n.scale())?),
        _ => None,
    };
    let pbr = material.pbr_metallic_roughness();
    let base_color = match pbr.base_color_texture() {
        Some(c) if options.read_base_color_texture => Some(texture(file, c.texture(), "baseColorTexture", 1.0)?),
        _ => None,
    };
    if material.emissive_texture().is_some() || material.occlusion_texture().is_some() {
        notes.push("the material's occlusion and emissive textures are not drawn".into());
    }
    Ok(MeshMaterial {
        name: material_name(material),
        normal,
        base_color,
        base_color_factor: pbr.base_color_factor(),
        tex_coord,
    })
}
