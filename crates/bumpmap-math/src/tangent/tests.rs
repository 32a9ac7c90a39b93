use super::faces::{acos, corner_angles};
use super::*;
use crate::lighting::{Light, ObjectLighting, TangentFrame, Viewer};
use crate::surface::{BicubicPatch, Surface};
use glam::{Mat4, Vec2};

/// Two unit quads side by side in the x–y plane, the left one's texture mirrored in s: the
/// seam at x = 0 has s = 1 on both sides, so its vertices are shared in the input.
fn mirrored_pair() -> Mesh {
    let mut m = Mesh::default();
    for (x, s) in [(-1.0, 0.0), (0.0, 1.0), (1.0, 0.0)] {
        for y in [0.0, 1.0] {
            m.positions.push(Vec3::new(x, y, 0.0));
            m.normals.push(Vec3::Z);
            m.texcoords.push(Vec2::new(s, y));
        }
    }
    // Vertices: 0 (−1,0) 1 (−1,1) 2 (0,0) 3 (0,1) 4 (1,0) 5 (1,1); counter-clockwise.
    m.indices = vec![[0, 2, 3], [0, 3, 1], [2, 4, 5], [2, 5, 3]];
    m
}

#[test]
fn mirrored_seam_splits_and_lights_both_sides_alike() {
    let (mesh, report) = generate_tangents(&mirrored_pair(), &TangentOptions::default()).unwrap();
    assert_eq!(report.mirrored, 2, "the right quad's s runs against x");
    assert_eq!(report.vertices_split, 2, "both seam vertices split");
    let frame = |v: usize| {
        let t = mesh.tangents[v];
        TangentFrame { t: t.truncate(), b: mesh.bitangent(v), n: mesh.normals[v] }
    };
    // Each triangle's corners agree on handedness: +1 left, −1 right.
    for (tri, w) in [(0, 1.0), (1, 1.0), (2, -1.0), (3, -1.0)] {
        for &v in &mesh.indices[tri] {
            assert_eq!(mesh.tangents[v as usize].w, w, "triangle {tri} vertex {v}");
        }
    }
    // Mirror-image points lit by mirror-image lights see the same tangent-space light.
    let lit = |light: Vec3| ObjectLighting::new(Mat4::IDENTITY, Light::Positional(light), Viewer::Infinite(Vec3::Z));
    let (left, _) = lit(Vec3::new(-0.5 - 0.3, 0.7, 1.0)).tangent_space(Vec3::new(-0.5, 0.5, 0.0), &frame(0));
    let (right, _) = lit(Vec3::new(0.5 + 0.3, 0.7, 1.0)).tangent_space(Vec3::new(0.5, 0.5, 0.0), &frame(4));
    assert!((left - right).length() < 1e-6, "{left} vs {right}");
    assert!(left.x < 0.0, "the light lies toward decreasing s on both sides");
}

#[test]
fn flat_grid_gets_the_analytic_frame_without_splits() {
    let mesh = Surface::Wall { width: 2.0, height: 1.0 }.tessellate(6, 3, Vec2::new(3.0, 1.0));
    let mut bare = mesh.clone();
    bare.tangents.clear();
    let (out, report) = generate_tangents(&bare, &TangentOptions::default()).unwrap();
    assert_eq!(report, TangentReport::default());
    for t in &out.tangents {
        assert!((t.truncate() - Vec3::X).length() < 1e-6 && t.w == 1.0, "{t}");
    }
}

#[test]
fn degenerate_uv_triangles_are_reported_and_framed() {
    let mut m = mirrored_pair();
    // Collapse the texture coordinates of the left quad onto a point.
    for i in [0, 1] {
        m.texcoords[i] = Vec2::new(1.0, 0.5);
    }
    m.texcoords[3] = Vec2::new(1.0, 0.5);
    m.texcoords[2] = Vec2::new(1.0, 0.5);
    let (out, report) = generate_tangents(&m, &TangentOptions::default()).unwrap();
    // Three triangles touch only collapsed coordinates (the left quad, and the right quad's
    // triangle with two seam vertices); the fourth still spans texture space.
    assert_eq!(report.degenerate_uv, 3);
    for (t, n) in out.tangents.iter().zip(&out.normals) {
        assert!(
            t.is_finite() && (t.truncate().length() - 1.0).abs() < 1e-5 && t.truncate().dot(*n).abs() < 1e-5,
            "{t}"
        );
    }
}

#[test]
fn tessellated_surfaces_match_their_analytic_tangents() {
    for surface in
        [Surface::default_torus(), Surface::Sphere { radius: 1.0 }, Surface::Patch(BicubicPatch::stretched())]
    {
        let analytic = surface.tessellate(32, 16, Vec2::new(2.0, 1.0));
        let mut bare = analytic.clone();
        bare.tangents.clear();
        for mode in [TangentMode::Ours, TangentMode::MikkTSpace] {
            let (out, _) = generate_tangents(&bare, &TangentOptions { mode, ..Default::default() }).unwrap();
            assert_eq!(out.vertex_count(), analytic.vertex_count(), "{surface:?} {mode:?}: no splits");
            let worst = out
                .tangents
                .iter()
                .zip(&analytic.tangents)
                .skip(33) // the sphere's south-pole row has no defined ∂P/∂u
                .take(out.vertex_count() - 66)
                .map(|(a, b)| a.truncate().angle_between(b.truncate()).to_degrees())
                .fold(0.0f32, f32::max);
            // Finite differences over one 1/32-turn facet: a few degrees at most.
            assert!(worst < 8.0, "{surface:?} {mode:?}: worst {worst}°");
        }
    }
}

#[test]
fn bad_meshes_are_errors() {
    let mut m = mirrored_pair();
    m.indices.push([0, 1, 9]);
    assert!(matches!(
        generate_tangents(&m, &TangentOptions::default()),
        Err(MeshError::IndexOutOfRange { index: 9, .. })
    ));
    let mut m = mirrored_pair();
    m.positions[2].x = f32::NAN;
    assert!(matches!(generate_tangents(&m, &TangentOptions::default()), Err(MeshError::NonFinite { .. })));
    let mut m = mirrored_pair();
    m.texcoords.clear();
    assert_eq!(generate_tangents(&m, &TangentOptions::default()).unwrap_err(), MeshError::NoTexcoords);
}

/// A disc of `n` triangles around one vertex, texture mapped flat.
fn fan(n: usize) -> Mesh {
    let mut m = Mesh::default();
    m.positions.push(Vec3::ZERO);
    m.texcoords.push(glam::Vec2::splat(0.5));
    for i in 0..=n {
        let a = std::f32::consts::TAU * i as f32 / n as f32;
        m.positions.push(Vec3::new(a.cos(), a.sin(), 0.0));
        m.texcoords.push(glam::Vec2::new(0.5 + 0.5 * a.cos(), 0.5 - 0.5 * a.sin()));
    }
    m.indices = (0..n as u32).map(|i| [0, i + 1, i + 2]).collect();
    m.normals = vec![Vec3::Z; m.positions.len()];
    m
}

#[test]
fn fans_around_one_vertex_are_framed_or_refused_not_overflowed() {
    // Ours: every corner at the centre in one cluster, found without searching its row.
    let (out, report) = generate_tangents(&fan(50_000), &TangentOptions::default()).unwrap();
    assert_eq!(report.vertices_split, 0);
    // Each sliver spans 6e-5 of the texture: single precision frames it to about 1e-3.
    let worst = out.tangents.iter().map(|t| t.truncate().distance(Vec3::X)).fold(0.0f32, f32::max);
    assert!(worst < 1e-2, "the flat map's +s is +x: off by {worst}");
    // MikkTSpace: a fan it can take runs on a stack sized for it (8,000 corners at the centre
    // recurse deeper than a rayon worker's 2 MiB allow)…
    let mikk = TangentOptions { mode: TangentMode::MikkTSpace, ..Default::default() };
    let (out, _) = generate_tangents(&fan(8_000), &mikk).unwrap();
    let worst = out.tangents.iter().map(|t| t.truncate().distance(Vec3::X)).fold(0.0f32, f32::max);
    assert!(worst < 1e-2, "MikkTSpace off by {worst}");
    // …and past its limit the mesh is refused, saying why.
    let e = generate_tangents(&fan(MAX_CORNERS_AT_ONE_POSITION + 1), &mikk).unwrap_err().to_string();
    assert!(e.contains("10001 triangle corners share one position"), "{e}");
}

/// The weights' arccos: within 5·10⁻⁷ rad of the f64 value everywhere on [−1, 1] (the
/// polynomial's 2·10⁻⁸, its f32 coefficients, and f32 rounding near π, where one ulp is
/// 2.4·10⁻⁷), and clamped outside.
#[test]
fn polynomial_acos_is_within_half_a_microradian() {
    let mut worst = 0.0f64;
    for i in 0..=200_000 {
        let x = -1.0 + i as f32 * 1e-5;
        let x = x.clamp(-1.0, 1.0);
        worst = worst.max((acos(x) as f64 - (x as f64).acos()).abs());
    }
    assert!(worst < 5e-7, "worst error {worst} rad");
    assert!(acos(1.0).abs() < 1e-6 && (acos(-1.0) - std::f32::consts::PI).abs() < 1e-6);
    assert!((acos(0.0) - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    assert_eq!((acos(1.5), acos(-1.5)), (acos(1.0), acos(-1.0)));
}

/// Corner angles sum to π and match the definition on a right triangle.
#[test]
fn corner_angles_of_a_right_triangle() {
    let a = corner_angles([Vec3::ZERO, Vec3::X, Vec3::Y]);
    let quarter = std::f32::consts::FRAC_PI_4;
    assert!(
        (a[0] - 2.0 * quarter).abs() < 1e-6 && (a[1] - quarter).abs() < 1e-6 && (a[2] - quarter).abs() < 1e-6,
        "{a:?}"
    );
    assert_eq!(corner_angles([Vec3::ZERO, Vec3::ZERO, Vec3::Y])[0], 0.0);
}

#[test]
fn vertex_colours_follow_their_vertices_through_splits_parts_and_back_faces() {
    // Each vertex's colour names its position, so a colour left behind by a copy shows.
    let mut mesh = mirrored_pair();
    mesh.colors = mesh.positions.iter().map(|p| p.extend(1.0) * 0.5 + 0.5).collect();
    let colour_of = |m: &Mesh, i: usize| m.positions[i].extend(1.0) * 0.5 + 0.5;
    let check = |what: &str, m: &Mesh| {
        m.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(m.has_colors(), "{what}");
        for i in 0..m.vertex_count() {
            assert_eq!(m.colors[i], colour_of(m, i), "{what}: vertex {i}");
        }
    };
    for mode in [TangentMode::Ours, TangentMode::MikkTSpace] {
        let (split, report) = generate_tangents(&mesh, &TangentOptions { mode, ..Default::default() }).unwrap();
        assert!(report.vertices_split > 0, "{mode:?}: the seam splits");
        check(&format!("{mode:?}"), &split);
        let mut part = split.submesh(&split.indices[2..]);
        check("a part", &part);
        part.add_back_faces();
        check("with back faces", &part);
    }
    let mut short = mesh.clone();
    short.colors.pop();
    assert!(matches!(short.validate(), Err(MeshError::CountMismatch { what: "colours", .. })));
    mesh.colors[3].y = f32::NAN;
    assert!(matches!(mesh.validate(), Err(MeshError::NonFinite { what: "colour", vertex: 3, .. })));
}
