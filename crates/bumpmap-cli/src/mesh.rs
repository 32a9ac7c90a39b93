//! Meshes for `render --scene mesh:FILE` and `bumpmap tangents`.

use std::path::{Path, PathBuf};

use bumpmap_io::MeshOptions;
use bumpmap_io::atomic::{FileSet, ensure_not_input};
use bumpmap_math::tangent::{TangentOptions, generate_tangents};

use crate::args::TangentsArgs;
use crate::error::CliError;
use bumpmap_words::maps::tangent_error;

fn mesh_err(path: &Path, e: impl std::fmt::Display) -> CliError {
    CliError::Path { path: path.to_path_buf(), reason: e.to_string() }
}

/// `bumpmap tangents IN -o OUT`: generate tangents and write glTF with a TANGENT attribute.
pub fn run(args: &TangentsArgs) -> Result<(), CliError> {
    let options = tangent_options(args)?;
    ensure_not_input(&args.output, &[&args.input])?;
    let ext = args.output.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    if !matches!(ext.as_deref(), Some("gltf") | Some("glb")) {
        return Err(
            bumpmap_io::IoError::UnsupportedOutput { path: args.output.clone(), expected: ".gltf or .glb" }.into()
        );
    }
    let loaded = bumpmap_io::load_mesh_with(
        &args.input,
        &MeshOptions { allow_outside_paths: args.allow_outside_paths, obj_texcoords: args.obj_v, ..Default::default() },
    )?;
    let (mesh, report) = generate_tangents(&loaded.mesh, &options).map_err(|e| mesh_err(&args.input, e))?;
    // The outputs (a .gltf and its .bin, or a .glb) replace none of the files read, the
    // input's buffer files included, and land together or not at all.
    let texture = args.normal_map.as_deref().map(read_normal_texture).transpose()?;
    let mut sources: Vec<&Path> = loaded.sources.iter().map(PathBuf::as_path).collect();
    sources.extend(args.normal_map.as_deref());
    let mut set = FileSet::new(&sources);
    let repaired = bumpmap_io::mesh_file::save_gltf_into(&mut set, &args.output, &mesh, texture.as_deref())?;
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
    let mirrored = bumpmap_io::mesh_file::mirrored_as_displayed(&mesh);
    println!("  mirrored (glTF w = -1):      {mirrored} triangles");
    println!("  vertices split:              {}", report.vertices_split);
    if repaired.normals + repaired.tangents > 0 {
        println!(
            "  repaired for glTF:           {} normals (zero or not finite: made from the faces), {} tangents (made perpendicular to the normal)",
            repaired.normals, repaired.tangents
        );
    }
    println!("wrote {}", args.output.display());
    Ok(())
}

/// The tangent options `args` give, `--split-angle` checked.
pub fn tangent_options(args: &TangentsArgs) -> Result<TangentOptions, CliError> {
    let options = args.tangents.0;
    options.check().map_err(tangent_error)?;
    Ok(options)
}

/// The bytes of a PNG normal map for a glTF material, after decoding it once to be sure it is
/// one (glTF carries PNG or JPEG; a normal map must not be JPEG's lossy colour).
fn read_normal_texture(path: &Path) -> Result<Vec<u8>, CliError> {
    use std::io::Read as _;
    // The glTF buffer it travels in holds at most 1 GiB; the signature is read before the rest.
    const MAX_BYTES: u64 = 1 << 30;
    let read_err = |source| bumpmap_io::IoError::Read { path: path.to_path_buf(), source };
    let meta = std::fs::metadata(path).map_err(read_err)?;
    if !meta.is_file() {
        return Err(mesh_err(path, "not a regular file (a folder, a FIFO or a device)"));
    }
    if meta.len() > MAX_BYTES {
        return Err(mesh_err(
            path,
            format!("{} bytes; a normal map packed into a glTF may have {MAX_BYTES}", meta.len()),
        ));
    }
    let mut file = std::fs::File::open(path).map_err(read_err)?;
    let mut bytes = vec![0u8; 8];
    if file.read_exact(&mut bytes).is_err() || bytes != b"\x89PNG\r\n\x1a\n" {
        return Err(mesh_err(path, "--normal-map must be a PNG file (glTF carries PNG or JPEG, and JPEG is lossy)"));
    }
    file.take(MAX_BYTES).read_to_end(&mut bytes).map_err(read_err)?;
    bumpmap_io::read_rgba8(&bytes, path, &bumpmap_io::DecodeLimits::default())?;
    Ok(bytes)
}
