//! The demo's bake: a cube with rounded edges (HIGH) baked onto the plain cube with hard edges
//! and one UV island a face (LOW), by averaged rays and by explicit ones, and the figure of the
//! four side by side — HIGH, LOW with the averaged bake, LOW with the explicit one (a seam
//! along every hard edge), LOW without.

use std::path::Path;

use bumpmap::assets::{MeshLoad, load_mesh};
use bumpmap::bake::{BakeOutputs, BakeRequest, RayMode, bake_files};
use bumpmap::frame::draw_passes;
use bumpmap::{Light, Prepared, Renderer, SceneLight, TechniqueName, TechniqueOptions};
use bumpmap_io::image_file::{PngLayout, save_png};
use bumpmap_math::mesh::{Mesh, rounded_cube};
use bumpmap_math::tangent::generate_tangents;
use bumpmap_words::Error;
use bumpmap_words::frame::lib_err;
use glam::Vec3;

/// The figure (the README shows it).
pub const BAKE_FIGURE: &str = "bake_figure.png";

/// Each panel's side in pixels.
const SIDE: usize = 256;

/// Writes `bake/` (both meshes, both bakes, LOW with each as a GLB) and the figure into `out`;
/// returns the index's lines.
pub fn write(out: &Path, renderer: &mut Renderer) -> Result<String, Error> {
    let dir = out.join("bake");
    let with_tangents = |mesh: Mesh| -> Result<Mesh, Error> {
        Ok(generate_tangents(&mesh, &Default::default()).map_err(bumpmap_words::maps::tangent_error)?.0)
    };
    let (high, low) = (dir.join("high.glb"), dir.join("low.glb"));
    let mut set = bumpmap_io::atomic::FileSet::new(&[]);
    bumpmap_io::mesh_file::save_gltf_into(&mut set, &high, &with_tangents(rounded_cube(48, 0.2))?, None)?;
    bumpmap_io::mesh_file::save_gltf_into(&mut set, &low, &with_tangents(rounded_cube(1, 0.0))?, None)?;
    set.commit()?;
    let mut lines = String::new();
    for (rays, name) in [(RayMode::Averaged, "averaged"), (RayMode::Explicit, "explicit")] {
        let mut request = BakeRequest::default();
        request.options.width = 512;
        request.options.height = 512;
        request.options.rays = rays;
        (request.options.front, request.options.back) = (Some(0.3), Some(0.3));
        let outputs = BakeOutputs {
            normal_map: dir.join(format!("{name}_normal.png")),
            low: Some(dir.join(format!("low_{name}.glb"))),
            curvature: (rays == RayMode::Averaged).then(|| dir.join("curvature.png")),
            occlusion: (rays == RayMode::Averaged).then(|| dir.join("occlusion.png")),
            ..Default::default()
        };
        bake_files(&high, &low, &request, &outputs, &|_, _| {})
            .map_err(|e| bumpmap_words::bake::bake_error(e, &high, &low))?;
    }
    let panels = [
        (high.clone(), TechniqueName::NoBump),
        (dir.join("low_averaged.glb"), TechniqueName::SinglePass),
        (dir.join("low_explicit.glb"), TechniqueName::SinglePass),
        (low.clone(), TechniqueName::NoBump),
    ];
    let mut images = Vec::new();
    for (mesh, technique) in &panels {
        images.push(draw(renderer, mesh, *technique)?);
    }
    let mut rgb = Vec::with_capacity(4 * SIDE * SIDE * 3);
    for y in 0..SIDE {
        for image in &images {
            rgb.extend(image.texels[y * SIDE..(y + 1) * SIDE].iter().flat_map(|t| [t[0], t[1], t[2]]));
        }
    }
    save_png(&out.join(BAKE_FIGURE), 4 * SIDE, SIDE, PngLayout::Rgb8, &rgb)?;
    lines += &format!(
        "- `bake/high.glb`, `bake/low.glb`: a cube with rounded edges and the plain cube (hard edges, one UV island a face); \
`bake/averaged_normal.png` and `bake/explicit_normal.png`: the first baked onto the second by averaged and by explicit rays \
(`bumpmap bake bake/high.glb bake/low.glb -o … --decode per-vertex --extrude 0.3 --max-distance 0.3`), and `bake/low_averaged.glb`, \
`bake/low_explicit.glb`, the plain cube with each as its normalTexture (`bumpmap view --scene mesh:bake/low_averaged.glb`); \
`bake/curvature.png` (with `bake/curvature.range.json`) and `bake/occlusion.png`: the rounded cube's curvature and ambient occlusion \
baked with the averaged rays (`--curvature-out`, `--ao-out`)\n\
- `{BAKE_FIGURE}`: from left to right, the rounded cube; the plain cube with the averaged bake; with the explicit bake (a seam \
along every hard edge, where the two faces' rays part); the plain cube without\n"
    );
    Ok(lines)
}

/// `mesh` seen from a corner, three faces in view, by `technique` under one light, no decal.
fn draw(renderer: &mut Renderer, mesh: &Path, technique: TechniqueName) -> Result<bumpmap::Rgba8Image, Error> {
    let asset = load_mesh(mesh, &MeshLoad::default()).map_err(lib_err)?;
    let mut spec = asset.spec();
    spec.params.eye = Some(Vec3::new(3.2, -4.0, 2.6));
    spec.params.target = Some(Vec3::ZERO);
    spec.params.lights = vec![SceneLight::white(Light::Directional(Vec3::new(1.0, -0.6, 1.4).normalize()))];
    spec.params.default_decal = false;
    spec.params.specular = Vec3::splat(0.3);
    spec.params.shininess = 30.0;
    let prepared = Prepared::new(&spec, technique, &TechniqueOptions::default()).map_err(lib_err)?;
    let frame = draw_passes(renderer, &prepared.scene, &prepared.technique, SIDE, SIDE, false).map_err(lib_err)?;
    Ok(frame.image)
}
