//! Mesh files: what a loaded mesh is, how a file is read, and which reader reads it.
//!
//! - `obj_read`: OBJ (via `tobj`), v flipped into this crate's texture space ([`ObjTexcoords`]);
//! - `gltf_read`: a glTF or GLB file read without trusting it (container, buffers, accessors);
//! - `gltf_mesh`: its scene's meshes placed by their node transforms and merged into one mesh,
//!   each primitive of each node a [`MeshPart`] of it with its own material ([`MeshMaterial`]);
//! - `gltf_material`: a material's texture reads (`texCoord`, `KHR_texture_transform`), checks
//!   and textures;
//! - `gltf_write`: glTF or GLB out, with a TANGENT attribute ([`save_gltf_into`]).
//!
//! glTF's texture coordinates are this crate's as they are; its TANGENT handedness is ours
//! negated ([`gltf_handedness`]), on the way in and out. A file without normals gets
//! area-weighted vertex normals (the documented fallback); one without texture coordinates
//! loads, but tangent generation then refuses it. Counts are checked against `MAX_ELEMENTS`
//! before any data is read.

mod gltf_material;
mod gltf_mesh;
mod gltf_write;
mod obj_read;

use std::path::{Path, PathBuf};

use bumpmap_math::mesh::{AlphaMode, Mesh};

use crate::error::IoError;
use crate::texture_read::StoredTexture;

pub use gltf_write::{GltfRepairs, gltf_normals_and_tangents, save_gltf, save_gltf_into};

/// A loaded mesh and what the file itself supplied.
#[derive(Clone, Debug, Default)]
pub struct LoadedMesh {
    /// The mesh, in the file's own units and axes (glTF node transforms applied).
    pub mesh: Mesh,
    /// Whether the file had normals (otherwise they were computed from the faces).
    pub had_normals: bool,
    /// Whether the file had tangents (glTF's TANGENT), now in [`Mesh::tangents`].
    pub had_tangents: bool,
    /// Every file read: the mesh file and, for glTF, its buffer and image files. An output must
    /// replace none of them.
    pub sources: Vec<PathBuf>,
    /// The glTF materials the parts draw with, each once (their textures read where
    /// [`MeshOptions`] asks for them). Empty for OBJ.
    pub materials: Vec<MeshMaterial>,
    /// Which triangles of [`LoadedMesh::mesh`] each glTF primitive (of each node that holds it)
    /// is, in the order read, and its material. Empty for OBJ: one part, no material.
    pub parts: Vec<MeshPart>,
    /// Each named object's triangles, in the order read: a glTF node that holds a mesh (the
    /// node's name, else its mesh's, else `node N`), or an OBJ object or group (`o` or `g`: the
    /// name tobj gives it). Empty for a mesh not read from a file.
    pub objects: Vec<(String, std::ops::Range<usize>)>,
    /// What the reader left out, in words (an alpha mode, a line primitive, …).
    pub notes: Vec<String>,
}

/// One glTF primitive of one node: a run of the merged mesh's triangles and its material.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshPart {
    /// Its triangles: a range of [`Mesh::indices`].
    pub triangles: std::ops::Range<usize>,
    /// Its material, an index into [`LoadedMesh::materials`]; `None` for glTF's default
    /// material (no textures, white, single-sided).
    pub material: Option<usize>,
    /// Whether it has the texture-coordinate set its material reads. Without it the part's
    /// texture coordinates are zeros and it can only be drawn unbumped and untextured.
    pub textured: bool,
}

/// What a glTF material gives a renderer.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshMaterial {
    /// How messages name it after the word "material": `'its name'`, else its index.
    pub name: String,
    /// `normalTexture`, with its `scale`.
    pub normal: Option<MaterialTexture>,
    /// `pbrMetallicRoughness.baseColorTexture`.
    pub base_color: Option<MaterialTexture>,
    /// `pbrMetallicRoughness.baseColorFactor` (linear RGBA; it multiplies the texture).
    pub base_color_factor: [f32; 4],
    /// The texture-coordinate set the mesh was read with (`TEXCOORD_n`): the normal texture's
    /// when it is read, else the base colour's when that is read, else 0.
    pub tex_coord: u32,
    /// `doubleSided`: back faces drawn, lit with the normal and the tangent frame reversed
    /// (glTF 2.0 §3.9.6); otherwise culled.
    pub double_sided: bool,
    /// The `KHR_texture_transform` already applied to the parts' texture coordinates (the
    /// normal texture's when it is read, else the base colour's), when it changes anything.
    pub texture_transform: Option<TextureTransform>,
    /// The sampler its textures are drawn with (the normal texture's when it is read, else the
    /// base colour's).
    pub sampler: TextureSampler,
    /// `alphaMode` with `alphaCutoff` (default 0.5).
    pub alpha_mode: AlphaMode,
    /// `occlusionTexture`, its `strength` as the scale; its red channel is the occlusion.
    pub occlusion: Option<MaterialTexture>,
    /// `emissiveTexture` (sRGB-encoded).
    pub emissive: Option<MaterialTexture>,
    /// `emissiveFactor` (linear; it multiplies the texture).
    pub emissive_factor: [f32; 3],
    /// `pbrMetallicRoughness.metallicRoughnessTexture`: roughness in green, metalness in blue.
    pub metallic_roughness: Option<MaterialTexture>,
    /// `pbrMetallicRoughness.roughnessFactor` (it multiplies the texture's green).
    pub roughness_factor: f32,
}

/// A glTF sampler as the file stores it: GL enums (`bumpmap_core::state` reads them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureSampler {
    /// `wrapS` (default `GL_REPEAT`, 10497).
    pub wrap_s: u32,
    /// `wrapT` (default `GL_REPEAT`).
    pub wrap_t: u32,
    /// `magFilter`, if given.
    pub mag_filter: Option<u32>,
    /// `minFilter`, if given.
    pub min_filter: Option<u32>,
}

impl Default for TextureSampler {
    /// A texture without a sampler: repeating, filters left to the renderer.
    fn default() -> Self {
        Self { wrap_s: 10497, wrap_t: 10497, mag_filter: None, min_filter: None }
    }
}

/// `KHR_texture_transform` on a texture reference: `uv' = T·R·S·uv`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureTransform {
    /// T's translation, in texture coordinates.
    pub offset: glam::Vec2,
    /// R's angle in radians, counter-clockwise in the image as displayed.
    pub rotation: f32,
    /// S's scale along u and v.
    pub scale: glam::Vec2,
    /// The texture-coordinate set it reads instead of the reference's own `texCoord`.
    pub tex_coord: Option<u32>,
}

impl Default for TextureTransform {
    /// The identity.
    fn default() -> Self {
        Self { offset: glam::Vec2::ZERO, rotation: 0.0, scale: glam::Vec2::ONE, tex_coord: None }
    }
}

/// One of a material's textures, decoded.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialTexture {
    /// The image's texels.
    pub texture: StoredTexture,
    /// `normalTexture.scale`, `occlusionTexture.strength` (1 for other textures).
    pub scale: f32,
    /// Where it came from: the image's file, or the glTF with the image's index.
    pub source: PathBuf,
    /// The glTF image's index: materials that share an image share it.
    pub image: usize,
}

pub(crate) fn mesh_err(path: &Path, reason: impl std::fmt::Display) -> IoError {
    IoError::Mesh { path: path.to_path_buf(), reason: reason.to_string() }
}

/// How a mesh file is read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshOptions {
    /// Let a glTF's buffer and image URIs lead outside its folder (absolute paths, `..`). Off by
    /// default: a glTF from elsewhere must not make the tool read arbitrary files.
    pub allow_outside_paths: bool,
    /// How an OBJ's `vt` become texture coordinates.
    pub obj_texcoords: ObjTexcoords,
    /// Read a glTF material's `normalTexture` (an error if it cannot be read).
    pub read_normal_texture: bool,
    /// Read a glTF material's `baseColorTexture`, and with it the other textures of its look:
    /// `occlusionTexture`, `emissiveTexture` and `metallicRoughnessTexture` (an error if one
    /// cannot be read).
    pub read_base_color_texture: bool,
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

bumpmap_math::named!(ObjTexcoords {
    FlipV => "flip": "v = 0 is the image's bottom row, as Blender, Maya and OBJ exporters write it",
    Keep => "keep": "v = 0 is the image's top row (OBJ files from tools that write glTF's convention)",
});

/// glTF's TANGENT handedness for this crate's `w`, and back (the map is its own inverse).
///
/// Here `w` makes `cross(N, T)·w` point along +t, down the image as displayed; glTF reads the
/// normal texture's +Y (up the image) along `cross(N, T)·w`, so its `w` is ours negated.
pub fn gltf_handedness(w: f32) -> f32 {
    -w
}

/// Triangles whose texture is mirrored as the image is displayed: glTF's handedness −1 at their
/// first corner (after splitting, a triangle's corners agree). This is what `bumpmap tangents`
/// and Python's `tangents` report as mirrored; the tangent report's own count
/// (`TangentReport::mirrored`, `w = −1` in this crate's texture space, whose t runs down the
/// image) counts the other triangles of a mesh read from a file.
pub fn mirrored_as_displayed(mesh: &Mesh) -> usize {
    mesh.indices.iter().filter(|t| gltf_handedness(mesh.tangents[t[0] as usize].w) < 0.0).count()
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
            obj_read::parse_obj(path, &bytes, options.obj_texcoords)?
        }
        MeshFormat::Gltf => {
            gltf_mesh::from_gltf(path, crate::gltf_read::read(path, options.allow_outside_paths)?, options)?
        }
    };
    finish(path, loaded)
}

/// A mesh file's bytes already in memory; `name` is the file errors name. A glTF read this
/// way has no folder, so only `data:` URIs and a GLB's own chunk supply its buffers and its
/// material's images (both textures are read). OBJ texture coordinates are flipped as
/// [`ObjTexcoords::FlipV`] says.
pub fn read_mesh(bytes: &[u8], name: &Path, format: MeshFormat) -> Result<LoadedMesh, IoError> {
    let options = MeshOptions { read_normal_texture: true, read_base_color_texture: true, ..Default::default() };
    let loaded = match format {
        MeshFormat::Obj => obj_read::parse_obj(name, bytes, ObjTexcoords::FlipV)?,
        MeshFormat::Gltf => gltf_mesh::from_gltf(
            name,
            crate::gltf_read::parse(name, bytes, crate::gltf_read::BufferFiles::None)?,
            &options,
        )?,
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
