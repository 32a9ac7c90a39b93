//! The bake against closed forms on curved surfaces: HIGH is a sphere or a torus tessellated to
//! four vertices a texel and displaced along its normal by a height field, LOW the same surface
//! tessellated a vertex a texel. The expected normal at a texel is the displaced analytic
//! surface's, `∂P/∂u × ∂P/∂v` of `P = S + depth·h·N`, at the texel's centre; the bake's
//! object-space normal is compared with it, and HIGH's curvature with the surface's own.
//!
//! The tolerance is the plane's (`closed_form.rs`: mean ≤ 0.5°, 99th percentile ≤ 2°), though
//! LOW's point at a texel centre lies on a chord, inside the surface, so its ray meets HIGH a
//! little off the analytic point of the same (u, v); the angles printed are the measurement.

use bumpmap_bake::{BakeOptions, bake};
use bumpmap_math::mesh::Mesh;
use bumpmap_math::surface::Surface;
use glam::{Vec2, Vec3};

/// Texels across (u); half as many down (v).
const N: usize = 64;
/// How far the heights displace HIGH, in the surfaces' units.
const DEPTH: f32 = 0.05;

/// Heights in [0, 1], periodic in u and v, constant at v = 0 and 1 (a sphere's poles).
fn heights(u: f32, v: f32) -> f32 {
    use std::f32::consts::{PI, TAU};
    0.5 + 0.4 * (TAU * 6.0 * u).sin() * (PI * v).sin().powi(2) * (TAU * 4.0 * v).cos()
}

/// The displaced surface's point at (u, v).
fn displaced(surface: &Surface, u: f32, v: f32) -> Vec3 {
    let p = surface.eval(u, v);
    p.position + p.normal * DEPTH * heights(u, v)
}

/// The displaced surface's unit normal at (u, v), by central differences.
fn displaced_normal(surface: &Surface, u: f32, v: f32) -> Vec3 {
    const E: f32 = 1e-3;
    let du = displaced(surface, u + E, v) - displaced(surface, u - E, v);
    let dv = displaced(surface, u, v + E) - displaced(surface, u, v - E);
    du.cross(dv).normalize()
}

/// `surface` tessellated `nu`×`nv`, displaced by `depth`× the heights, its seam and poles welded
/// as a modelled mesh has them (the analytic ones land a rounding error apart).
fn tessellated(surface: &Surface, nu: usize, nv: usize, depth: f32) -> Mesh {
    let mut mesh = surface.tessellate(nu, nv, Vec2::ONE);
    for (p, uv) in mesh.positions.iter_mut().zip(&mesh.texcoords) {
        let at = surface.eval(uv.x, uv.y);
        *p = at.position + at.normal * depth * heights(uv.x, uv.y);
    }
    let row = nu + 1;
    for j in 0..=nv {
        mesh.positions[j * row + nu] = mesh.positions[j * row];
    }
    if matches!(surface, Surface::Sphere { .. }) {
        for j in [0, nv] {
            for i in 1..=nu {
                mesh.positions[j * row + i] = mesh.positions[j * row];
            }
        }
    }
    mesh
}

/// Mean and 99th percentile of `degrees`.
fn mean_p99(mut degrees: Vec<f32>) -> (f32, f32) {
    degrees.sort_by(f32::total_cmp);
    (degrees.iter().sum::<f32>() / degrees.len() as f32, degrees[degrees.len() * 99 / 100])
}

/// Bakes the displaced `surface` onto the plain one; the angles between the bake's object-space
/// normals and the closed form's, over texels at least `margin` rows from v = 0 and v = 1.
fn normals_against_closed_form(surface: &Surface, margin: usize) -> (f32, f32) {
    let (w, h) = (N, N / 2);
    let mut high = tessellated(surface, 4 * w, 4 * h, DEPTH);
    high.compute_normals();
    let low = tessellated(surface, w, h, 0.0);
    let options = BakeOptions {
        width: w,
        height: h,
        samples: 1,
        front: Some(4.0 * DEPTH),
        back: Some(4.0 * DEPTH),
        ..Default::default()
    };
    let baked = bake(&high, &low, &options, &|_, _| {}).unwrap();
    let degrees: Vec<f32> = (margin..h - margin)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let k = y * w + x;
            assert!(baked.hit[k], "texel ({x}, {y}) missed");
            let expected = displaced_normal(surface, (x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
            baked.object[k].dot(expected).clamp(-1.0, 1.0).acos().to_degrees()
        })
        .collect();
    // Not trivially flat: the heights tilt the normals away from the surface's.
    let tilt = (0..w * h)
        .map(|k| {
            let (u, v) = (((k % w) as f32 + 0.5) / w as f32, ((k / w) as f32 + 0.5) / h as f32);
            displaced_normal(surface, u, v).dot(surface.eval(u, v).normal).acos().to_degrees()
        })
        .fold(0.0, f32::max);
    assert!(tilt > 5.0, "{tilt}°");
    mean_p99(degrees)
}

#[test]
fn a_displaced_sphere_bakes_to_its_closed_form() {
    let (mean, p99) = normals_against_closed_form(&Surface::Sphere { radius: 1.0 }, 2);
    eprintln!(
        "sphere, 4 vertices a texel, against the displaced sphere's normals: mean {mean:.3}°, 99th percentile {p99:.3}°"
    );
    assert!(mean <= 0.5 && p99 <= 2.0, "mean {mean}°, 99th percentile {p99}°");
}

#[test]
fn a_displaced_torus_bakes_to_its_closed_form() {
    let (mean, p99) = normals_against_closed_form(&Surface::default_torus(), 0);
    eprintln!(
        "torus, 4 vertices a texel, against the displaced torus's normals: mean {mean:.3}°, 99th percentile {p99:.3}°"
    );
    assert!(mean <= 0.5 && p99 <= 2.0, "mean {mean}°, 99th percentile {p99}°");
}

#[test]
fn the_curvature_baked_is_the_surfaces() {
    let bake_plain = |surface: &Surface| {
        let high = tessellated(surface, 4 * N, 2 * N, 0.0);
        let low = tessellated(surface, N, N / 2, 0.0);
        let options = BakeOptions {
            width: N,
            height: N / 2,
            samples: 1,
            front: Some(0.05),
            back: Some(0.05),
            curvature: true,
            ..Default::default()
        };
        bake(&high, &low, &options, &|_, _| {}).unwrap()
    };
    // A sphere of radius 2 bends by 1/2 everywhere.
    let sphere = bake_plain(&Surface::Sphere { radius: 2.0 });
    let worst =
        sphere.curvature.iter().zip(&sphere.hit).filter(|(_, h)| **h).map(|(k, _)| (k - 0.5).abs()).fold(0.0, f32::max);
    assert!(worst < 0.01, "sphere: {worst}");
    // A torus: the mean of its principal curvatures, 1/r around the tube and
    // cos v / (R + r cos v) around the hole (negative on the inside, where it is saddle-shaped).
    let (major, minor) = (2.0, 0.7);
    let torus = bake_plain(&Surface::Torus { major, minor });
    let errors: Vec<f32> = (0..N * N / 2)
        .map(|k| {
            let v = ((k / N) as f32 + 0.5) / (N / 2) as f32;
            let c = (std::f32::consts::TAU * v).cos();
            let mean = 0.5 * (1.0 / minor + c / (major + minor * c));
            (torus.curvature[k] - mean).abs()
        })
        .collect();
    let (mean, p99) = mean_p99(errors);
    eprintln!(
        "torus curvature against its mean curvature: mean |error| {mean:.4}, 99th percentile {p99:.4} (1/r = {:.3})",
        1.0 / minor
    );
    assert!(mean < 0.01, "{mean}");
}
