//! The only crate that knows file formats.
//!
//! - [`image_file`]: height fields and colour images in (anything `image` decodes, with size
//!   limits checked before decoding), PNG out;
//! - [`texture_file`]: DDS and KTX2 containers out, for mip chains and cube maps;
//! - [`texture_read`]: normal maps in with the levels they carry (PNG, DDS, KTX2, BC5/BC7);
//! - [`height_file`]: heights as geometry out and in, every level, with their min–max levels;
//! - [`mesh_file`]: OBJ and glTF meshes in (with a glTF's material textures), glTF out —
//!   `obj_read`, `gltf_read`, `gltf_mesh` and `gltf_write` behind it;
//! - [`atomic`]: every write goes to a temporary file in the destination folder and is renamed
//!   into place with the rest of its set, so a failure never leaves a partial file, and no
//!   write may replace an input;
//! - [`error`]: every message names the file.
//!
//! What this crate does not do: interpret what it reads (a normal map's green, a height's
//! units) beyond what the format itself says; that is `bumpmap-math`'s.

#![warn(missing_docs)]

pub mod atomic;
pub mod error;
mod gltf_read;
pub mod gray_file;
pub mod height_file;
pub mod horizon_file;
pub mod image_file;
pub mod mesh_file;
pub mod siblings;
pub mod texture_file;
pub mod texture_read;

pub use error::IoError;
pub use image_file::{
    Channel, DecodeLimits, HeightSource, PngLayout, load_height_field, load_rgba8, png_file_bytes, read_height_field,
    read_rgba8,
};
pub use mesh_file::{
    LoadedMesh, MaterialTexture, MeshFormat, MeshMaterial, MeshOptions, MeshPart, ObjTexcoords, TextureSampler,
    TextureTransform, load_mesh, load_mesh_with, read_mesh, save_gltf,
};
pub use texture_read::{
    AnyTexture, StoredLevels, StoredTexture, declared_size, load_any_texture, load_texture, load_texture_chain,
    load_texture_within, read_any_texture, read_texture,
};
