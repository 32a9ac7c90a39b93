//! `parallax.wgsl`'s `parallax_fragment()` against its definition,
//! `bumpmap_core::parallax::fragment`, on random fragments over bricks: every march, every
//! shadow mode (the horizon map's too), with and without silhouettes, the hit shaded with the
//! normal map's normal or the heights' own, on a compute shader reading
//! the same heights, min–max levels and horizons from a storage buffer.
//!
//! Tolerance: both sides compute in f32, but the GPU may contract multiply-adds and orders a few
//! sums differently, so a march may end one layer apart (or a walk one crossing apart) where the
//! ray grazes a height within rounding. So: the hit within 1e-3 of a texture coordinate (a
//! quarter texel at 256²; far below, 1e-6, in practice) for at least 98 % of the fragments, the
//! discard decision and the shadow on at least 98 %, and L, V and the heights' normal within 1e-3
//! wherever the hits agree.

mod common;

use bumpmap_core::parallax::{
    FragmentHeights, FragmentRays, HitNormal, HorizonLookup, Parallax, ParallaxMethod, ParallaxOptions, ParallaxShadow,
    fragment,
};
use bumpmap_gpu::{parallax_name, parallax_shadow_name, parallax_wgsl};
use bumpmap_math::HeightMips;
use glam::{Vec2, Vec3};

use common::Rng;

/// The heights, their min–max levels and their horizons behind a header, as `data` lays them
/// out.
fn heights_buffer(m: &HeightMips, fragments: &[[f32; 16]]) -> Vec<f32> {
    let levels = m.levels();
    let minmax = m.minmax().unwrap();
    let horizons = m.horizons().unwrap();
    let l = levels.len();
    let frag = 2 + 9 * l;
    let mut texels_at = frag + 16 * fragments.len();
    let mut header = vec![fragments.len() as f32, l as f32];
    let mut texels = Vec::new();
    for level in levels {
        header.extend([level.width as f32, level.height as f32, texels_at as f32]);
        texels.extend_from_slice(&level.texels);
        texels_at += level.texels.len();
    }
    for level in minmax {
        header.extend([level.width as f32, level.height as f32, texels_at as f32]);
        texels.extend(level.texels.iter().flatten());
        texels_at += 2 * level.texels.len();
    }
    for level in horizons.levels() {
        header.extend([level.width as f32, level.height as f32, texels_at as f32]);
        texels.extend(level.texels.iter().flatten());
        texels_at += 8 * level.texels.len();
    }
    assert!(texels_at < 1 << 24, "offsets stay exact in f32");
    header.extend(fragments.iter().flatten());
    header.extend(texels);
    header
}

const HARNESS: &str = "
@group(0) @binding(0) var<storage, read> data: array<f32>;
@group(0) @binding(1) var<storage, read_write> outputs: array<vec4<f32>>;

fn hdr(i: u32) -> u32 {
    return u32(data[i]);
}

fn height_size(level: u32) -> vec2<u32> {
    return vec2<u32>(hdr(2u + 3u * level), hdr(3u + 3u * level));
}

fn height_texel(x: i32, y: i32, level: u32) -> f32 {
    return data[hdr(4u + 3u * level) + u32(y) * hdr(2u + 3u * level) + u32(x)];
}

fn minmax_levels() -> u32 {
    return hdr(1u);
}

fn minmax_size(level: u32) -> vec2<u32> {
    let b = 2u + 3u * hdr(1u) + 3u * level;
    return vec2<u32>(hdr(b), hdr(b + 1u));
}

fn minmax_texel(x: i32, y: i32, level: u32) -> vec2<f32> {
    let b = 2u + 3u * hdr(1u) + 3u * level;
    let o = hdr(b + 2u) + 2u * (u32(y) * hdr(b) + u32(x));
    return vec2<f32>(data[o], data[o + 1u]);
}

fn horizon_size(level: u32) -> vec2<u32> {
    let b = 2u + 6u * hdr(1u) + 3u * level;
    return vec2<u32>(hdr(b), hdr(b + 1u));
}

fn horizon_texel(x: i32, y: i32, level: u32, half: u32) -> vec4<f32> {
    let b = 2u + 6u * hdr(1u) + 3u * level;
    let o = hdr(b + 2u) + 8u * (u32(y) * hdr(b) + u32(x)) + 4u * half;
    return vec4<f32>(data[o], data[o + 1u], data[o + 2u], data[o + 3u]);
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= hdr(0u) {
        return;
    }
    let b = 2u + 9u * hdr(1u) + 16u * id.x;
    let f = parallax_fragment(
        vec2<f32>(data[b], data[b + 1u]),
        vec3<f32>(data[b + 2u], data[b + 3u], data[b + 4u]),
        vec3<f32>(data[b + 5u], data[b + 6u], data[b + 7u]),
        vec4<f32>(data[b + 8u], data[b + 9u], data[b + 10u], data[b + 11u]),
        vec2<f32>(data[b + 12u], data[b + 13u]),
        DEPTH,
        LAYERS,
        data[b + 15u] > 0.5,
        hdr(b + 14u),
    );
    outputs[4u * id.x] = vec4<f32>(f.st, f.light, f.kappa);
    outputs[4u * id.x + 1u] = vec4<f32>(f.l, select(0.0, 1.0, f.ok));
    outputs[4u * id.x + 2u] = vec4<f32>(f.v, 0.0);
    outputs[4u * id.x + 3u] = vec4<f32>(f.normal, f.occlusion);
}
";

#[test]
fn wgsl_parallax_fragment_is_the_cores() {
    let Some(ctx) = common::context() else { return };
    let heights = HeightMips::from_field(&bumpmap_math::HeightPreset::Bricks.render(64, 32)).unwrap();
    let (depth, layers) = (0.05f32, 24u32);
    let mut rng = Rng(5);
    // Fragments on a wall of texels 1/32 of a unit (s per unit 2, t per unit 1: unequal), seen
    // from 0° to 87°, lights from 5° to 85° above the plane, a point light half the time; the
    // curvature of a sphere of radius 1 or 2 or of a saddle.
    let fragments: Vec<[f32; 16]> = (0..512)
        .map(|i| {
            let theta = (rng.unit() * 87.0).to_radians();
            let phi = rng.unit() * std::f32::consts::TAU;
            let eye =
                Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()) * (1.0 + 3.0 * rng.unit());
            let lift = (5.0 + 80.0 * rng.unit()).to_radians();
            let az = rng.unit() * std::f32::consts::TAU;
            let light = Vec3::new(lift.cos() * az.cos(), lift.cos() * az.sin(), lift.sin()) * 2.0;
            let jacobian = [0.5, 0.05 * (rng.unit() - 0.5), 0.0, 1.0];
            let frame = bumpmap_core::parallax::TextureFrame { jacobian, depth };
            let (to_eye, to_light) = (frame.to_texture(eye), frame.to_texture(light));
            let curvature = match i % 3 {
                0 => Vec2::new(0.5, 0.5) / depth * 0.25,
                1 => Vec2::new(0.25, 0.25) / depth * 0.25,
                _ => Vec2::new(0.3, -0.3) / depth * 0.25,
            };
            let level = if i % 5 == 0 { 1.0 } else { 0.0 };
            let st = Vec2::new(rng.unit() * 3.0, rng.unit() * 2.0);
            [
                st.x,
                st.y,
                to_eye.x,
                to_eye.y,
                to_eye.z,
                to_light.x,
                to_light.y,
                to_light.z,
                jacobian[0],
                jacobian[1],
                jacobian[2],
                jacobian[3],
                curvature.x,
                curvature.y,
                level,
                (i % 2) as f32,
            ]
        })
        .collect();
    let data = heights_buffer(&heights, &fragments);
    let program =
        format!("{}\nconst DEPTH: f32 = {depth:?};\nconst LAYERS: u32 = {layers}u;\n{HARNESS}", parallax_wgsl());
    let levels = heights.levels();
    let exact = FragmentHeights { level0: &levels[0], minmax: Some(heights.minmax().unwrap()) };
    let horizons = heights.horizons().unwrap();
    let mut worst = 0f32;
    for method in ParallaxMethod::ALL {
        for shadow in ParallaxShadow::ALL {
            for (silhouettes, hit_normal) in
                [false, true].into_iter().flat_map(|s| [HitNormal::Map, HitNormal::Heights].map(|h| (s, h)))
            {
                // Ambient occlusion from the horizon map along with its shadows.
                let ambient_occlusion = shadow == ParallaxShadow::Horizon;
                let constants = [
                    ("PARALLAX", code(parallax_name(Some(method)))),
                    ("PARALLAX_SHADOW", code(parallax_shadow_name(shadow))),
                    ("SILHOUETTES", silhouettes as u32 as f64),
                    ("AMBIENT_OCCLUSION", ambient_occlusion as u32 as f64),
                    ("HIT_NORMAL_HEIGHTS", (hit_normal == HitNormal::Heights) as u32 as f64),
                ];
                let got =
                    common::run_compute_with(&ctx, &program, common::bytes(&data), 4 * fragments.len(), &constants)
                        .expect("parallax.wgsl compiles");
                let options = ParallaxOptions {
                    layers,
                    shadow,
                    silhouettes,
                    write_depth: true,
                    ambient_occlusion,
                    hit_normal: Some(hit_normal),
                };
                let p = Parallax { method, options };
                let (mut hits, mut decisions, mut shadows, mut occluded) = (0, 0, 0, 0);
                for (i, f) in fragments.iter().enumerate() {
                    let rays = FragmentRays {
                        st: Vec2::new(f[0], f[1]),
                        to_eye: Vec3::new(f[2], f[3], f[4]),
                        to_light: Vec3::new(f[5], f[6], f[7]),
                        jacobian: [f[8], f[9], f[10], f[11]],
                        curvature: Vec2::new(f[12], f[13]),
                    };
                    let level = &levels[f[14] as usize];
                    let mut sample = |st: Vec2| level.bilinear(st.x, st.y);
                    let mut sample_horizons = |st: Vec2| horizons.levels()[f[14] as usize].bilinear(st.x, st.y);
                    let size = Vec2::new(levels[0].width as f32, levels[0].height as f32);
                    let lookup = HorizonLookup { size, sample: &mut sample_horizons };
                    let want = fragment(&rays, &p, depth, f[15] > 0.5, &mut sample, exact, Some(lookup));
                    let g = &got[4 * i..4 * i + 4];
                    let ok = g[1][3] > 0.5;
                    if ok != want.is_some() {
                        continue;
                    }
                    decisions += 1;
                    let Some(want) = want else {
                        hits += 1;
                        shadows += 1;
                        continue;
                    };
                    let st = Vec2::new(g[0][0], g[0][1]);
                    if (st - want.st).abs().max_element() > 1e-3 {
                        continue;
                    }
                    hits += 1;
                    if (g[0][2] - want.light).abs() <= 1e-2 {
                        shadows += 1;
                    }
                    let v3 = |a: [f32; 4]| Vec3::new(a[0], a[1], a[2]);
                    for (a, b) in [(v3(g[1]), want.l), (v3(g[2]), want.v)] {
                        let d = (a - b).length() / b.length().max(1e-6);
                        worst = worst.max(d);
                        assert!(d < 1e-3, "{method:?} {shadow:?}: {a} vs {b} (fragment {i})");
                    }
                    assert!(
                        (g[3][3] - want.occlusion).abs() < 1e-4,
                        "{method:?} {shadow:?}: occlusion {} vs {}",
                        g[3][3],
                        want.occlusion
                    );
                    occluded += (want.occlusion < 0.95) as usize;
                    assert_eq!(want.normal.is_some(), hit_normal == HitNormal::Heights, "{method:?} {hit_normal:?}");
                    if let Some(n) = want.normal {
                        assert!((v3(g[3]) - n).length() < 1e-3, "{method:?}: normal {} vs {n}", v3(g[3]));
                    }
                }
                let n = fragments.len();
                let share = |k: usize| k as f32 / n as f32;
                println!(
                    "{method:?} {shadow:?} silhouettes {silhouettes} {hit_normal:?}: hits {:.3}, discards {:.3}, shadows {:.3}",
                    share(hits),
                    share(decisions),
                    share(shadows)
                );
                assert!(
                    share(decisions) >= 0.98,
                    "{method:?} {shadow:?} {silhouettes}: discards agree on {decisions}/{n}"
                );
                assert!(share(hits) >= 0.98, "{method:?} {shadow:?} {silhouettes}: hits agree on {hits}/{n}");
                assert!(share(shadows) >= 0.98, "{method:?} {shadow:?} {silhouettes}: shadows agree on {shadows}/{n}");
                if ambient_occlusion {
                    assert!(
                        occluded > 20,
                        "{method:?}: only {occluded} fragments occluded: the check would be vacuous"
                    );
                }
                if shadow == ParallaxShadow::Horizon {
                    let dark = got.chunks(4).filter(|g| g[1][3] > 0.5 && g[0][2] < 0.5).count();
                    assert!(dark > 20, "{method:?}: only {dark} fragments in the horizon's shadow");
                }
            }
        }
    }
    println!("parallax.wgsl vs bumpmap_core::parallax::fragment: max relative |ΔL|, |ΔV| {worst:e}");
}

/// A switch value's code, by its name in the prelude.
fn code(name: &str) -> f64 {
    let prelude = parallax_wgsl();
    let line = prelude.lines().find(|l| l.starts_with(&format!("const {name}: u32 = "))).expect(name);
    line.rsplit(' ').next().unwrap().trim_end_matches(';').trim_end_matches('u').parse().unwrap()
}
