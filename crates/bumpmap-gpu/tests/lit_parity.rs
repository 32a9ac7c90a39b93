//! `shading.wgsl`'s `shade()` against its definition, `bumpmap_core::shading::shade`, on random
//! fragments for every self-shadowing and specular-gate mode, whole and fractional shininess,
//! without a specular filter, with Toksvig's, the roughness map's, LEAN's and CLEAN's, on a compute
//! shader.
//!
//! Tolerance: 2e-4 per channel (a twentieth of one 8-bit step, 1/255 ≈ 3.9e-3). Both sides
//! compute in f32; the GPU may fuse multiply-adds in the dot products, and its `pow` for a
//! fractional exponent is `exp2(y·log2 x)` with a few ulps of error each, magnified by the
//! exponent (up to 100 here) where x is near 1.

mod common;

use bumpmap_core::shading::{Fragment, LeanMoments, LitTerms, shade};
use bumpmap_core::technique::{SelfShadow, SpecularFilter, SpecularShadow};
use bumpmap_gpu::{self_shadow_name, shading_wgsl, specular_filter_name, specular_shadow_name};
use glam::{Vec2, Vec3, Vec4};

use common::{Rng, wgsl_literal};

/// A random direction (+Z where the draw has none).
fn vec3(rng: &mut Rng) -> Vec3 {
    Vec3::new(rng.unit() * 2.0 - 1.0, rng.unit() * 2.0 - 1.0, rng.unit() * 2.0 - 1.0).normalize_or(Vec3::Z)
}

#[test]
fn wgsl_shade_is_the_lighting_model() {
    let Some(ctx) = common::context() else { return };
    let mut rng = Rng(17);
    let n = 2048;
    let fragments: Vec<Fragment> = (0..n)
        .map(|_| {
            let (l, h) = (vec3(&mut rng), vec3(&mut rng));
            Fragment {
                normal: Vec4::new(rng.unit(), rng.unit(), rng.unit(), rng.unit()),
                decal: Vec3::new(rng.unit(), rng.unit(), rng.unit()),
                gloss: rng.unit(),
                l,
                h,
                l_n: l.z,
                h_n: h.z,
                light: rng.unit(),
                moments: {
                    // Slopes in [−2, 2] and second moments at least their squares (a spread).
                    let b = Vec2::new(rng.unit() * 4.0 - 2.0, rng.unit() * 4.0 - 2.0);
                    let spread = Vec3::new(rng.unit(), rng.unit() * 0.2 - 0.1, rng.unit());
                    let j = 1.0 + rng.unit() * 10.0;
                    LeanMoments { b, m: Vec3::new(b.x * b.x, b.x * b.y, b.y * b.y) + spread, j }
                },
                // Roughness from 0.35 (exponent 129) to 1: past 0.35 the lobe's peak times its
                // energy factor grows past what an absolute 2e-4 can say of pow's few ulps.
                roughness: 0.35 + rng.unit() * 0.65,
                occlusion: rng.unit(),
            }
        })
        .collect();
    let flat: Vec<f32> = fragments
        .iter()
        .flat_map(|f| {
            let mut v = f.normal.to_array().to_vec();
            v.extend(f.decal.extend(f.gloss).to_array());
            v.extend(f.l.extend(f.light).to_array());
            v.extend(f.h.extend(f.l_n).to_array());
            v.extend([f.h_n, f.moments.b.x, f.moments.b.y, f.moments.m.x]);
            v.extend([f.moments.m.y, f.moments.m.z, f.moments.j, f.roughness]);
            v.extend([f.occlusion, 0.0, 0.0, 0.0]);
            v
        })
        .collect();
    let mut worst = 0f32;
    let mut cases = 0;
    let shading = shading_wgsl();
    for self_shadow in [SelfShadow::Ramp, SelfShadow::Step, SelfShadow::Off] {
        for specular_shadow in [SpecularShadow::Kilgard, SpecularShadow::CgTutorial, SpecularShadow::Off] {
            // The modes by the prelude's names, as lit.wgsl passes them.
            let (ss, sg) = (self_shadow_name(self_shadow), specular_shadow_name(specular_shadow));
            for (shininess, specular_filter) in [8.0f32, 1.0, 33.0, 7.5, 100.0].into_iter().flat_map(|s| {
                [
                    SpecularFilter::None,
                    SpecularFilter::Toksvig,
                    SpecularFilter::RoughnessMap,
                    SpecularFilter::Lean,
                    SpecularFilter::Clean,
                ]
                .map(|f| (s, f))
            }) {
                let sf = specular_filter_name(specular_filter);
                let terms = LitTerms {
                    ambient: Vec3::new(0.2, 0.1, 0.05),
                    diffuse: Vec3::new(0.8, 0.7, 0.9),
                    specular: Vec3::new(1.0, 0.5, 0.25),
                    shininess,
                    self_shadow,
                    specular_shadow,
                    specular_filter,
                };
                let v3 =
                    |v: Vec3| format!("vec3<f32>({}, {}, {})", wgsl_literal(v.x), wgsl_literal(v.y), wgsl_literal(v.z));
                let wgsl = format!(
                    "{shading}
struct In {{ normal: vec4<f32>, decal_gloss: vec4<f32>, l_light: vec4<f32>, h_ln: vec4<f32>, hn: vec4<f32>, m: vec4<f32>, o: vec4<f32> }};
@group(0) @binding(0) var<storage, read> inputs: array<In>;
@group(0) @binding(1) var<storage, read_write> outputs: array<vec4<f32>>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
    if id.x >= arrayLength(&outputs) {{ return; }}
    let i = inputs[id.x];
    let t = Terms({}, {}, {}, {}, {ss}, {sg}, {sf});
    let f = Fragment(i.normal, i.decal_gloss.xyz, i.decal_gloss.w, i.l_light.xyz, i.h_ln.xyz, i.h_ln.w, i.hn.x, i.l_light.w, i.hn.yz, vec3<f32>(i.hn.w, i.m.xy), i.m.z, i.m.w, i.o.x);
    outputs[id.x] = vec4<f32>(shade(t, f), 1.0);
}}",
                    v3(terms.ambient),
                    v3(terms.diffuse),
                    v3(terms.specular),
                    wgsl_literal(shininess)
                );
                let got = common::run_compute(&ctx, &wgsl, common::bytes(&flat), n).expect("shading.wgsl compiles");
                for (f, g) in fragments.iter().zip(&got) {
                    let want = shade(&terms, f);
                    for c in 0..3 {
                        let d = (want[c] - g[c]).abs();
                        worst = worst.max(d);
                        assert!(
                            d <= 2e-4,
                            "{self_shadow:?}, {specular_shadow:?}, {specular_filter:?}, shininess {shininess}: {want} vs {g:?} for {f:?}"
                        );
                    }
                }
                cases += 1;
            }
        }
    }
    println!("shading.wgsl vs bumpmap_core::shading::shade: {cases} term sets x {n} fragments, max |diff| {worst:e}");
}
