//! An OBJ mesh gets MikkTSpace tangents (what Blender and glTF viewers expect) and is written as
//! a GLB with its TANGENT attribute, which the renderer then uses as the file's own: the brick
//! cube it draws on the CPU is held against its screenshot
//! (`examples/screenshots/obj_tangents_glb.png`) at 60 dB: the CPU's path is deterministic, and
//! the slack covers libm's sin and cos differing between machines (the CPU goldens allow 1/255
//! on 0.5 % of pixels, about 71 dB).
//!
//! `cargo run --release -p bumpmap --example obj_tangents_glb [IN.obj [OUT.glb]]`

use std::path::PathBuf;

use bumpmap::assets::{MeshLoad, load_mesh};
use bumpmap::bumpmap_math::tangent::{TangentMode, TangentOptions, generate_tangents};
use bumpmap::{BackendChoice, Renderer, TechniqueName};

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
    let image = Renderer::new(BackendChoice::Cpu)?.render(&asset.spec(), TechniqueName::SinglePass, 128, 128)?;
    let screenshot = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/screenshots/obj_tangents_glb.png");
    bumpmap_testkit::assert_screenshot(
        "obj_tangents_glb",
        screenshot.as_ref(),
        &image,
        60.0,
        "deterministic but for libm's sin and cos",
    );
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
