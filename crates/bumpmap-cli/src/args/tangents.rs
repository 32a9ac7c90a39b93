//! `bumpmap tangents`' options.

use std::path::PathBuf;

use clap::Args;

use bumpmap_io::ObjTexcoords;

use bumpmap::option_table::TANGENTS;
use bumpmap_math::tangent::TangentOptions;

use crate::args::choice;
use crate::args::table::{Table, rows};

rows!(
    /// How tangent frames are made: the library's [`TANGENTS`] table.
    Tangents: TangentOptions = TANGENTS
);

/// `bumpmap tangents`.
#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap tangents model.obj -o model.glb\n  \
bumpmap tangents scan.gltf -o scan_tangents.gltf --mode mikktspace\n  \
bumpmap tangents model.obj --normal-map n.png -o model.glb   # a ready-to-view asset\n\n\
Reads OBJ, glTF or GLB (positions, normals, texture coordinates; normals are computed when \
missing; glTF node transforms applied; OBJ v flipped, see --obj-v). Writes positions, normals, \
TEXCOORD_0, TANGENT (VEC4, glTF's w = ±1 handedness) and indices, repairs normals and tangents \
glTF would call invalid, and reports degenerate, mirrored, split and repaired geometry.\n\n\
Limits: files and glTF buffers up to 1 GiB each, buffers read only from data: URIs, the GLB \
chunk or files inside the glTF's folder (see --allow-outside-paths), at most byteLength bytes; \
50,000,000 vertices, triangles or accessor elements; --mode mikktspace takes at most 10,000 \
triangle corners at one position (its time grows with their square).")]
pub struct TangentsArgs {
    /// Mesh file: .obj, .gltf or .glb
    pub input: PathBuf,
    /// Output: .gltf (with a .bin beside it) or .glb
    #[arg(short, long)]
    pub output: PathBuf,
    /// How the frames are made: the library's [`TANGENTS`] table.
    #[command(flatten)]
    pub tangents: Table<Tangents>,
    /// glTF only: let buffer URIs lead outside the glTF's folder (absolute paths, ..); off by default, so a downloaded glTF cannot make bumpmap read other files
    #[arg(long = "allow-outside-paths")]
    pub allow_outside_paths: bool,
    /// OBJ only: flip (v = 0 at the image's bottom, the OBJ convention) or keep the file's v
    #[arg(long = "obj-v", value_parser = choice::<ObjTexcoords>(), default_value = "flip")]
    pub obj_v: ObjTexcoords,
    /// A PNG normal map (green up, as `normalmap` writes by default) to pack into the output as the material's normalTexture: a ready-to-view asset
    #[arg(long = "normal-map")]
    pub normal_map: Option<PathBuf>,
}
