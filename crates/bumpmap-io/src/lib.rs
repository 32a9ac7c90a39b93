//! The only crate that knows file formats.
//!
//! Height fields and colour images in (anything `image` decodes, with size limits checked
//! before decoding), PNG out, DDS and KTX2 containers for mip chains and cube maps, OBJ and
//! glTF meshes. Every write goes to a temporary file in the destination folder and is renamed
//! into place, so a failure never leaves a partial file, and no write may replace an input.

pub mod atomic;
pub mod error;
mod gltf_read;
pub mod image_file;
pub mod mesh_file;
pub mod texture_file;

pub use error::IoError;
pub use image_file::{
    Channel, DecodeLimits, HeightSource, load_height_field, load_rgba8, read_height_field, read_rgba8,
};
pub use mesh_file::{
    LoadedMesh, MeshFormat, MeshOptions, ObjTexcoords, load_mesh, load_mesh_with, read_mesh, save_gltf,
};
