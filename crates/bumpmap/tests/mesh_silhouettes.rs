//! Silhouettes on a mesh: the torus exported as a mesh (no analytic surface behind it) drawn by
//! `pom --silhouettes`, its outline against the reference that micro-tessellates the displaced
//! built-in torus (`reference-displaced`), at a grazing view where the bricks cut the rim. The
//! mesh's curvature comes from a quadric fitted at each vertex
//! (`bumpmap_math::mesh::Mesh::st_normal_curvature`); without it a mesh's rays never leave.

use std::path::{Path, PathBuf};

use bumpmap::frame::{FrameRequest, draw_frame, prepare_frame};
use bumpmap::option_table::{SCENE, find};
use bumpmap::options::Given;
use bumpmap::{BackendChoice, Renderer, Rgba8Image};
use bumpmap_math::surface::Surface;
use glam::Vec2;

const SIZE: usize = 192;

/// `scene` drawn with `options` (name, value) and the shared camera and heights.
fn draw(scene: &str, options: &[(&str, &str)]) -> Rgba8Image {
    let mut request = FrameRequest { size: (SIZE, SIZE), backend: BackendChoice::Cpu, ..Default::default() };
    let shared = [
        ("scene", scene),
        ("eye", "0,-6.5,0.9"),
        ("target", "0,0,0"),
        ("up", "0,0,1"),
        ("fov", "32"),
        ("depth", "0.15"),
        ("ambient", "0.35"),
        ("decal", "none"),
        ("height-field", "bricks"),
    ];
    for (name, text) in shared.iter().chain(options) {
        let row = find(SCENE, name).unwrap_or_else(|| panic!("{name} is a row"));
        let value = row.parse_text(text).unwrap_or_else(|e| panic!("--{name} {text}: {e}"));
        row.set(&mut request, value).unwrap();
    }
    let prepared = prepare_frame(&request, &Given::default()).unwrap();
    let mut renderer = Renderer::new(BackendChoice::Cpu).unwrap();
    draw_frame(&mut renderer, &prepared, false).unwrap().image
}

/// Which pixels show the surface (anything but the black background).
fn mask(image: &Rgba8Image) -> Vec<bool> {
    image.texels.iter().map(|t| t[..3].iter().any(|&c| c > 2)).collect()
}

/// Intersection over union of two masks, and how many pixels either covers.
fn iou(a: &[bool], b: &[bool]) -> (f64, usize) {
    let both = a.iter().zip(b).filter(|(x, y)| **x && **y).count();
    let either = a.iter().zip(b).filter(|(x, y)| **x || **y).count();
    (both as f64 / either.max(1) as f64, either)
}

fn torus_mesh(dir: &Path) -> PathBuf {
    // The built-in torus's surface and texture layout (radii 2 and 0.7, repeats 6 and 2).
    let torus = Surface::Torus { major: 2.0, minor: 0.7 }.tessellate(128, 64, Vec2::new(6.0, 2.0));
    let path = dir.join("torus.glb");
    bumpmap_io::save_gltf(&path, &torus).unwrap();
    path
}

#[test]
fn silhouettes_cut_a_meshs_outline_as_the_displaced_surface_does() {
    let dir = std::env::temp_dir().join(format!("bumpmap-mesh-silhouettes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = format!("mesh:{}", torus_mesh(&dir).display());
    let reference = mask(&draw("torus", &[("technique", "reference-displaced"), ("spp", "4")]));
    let cut = mask(&draw(&mesh, &[("technique", "pom"), ("silhouettes", "true")]));
    let whole = mask(&draw(&mesh, &[("technique", "pom")]));
    let built_in = mask(&draw("torus", &[("technique", "pom"), ("silhouettes", "true")]));
    let (with, pixels) = iou(&cut, &reference);
    let (without, _) = iou(&whole, &reference);
    let (analytic, _) = iou(&built_in, &reference);
    // Where two outlines differ: the pixels only one of them covers.
    let apart = |a: &[bool], b: &[bool]| a.iter().zip(b).filter(|(x, y)| x != y).count();
    eprintln!(
        "silhouette IoU against the displaced reference: the mesh with --silhouettes {with:.4} ({} pixels apart), \
         without {without:.4} ({} apart), the built-in torus with {analytic:.4} ({} apart); the mesh's cut and the \
         built-in's {} pixels apart, the mesh's with and without {} apart; {pixels} pixels",
        apart(&cut, &reference),
        apart(&whole, &reference),
        apart(&built_in, &reference),
        apart(&cut, &built_in),
        apart(&cut, &whole),
    );
    assert!(pixels > SIZE * SIZE / 6, "the torus fills the frame: {pixels}");
    assert!(with >= 0.95, "IoU {with}");
    // The fitted curvature cuts as the surface's own does, and cuts: without it a mesh's rays
    // never left the surface and the two masks were the same.
    assert!(
        apart(&cut, &built_in) * 10 <= apart(&cut, &whole),
        "{} vs {}",
        apart(&cut, &built_in),
        apart(&cut, &whole)
    );
    assert!(apart(&cut, &whole) > 50, "{}", apart(&cut, &whole));
    std::fs::remove_dir_all(dir).unwrap();
}
