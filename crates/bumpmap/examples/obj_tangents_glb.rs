//! An OBJ mesh gets MikkTSpace tangents (what Blender and glTF viewers expect) and is written as
//! a GLB with its TANGENT attribute, which the renderer then uses as the file's own.
//!
//! `cargo run --release -p bumpmap --example obj_tangents_glb [IN.obj [OUT.glb]]`

use std::path::PathBuf;

use bumpmap::assets::{MeshLoad, load_mesh};
use bumpmap::bumpmap_math::tangent::{TangentMode, TangentOptions, generate_tangents};

fn main() -> Result<(), bumpmap::Error> {
    let mut args = std::env::args().skip(1);
    let input = args.next().map_or_else(
        || PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/cube.obj")),
        PathBuf::from,
    );
    let out = args.next().map_or_else(|| PathBuf::from("out/examples/cube.glb"), PathBuf::from);
    let loaded = bumpmap::bumpmap_io::load_mesh(&input)?;
    let options = TangentOptions { mode: TangentMode::MikkTSpace, ..Default::default() };
    let (mesh, report) = generate_tangents(&loaded.mesh, &options)
        .map_err(|e| bumpmap::bumpmap_io::IoError::Mesh { path: input.clone(), reason: e.to_string() })?;
    bumpmap::bumpmap_io::save_gltf(&out, &mesh)?;

    let asset = load_mesh(&out, &MeshLoad::default())?;
    assert!(asset.tangents_from_file, "the GLB carries its tangents");
    println!(
        "wrote {}: {} triangles, {} vertices ({} split at seams), {} degenerate in texture space",
        out.display(),
        mesh.triangle_count(),
        mesh.vertex_count(),
        report.vertices_split,
        report.degenerate_uv
    );
    Ok(())
}
