//! A bake is synced when the renderer, drawing LOW with its map, shades as HIGH does. Measured
//! here as the shading normals of both renders: each drawn three times, diffuse light only, one
//! directional light at a time; the three intensities of a pixel give its normal (photometric
//! stereo: I = L·n for the three light directions L), and the two renders' normals are compared
//! where both draw the surface.

use std::path::{Path, PathBuf};

use bumpmap::bake::{BakeOutputs, BakeRequest, TangentDecode, bake_files};
use bumpmap::frame::{FrameRequest, draw_frame, prepare_frame};
use bumpmap::option_table::{SCENE, find};
use bumpmap::options::Given;
use bumpmap::{BackendChoice, Renderer, Rgba8Image};
use bumpmap_math::surface::Surface;
use glam::{Mat3, Vec2, Vec3};

const SIZE: usize = 160;
const LIGHTS: [[f32; 3]; 3] = [[0.0, -1.0, 0.35], [0.8, -1.0, -0.25], [-0.8, -1.0, -0.25]];

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpmap-bake-synced-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `mesh` drawn by `technique` (a word, or `technique/decode`) from `eye` under the one
/// directional light `light`, diffuse only.
fn draw(mesh: &Path, technique: &str, eye: &str, light: [f32; 3]) -> Rgba8Image {
    let (technique, decode) = technique.split_once('/').map_or((technique, None), |(t, d)| (t, Some(d)));
    let mut request = FrameRequest { size: (SIZE, SIZE), backend: BackendChoice::Cpu, ..Default::default() };
    let scene = format!("mesh:{}", mesh.display());
    let light = format!("dir:{},{},{}", light[0], light[1], light[2]);
    for (name, text) in [
        ("scene", scene.as_str()),
        ("technique", technique),
        ("eye", eye),
        ("target", "0,0,0"),
        ("light", light.as_str()),
        ("decal", "none"),
        ("ambient", "0"),
        ("diffuse", "1"),
        ("specular", "0"),
        ("self-shadow", "off"),
    ] {
        let row = find(SCENE, name).unwrap_or_else(|| panic!("{name} is a row"));
        let value = row.parse_text(text).unwrap_or_else(|e| panic!("--{name} {text}: {e}"));
        row.set(&mut request, value).unwrap();
    }
    if let Some(decode) = decode {
        let row = find(SCENE, "decode").unwrap();
        row.set(&mut request, row.parse_text(decode).unwrap()).unwrap();
    }
    let prepared = prepare_frame(&request, &Given::default()).unwrap();
    let mut renderer = Renderer::new(BackendChoice::Cpu).unwrap();
    draw_frame(&mut renderer, &prepared, false).unwrap().image
}

/// Each pixel's shading normal from its three renders (`None` where one is dark: in shadow of a
/// light, or not the surface).
fn normals(mesh: &Path, technique: &str) -> Vec<Option<Vec3>> {
    normals_from(mesh, technique, "0,-4,0.6", LIGHTS)
}

/// [`normals`] seen from `eye` under `lights`.
fn normals_from(mesh: &Path, technique: &str, eye: &str, lights: [[f32; 3]; 3]) -> Vec<Option<Vec3>> {
    let images: Vec<Rgba8Image> = lights.iter().map(|l| draw(mesh, technique, eye, *l)).collect();
    let to_light = Mat3::from_cols_array_2d(&lights.map(|l| Vec3::from(l).normalize().to_array())).transpose();
    let inverse = to_light.inverse();
    (0..SIZE * SIZE)
        .map(|k| {
            let i =
                Vec3::new(images[0].texels[k][0] as f32, images[1].texels[k][0] as f32, images[2].texels[k][0] as f32)
                    / 255.0;
            (i.min_element() > 0.1).then(|| (inverse * i).normalize())
        })
        .collect()
}

/// Mean angle in degrees between the normals both have, away from either's silhouette, and how
/// many pixels that is.
fn mean_angle(a: &[Option<Vec3>], b: &[Option<Vec3>]) -> (f32, usize) {
    let inside = |n: &[Option<Vec3>], k: usize| {
        let (x, y) = ((k % SIZE) as i64, (k / SIZE) as i64);
        (-2..=2).all(|dy| {
            (-2..=2).all(|dx| {
                let (u, v) = (x + dx, y + dy);
                u >= 0 && v >= 0 && u < SIZE as i64 && v < SIZE as i64 && n[(v as usize) * SIZE + u as usize].is_some()
            })
        })
    };
    let angles: Vec<f32> = (0..SIZE * SIZE)
        .filter(|&k| inside(a, k) && inside(b, k))
        .map(|k| a[k].unwrap().dot(b[k].unwrap()).clamp(-1.0, 1.0).acos().to_degrees())
        .collect();
    (angles.iter().sum::<f32>() / angles.len().max(1) as f32, angles.len())
}

/// Bakes `high` onto `low` into `dir` as `NAME.png`, and returns `NAME.glb`: LOW with the map.
fn bake_into(dir: &Path, high: &Path, low: &Path, request: &BakeRequest, name: &str) -> PathBuf {
    let outputs = BakeOutputs {
        normal_map: dir.join(format!("{name}.png")),
        low: Some(dir.join(format!("{name}.glb"))),
        ..Default::default()
    };
    bake_files(high, low, request, &outputs, &|_, _| {}).unwrap();
    dir.join(format!("{name}.glb"))
}

#[test]
fn a_sphere_baked_onto_a_coarse_one_shades_as_the_sphere() {
    let dir = scratch();
    let (high, low) = (dir.join("high.glb"), dir.join("low.glb"));
    let sphere = Surface::Sphere { radius: 1.0 };
    // HIGH: the sphere with waves 2 % of its radius high, normals from its faces.
    let mut bumpy = sphere.tessellate(384, 192, Vec2::ONE);
    for (p, uv) in bumpy.positions.iter_mut().zip(&bumpy.texcoords) {
        let (u, v) = (uv.x * std::f32::consts::TAU, uv.y * std::f32::consts::PI);
        *p *= 1.0 + 0.02 * (8.0 * u).sin() * (6.0 * v).sin();
    }
    bumpy.compute_normals();
    bumpmap_io::save_gltf(&high, &bumpy).unwrap();
    bumpmap_io::save_gltf(&low, &sphere.tessellate(32, 16, Vec2::ONE)).unwrap();
    let bake_for = |decode, name: &str| {
        let mut request = BakeRequest::default();
        (request.options.width, request.options.height, request.options.decode) = (512, 256, decode);
        bake_into(&dir, &high, &low, &request, name)
    };
    // The defaults: the bake for MikkTSpace's decode, the renderer decoding per pixel on a mesh.
    let mikktspace = bake_for(TangentDecode::MikkTSpace, "mikktspace");
    let per_vertex = bake_for(TangentDecode::PerVertex, "per-vertex");
    let target = normals(&high, "no-bump");
    let (with_bake, pixels) = mean_angle(&target, &normals(&mikktspace, "single-pass"));
    let (synced_per_vertex, _) = mean_angle(&target, &normals(&per_vertex, "single-pass/per-vertex"));
    let (crossed, _) = mean_angle(&target, &normals(&mikktspace, "single-pass/per-vertex"));
    let (without, _) = mean_angle(&target, &normals(&low, "no-bump"));
    eprintln!(
        "sphere: mean angle to HIGH's shading normals {with_bake:.2}° with the default bake and decode (mikktspace), \
         {synced_per_vertex:.2}° with both per-vertex, {crossed:.2}° with a mikktspace bake decoded per vertex, \
         {without:.2}° without ({pixels} pixels)"
    );
    assert!(pixels > SIZE * SIZE / 8, "the sphere fills the frame: {pixels}");
    assert!(with_bake <= 1.0, "{with_bake}°");
    assert!(synced_per_vertex <= 1.0, "{synced_per_vertex}°");
    assert!(without > 3.0 * with_bake, "the bake is what brings LOW near: {without}° without");
}

/// `bumpmap_math::mesh::rounded_cube` with tangents.
fn rounded_cube(n: usize, r: f32) -> bumpmap_math::mesh::Mesh {
    let mesh = bumpmap_math::mesh::rounded_cube(n, r);
    bumpmap_math::tangent::generate_tangents(&mesh, &Default::default()).unwrap().0
}

#[test]
fn a_hard_edged_cube_baked_by_averaged_rays_has_no_seam_and_explicit_rays_leave_one() {
    let dir = scratch().join("cube");
    std::fs::create_dir_all(&dir).unwrap();
    let (high, low) = (dir.join("high.glb"), dir.join("low.glb"));
    bumpmap_io::save_gltf(&high, &rounded_cube(48, 0.2)).unwrap();
    // LOW: the cube with hard edges, each face its own four vertices and island.
    bumpmap_io::save_gltf(&low, &rounded_cube(1, 0.0)).unwrap();
    let bake_with = |rays: &str, name: &str| {
        let mut request = BakeRequest::default();
        let row = find(bumpmap::option_table::BAKE, "ray").unwrap();
        row.set(&mut request, row.parse_text(rays).unwrap()).unwrap();
        (request.options.width, request.options.height) = (384, 256);
        (request.options.front, request.options.back) = (Some(0.3), Some(0.3));
        bake_into(&dir, &high, &low, &request, name)
    };
    let target = cube_normals(&high, "no-bump");
    let averaged = cube_normals(&bake_with("averaged", "averaged"), "single-pass");
    let explicit = cube_normals(&bake_with("explicit", "explicit"), "single-pass");
    let (a, pixels) = mean_angle(&target, &averaged);
    let (e, _) = mean_angle(&target, &explicit);
    eprintln!(
        "bevelled cube: mean angle to HIGH's shading normals {a:.2}° by averaged rays, {e:.2}° by explicit ones ({pixels} pixels)"
    );
    assert!(pixels > SIZE * SIZE / 8, "{pixels}");
    assert!(a <= 1.0, "{a}°");
    assert!(e > 2.0 * a, "explicit rays: {e}°, averaged {a}°");
}

/// [`normals`] of the cube seen from a corner, three faces in view and lit by every light.
fn cube_normals(mesh: &Path, technique: &str) -> Vec<Option<Vec3>> {
    normals_from(mesh, technique, "3.2,-4,2.6", [[1.0, -1.0, 1.0], [1.8, -0.6, 0.6], [0.5, -0.7, 1.8]])
}
