//! Rasterizer invariants: watertight fill rule, perspective-correct varyings, repeatable depth,
//! clipping and culling, and robustness to bad vertices.

use super::*;
use bumpmap_core::state::Blend;

/// Outputs varying 0 in red and a constant elsewhere.
struct Show(f32);

impl FragmentShader for Show {
    type Scratch = ();
    fn scratch(&self) {}
    fn shade(&self, batch: &FragmentBatch, _: &mut (), out: &mut [Lanes; 4]) {
        for (j, &lane) in batch.live().iter().enumerate() {
            out[0][j] = batch.varyings[0][lane as usize];
            out[1][j] = self.0;
            out[2][j] = self.0;
            out[3][j] = 1.0;
        }
    }
}

fn vertex(x: f32, y: f32, z: f32, w: f32, var0: f32) -> Vertex {
    let mut varyings = [0.0; MAX_VARYINGS];
    varyings[0] = var0;
    Vertex { clip: Vec4::new(x * w, y * w, z * w, w), varyings }
}

#[test]
fn shared_edges_have_no_gaps_and_no_double_hits() {
    // A jittered 7×5 grid of triangles covering [-0.8, 0.8]², drawn additively with 1/255 each.
    let (nx, ny) = (7, 5);
    let mut verts = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let jitter = |k: usize| if k == 0 || k == nx.max(ny) { 0.0 } else { ((k * 7919) % 13) as f32 * 0.004 };
            let x = -0.8 + 1.6 * i as f32 / nx as f32 + if i > 0 && i < nx { jitter(i + j) } else { 0.0 };
            let y = -0.8 + 1.6 * j as f32 / ny as f32 + if j > 0 && j < ny { jitter(i * 3 + j) } else { 0.0 };
            verts.push(vertex(x, y, 0.0, 1.0, 0.0));
        }
    }
    let row = nx as u32 + 1;
    let mut tris = Vec::new();
    for j in 0..ny as u32 {
        for i in 0..nx as u32 {
            let (a, b, c, d) = (j * row + i, j * row + i + 1, (j + 1) * row + i + 1, (j + 1) * row + i);
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    let mut fb = Framebuffer::new(203, 141).unwrap();
    let pass = PassState {
        depth_func: DepthFunc::Always,
        depth_write: false,
        blend: Blend::new(BlendFactor::One, BlendFactor::One),
        color_mask: [true; 4],
        cull_back: true,
        alpha_test: None,
    };
    let state = DrawState::new(pass, 1);
    draw(&mut fb, &verts, &tris, &state, &Show(1.0 / 255.0));
    let img = fb.to_rgba8();
    // Pixel centres strictly inside the square's interior get exactly one hit.
    let (w, h) = (203.0f32, 141.0f32);
    let mut inside = 0;
    for (i, p) in img.iter().enumerate() {
        let (px, py) = ((i % 203) as f32 + 0.5, (i / 203) as f32 + 0.5);
        let (x, y) = (px / w * 2.0 - 1.0, 1.0 - py / h * 2.0);
        if x.abs() < 0.79 && y.abs() < 0.79 {
            assert_eq!(p[1], 1, "pixel {i} hit {} times", p[1]);
            inside += 1;
        } else if x.abs() > 0.81 || y.abs() > 0.81 {
            assert_eq!(p[1], 0, "pixel {i} outside was hit");
        }
    }
    assert!(inside > 15_000);
}

#[test]
fn varyings_are_perspective_correct() {
    // A quad from w = 1 (bottom) to w = 4 (top) with varying 0 running 0 → 1 bottom to top.
    let verts = [
        vertex(-1.0, -1.0, 0.0, 1.0, 0.0),
        vertex(1.0, -1.0, 0.0, 1.0, 0.0),
        vertex(1.0, 1.0, 0.0, 4.0, 1.0),
        vertex(-1.0, 1.0, 0.0, 4.0, 1.0),
    ];
    let mut fb = Framebuffer::new(64, 64).unwrap();
    draw(&mut fb, &verts, &[[0, 1, 2], [0, 2, 3]], &DrawState::OPAQUE, &Show(0.0));
    // At screen fraction f from the bottom, perspective gives v = f/w1 / ((1−f)/w0 + f/w1).
    for row in [8usize, 32, 56] {
        let f = 1.0 - (row as f32 + 0.5) / 64.0;
        let v = (f / 4.0) / ((1.0 - f) + f / 4.0);
        let got = fb.pixel(20, row)[0] as f32 / 255.0;
        assert!((got - v).abs() <= 0.6 / 255.0, "row {row}: {got} vs {v}");
        assert!((got - f).abs() > 0.05 || row == 8 || row == 56, "not affine");
    }
}

#[test]
fn equal_depth_holds_across_passes_and_culling_works() {
    let mesh = bumpmap_math::surface::Surface::default_torus().tessellate(48, 24, glam::Vec2::ONE);
    let view = glam::Mat4::look_at_rh(glam::Vec3::new(0.0, -6.0, 4.0), glam::Vec3::ZERO, glam::Vec3::Z);
    let proj = glam::Mat4::perspective_rh_gl(0.7, 1.0, 0.5, 30.0);
    let verts: Vec<Vertex> = mesh
        .positions
        .iter()
        .map(|p| Vertex { clip: proj * view * p.extend(1.0), varyings: [0.5; MAX_VARYINGS] })
        .collect();
    let mut fb = Framebuffer::new(160, 160).unwrap();
    draw(&mut fb, &verts, &mesh.indices, &DrawState::OPAQUE, &Show(0.2));
    let first = fb.to_rgba8();
    let drawn = first.iter().filter(|p| p[3] == 255).count();
    assert!(drawn > 5000, "torus covers {drawn} pixels");
    let equal = DrawState::new(
        PassState { depth_func: DepthFunc::Equal, depth_write: false, ..PassState::OPAQUE },
        MAX_VARYINGS,
    );
    draw(&mut fb, &verts, &mesh.indices, &equal, &Show(0.9));
    let second = fb.to_rgba8();
    for (a, b) in first.iter().zip(&second) {
        if a[3] == 255 {
            assert_eq!(b[1], 230, "every pixel of pass 1 passes EQUAL in pass 2");
        }
    }
    // A clockwise triangle is a back face: culled by default, drawn without culling.
    let tri = [vertex(-0.5, -0.5, 0.0, 1.0, 0.0), vertex(0.0, 0.5, 0.0, 1.0, 0.0), vertex(0.5, -0.5, 0.0, 1.0, 0.0)];
    let mut fb2 = Framebuffer::new(32, 32).unwrap();
    draw(&mut fb2, &tri, &[[0, 1, 2]], &DrawState::OPAQUE, &Show(0.2));
    assert!(fb2.to_rgba8().iter().all(|p| p[3] == 0), "back face culled");
    draw(
        &mut fb2,
        &tri,
        &[[0, 1, 2]],
        &DrawState::new(PassState { cull_back: false, ..PassState::OPAQUE }, MAX_VARYINGS),
        &Show(0.2),
    );
    assert_eq!(
        fb2.to_rgba8().iter().filter(|p| p[3] == 255).count(),
        16 * 16 / 2,
        "exactly the triangle's area: half of a 16×16 box"
    );
}

#[test]
fn clipping_and_bad_vertices_never_crash() {
    let mut fb = Framebuffer::new(64, 64).unwrap();
    let proj = glam::Mat4::perspective_rh_gl(1.0, 1.0, 0.1, 100.0);
    let v = |p: glam::Vec3| Vertex { clip: proj * p.extend(1.0), varyings: [0.0; MAX_VARYINGS] };
    // Crossing the near plane: a large floor under the eye, CCW seen from above.
    let floor =
        [v(glam::Vec3::new(-5.0, -1.0, 5.0)), v(glam::Vec3::new(5.0, -1.0, 5.0)), v(glam::Vec3::new(0.0, -1.0, -20.0))];
    draw(
        &mut fb,
        &floor,
        &[[0, 1, 2]],
        &DrawState::new(PassState { cull_back: false, ..PassState::OPAQUE }, MAX_VARYINGS),
        &Show(1.0),
    );
    let covered = fb.to_rgba8().iter().filter(|p| p[3] == 255).count();
    assert!(covered > 500 && covered < 64 * 64, "clipped floor covers {covered}");
    // Entirely behind the eye, NaN, infinite and huge coordinates, out-of-range indices.
    let mut fb = Framebuffer::new(64, 64).unwrap();
    let behind =
        [v(glam::Vec3::new(0.0, 0.0, 1.0)), v(glam::Vec3::new(1.0, 0.0, 1.0)), v(glam::Vec3::new(0.0, 1.0, 1.0))];
    let nan = [vertex(f32::NAN, 0.0, 0.0, 1.0, 0.0), vertex(1.0, 0.0, 0.0, 1.0, 0.0), vertex(0.0, 1.0, 0.0, 1.0, 0.0)];
    let huge = [vertex(-1e6, -1e6, 0.0, 1.0, 0.0), vertex(1e6, -1e6, 0.0, 1.0, 0.0), vertex(0.0, 1e6, 0.0, 1.0, 0.0)];
    let absurd =
        [vertex(-1e30, -1e30, 0.0, 1.0, 0.0), vertex(1e30, -1e30, 0.0, 1.0, 0.0), vertex(0.0, 1e30, 0.0, 1.0, 0.0)];
    let state = DrawState::new(PassState { cull_back: false, ..PassState::OPAQUE }, MAX_VARYINGS);
    draw(&mut fb, &behind, &[[0, 1, 2]], &state, &Show(1.0));
    assert!(fb.to_rgba8().iter().all(|p| p[3] == 0), "behind the eye draws nothing");
    draw(&mut fb, &nan, &[[0, 1, 2], [0, 1, 7]], &state, &Show(1.0));
    assert!(fb.to_rgba8().iter().all(|p| p[3] == 0), "NaN vertices and bad indices draw nothing");
    draw(&mut fb, &huge, &[[0, 1, 2]], &state, &Show(1.0));
    assert!(fb.to_rgba8().iter().all(|p| p[3] == 255), "a huge triangle, clipped to the guard band, covers the frame");
    // 1e30 is beyond f32's precision for clipping: whatever it draws, it must not crash.
    draw(&mut fb, &absurd, &[[0, 1, 2]], &state, &Show(1.0));
}

#[test]
fn the_vector_depth_test_is_depth_funcs_definition() {
    let values = [0.0, 0.25, 0.5, 0.5000001, 1.0, f32::NAN, -0.0];
    for func in [DepthFunc::Always, DepthFunc::Less, DepthFunc::LEqual, DepthFunc::Equal] {
        for &a in &values {
            for &b in &values {
                let z = Vec4::new(a, b, a, 0.5);
                let stored = Vec4::new(b, a, a, 0.5);
                let mask = depth_test_quad(func, z, stored);
                for k in 0..4 {
                    let expected = func.passes(z[k], stored[k]);
                    assert_eq!(mask >> k & 1 == 1, expected, "{func:?}: {} against {}", z[k], stored[k]);
                }
            }
        }
    }
}

#[test]
fn every_fast_blend_equals_the_general_blend() {
    use crate::pixel::{blend_pixel, rgba8_to_vec4, vec4_to_rgba8};
    type Fast = fn(Vec4, Vec4) -> Vec4;
    let fast: [(BlendFactor, BlendFactor, Fast); 4] = [
        (BlendFactor::One, BlendFactor::Zero, fast_blend::replace),
        (BlendFactor::DstColor, BlendFactor::Zero, fast_blend::modulate),
        (BlendFactor::DstAlpha, BlendFactor::One, fast_blend::add_by_dst_alpha),
        (BlendFactor::One, BlendFactor::One, fast_blend::add),
    ];
    let mut seed = 12345u32;
    let mut next = || {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        seed
    };
    for (src_factor, dst_factor, f) in fast {
        let blend = Blend::new(src_factor, dst_factor);
        for _ in 0..20_000 {
            let stored = next().to_le_bytes();
            // Source values a little outside [0, 1] too, which the GL clamps first.
            let src: [f32; 4] = std::array::from_fn(|_| (next() % 1400) as f32 / 1000.0 - 0.2);
            let fast = vec4_to_rgba8(f(Vec4::from_array(src).clamp(Vec4::ZERO, Vec4::ONE), rgba8_to_vec4(stored)));
            assert_eq!(
                fast,
                blend_pixel(&blend, src, stored, [true; 4]),
                "{src_factor:?}, {dst_factor:?}: {src:?} over {stored:?}"
            );
        }
    }
}
