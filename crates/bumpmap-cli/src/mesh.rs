//! Meshes for `render --scene mesh:FILE` and `bumpmap tangents`.

use std::path::{Path, PathBuf};

use bumpmap_io::atomic::{FileSet, ensure_not_input};
use bumpmap_math::mesh::Mesh;
use bumpmap_math::tangent::{TangentMode, TangentOptions, generate_tangents};

use crate::args::{TangentModeArg, TangentsArgs};
use crate::error::CliError;

fn mesh_err(path: &Path, e: impl std::fmt::Display) -> CliError {
    CliError::Path { path: path.to_path_buf(), reason: e.to_string() }
}

/// Loads a mesh and makes sure it has tangents (ours, generated, when the file has none).
pub fn load_for_render(path: &Path) -> Result<Mesh, CliError> {
    let loaded = bumpmap_io::load_mesh(path)?;
    if loaded.had_tangents {
        return Ok(loaded.mesh);
    }
    let (mesh, _) = generate_tangents(&loaded.mesh, &TangentOptions::default()).map_err(|e| mesh_err(path, e))?;
    Ok(mesh)
}

/// `bumpmap tangents IN -o OUT`: generate tangents and write glTF with a TANGENT attribute.
pub fn run(args: &TangentsArgs) -> Result<(), CliError> {
    ensure_not_input(&args.output, &[&args.input])?;
    let ext = args.output.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    if !matches!(ext.as_deref(), Some("gltf") | Some("glb")) {
        return Err(
            bumpmap_io::IoError::UnsupportedOutput { path: args.output.clone(), expected: ".gltf or .glb" }.into()
        );
    }
    let loaded = bumpmap_io::load_mesh(&args.input)?;
    if !(0.0..=180.0).contains(&args.split_angle) {
        return Err(CliError::Path {
            path: args.input.clone(),
            reason: format!("--split-angle must be in [0, 180], got {}", args.split_angle),
        });
    }
    let options = TangentOptions {
        mode: match args.mode {
            TangentModeArg::Ours => TangentMode::Ours,
            TangentModeArg::Mikktspace => TangentMode::MikkTSpace,
        },
        split_angle_degrees: args.split_angle,
    };
    let (mesh, report) = generate_tangents(&loaded.mesh, &options).map_err(|e| mesh_err(&args.input, e))?;
    // The outputs (a .gltf and its .bin, or a .glb) replace none of the files read, the
    // input's buffer files included, and land together or not at all.
    let sources: Vec<&Path> = loaded.sources.iter().map(PathBuf::as_path).collect();
    let mut set = FileSet::new(&sources);
    bumpmap_io::mesh_file::save_gltf_into(&mut set, &args.output, &mesh)?;
    set.commit()?;
    println!(
        "{}: {} triangles, {} vertices in, {} out{}",
        args.input.display(),
        mesh.triangle_count(),
        loaded.mesh.vertex_count(),
        mesh.vertex_count(),
        if loaded.had_normals { "" } else { " (normals computed: the file had none)" }
    );
    println!("  degenerate in texture space: {} triangles", report.degenerate_uv);
    println!("  degenerate in space:         {} triangles", report.degenerate_geometry);
    println!("  mirrored (w = -1):           {} triangles", report.mirrored);
    println!("  vertices split:              {}", report.vertices_split);
    println!("wrote {}", args.output.display());
    Ok(())
}
