//! Detail normals on the GPU: `detail.wgsl`'s `detail_normal()` against its definition,
//! `bumpmap_core::detail::detail_normal`, on random texels for every blend and several
//! strengths (compute shader), then whole renders with a detail map against the CPU pipeline.
//!
//! Tolerances: the function, 2e-5 per channel (both sides compute in f32; the GPU may fuse
//! multiply-adds and its `1 / length` is not the correctly rounded one — a few ulps, magnified
//! by RNM's division by `1 + z`). The renders, 40 dB as `parity.rs` argues: the same texture bytes,
//! the GPU's own λ and filter weights. A render with the detail must also differ from one
//! without it by far more than that, so a detail map the GPU ignored would fail.

mod common;

use std::sync::Arc;

use bumpmap_core::detail::{BlendMethod, DetailLayer, detail_normal};
use bumpmap_core::scenes::{self, SceneKind, SceneParams};
use bumpmap_core::technique::Technique;
use bumpmap_core::{TechniqueName, TechniqueOptions};
use bumpmap_gpu::{detail_name, shading_wgsl};
use bumpmap_math::{HeightPreset, MipChain, MipMode, Named, NormalMapOptions, Rgba8Image};
use glam::Vec4;

use common::{Rng, wgsl_literal};

/// A filtered texel: a direction in the upper hemisphere range-compressed, a length in [0.3, 1].
fn texel(rng: &mut Rng) -> Vec4 {
    let n = glam::Vec3::new(rng.unit() * 2.0 - 1.0, rng.unit() * 2.0 - 1.0, 0.05 + rng.unit()).normalize();
    (n * 0.5 + 0.5).extend(0.3 + 0.7 * rng.unit())
}

#[test]
fn wgsl_detail_normal_is_the_definition() {
    let Some(ctx) = common::context() else { return };
    let mut rng = Rng(5);
    let n = 4096;
    let pairs: Vec<(Vec4, Vec4)> = (0..n).map(|_| (texel(&mut rng), texel(&mut rng))).collect();
    let flat: Vec<f32> = pairs.iter().flat_map(|(b, d)| b.to_array().into_iter().chain(d.to_array())).collect();
    let shading = shading_wgsl();
    let mut worst = 0f32;
    for &method in BlendMethod::ALL {
        for strength in [0.0f32, 0.35, 1.0, 2.5] {
            let wgsl = format!(
                "{shading}
struct In {{ base: vec4<f32>, detail: vec4<f32> }};
@group(0) @binding(0) var<storage, read> inputs: array<In>;
@group(0) @binding(1) var<storage, read_write> outputs: array<vec4<f32>>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
    if id.x >= arrayLength(&outputs) {{ return; }}
    let i = inputs[id.x];
    outputs[id.x] = detail_normal(i.base, i.detail, {}, {});
}}",
                detail_name(Some(method)),
                wgsl_literal(strength)
            );
            let got = common::run_compute(&ctx, &wgsl, common::bytes(&flat), n).expect("detail.wgsl compiles");
            for ((b, d), g) in pairs.iter().zip(&got) {
                let want = detail_normal(*b, *d, method, strength);
                let diff = (want - Vec4::from_array(*g)).abs().max_element();
                worst = worst.max(diff);
                assert!(diff <= 2e-5, "{} at {strength}: {want} vs {g:?} for {b}, {d}", method.name());
            }
        }
    }
    println!("detail.wgsl vs bumpmap_core::detail::detail_normal: max |diff| {worst:e}");
}

const SIZE: usize = 160;

/// The noise preset's normal map, 128², as a tiling detail.
fn noise_detail(method: BlendMethod, strength: f32) -> DetailLayer {
    let field = HeightPreset::Noise(3).render(128, 128);
    let chain =
        MipChain::from_height(&field, &NormalMapOptions { scale: 2.0, ..Default::default() }, MipMode::LengthInAlpha)
            .expect("the noise makes a normal map");
    DetailLayer { map: Arc::new(chain.to_mips()), repeat: 5.0, method, strength }
}

fn render_both(
    gpu: &mut bumpmap_gpu::GpuRenderer,
    kind: &SceneKind,
    params: &SceneParams,
    t: &Technique,
) -> (Rgba8Image, Rgba8Image) {
    let scene = scenes::build(kind, params).unwrap();
    let mut fb = bumpmap_cpu::Framebuffer::new(SIZE, SIZE).unwrap();
    bumpmap_cpu::render(&scene, t, &mut fb).unwrap();
    let cpu = Rgba8Image::new(SIZE, SIZE, fb.to_rgba8());
    (cpu, gpu.render(&scene, t, SIZE, SIZE, |_, _| {}).unwrap())
}

#[test]
fn renders_with_a_detail_map_match_the_cpu() {
    let Some(mut gpu) = common::renderer() else { return };
    let reason = "same bytes, GPU's own λ and filter weights (parity.rs's module docs)";
    let with = |name: TechniqueName, detail: Option<DetailLayer>| {
        let mut t = name.technique(&TechniqueOptions::default());
        let Technique::SinglePass(o) = &mut t else { panic!("{} is a single pass", name.name()) };
        o.detail = detail;
        t
    };
    let mut cases: Vec<(String, SceneKind, TechniqueName, DetailLayer)> = BlendMethod::ALL
        .iter()
        .map(|&m| (format!("torus_{}", m.name()), SceneKind::Torus, TechniqueName::SinglePass, noise_detail(m, 1.0)))
        .collect();
    cases.push((
        "torus_toksvig_half".into(),
        SceneKind::Torus,
        TechniqueName::Toksvig,
        noise_detail(BlendMethod::Rnm, 0.5),
    ));
    cases.push((
        "wall_pom".into(),
        SceneKind::Wall,
        TechniqueName::Pom,
        noise_detail(BlendMethod::PartialDerivative, 1.0),
    ));
    for (case, kind, name, detail) in cases {
        let params = name.scene_params(&SceneParams::default());
        let (cpu, gpu_image) = render_both(&mut gpu, &kind, &params, &with(name, Some(detail)));
        bumpmap_testkit::assert_has_content(&format!("gpu_detail_{case}"), &cpu);
        let psnr = bumpmap_testkit::assert_psnr(&format!("gpu_detail_{case}"), &cpu, &gpu_image, 40.0, reason);
        let (plain, _) = render_both(&mut gpu, &kind, &params, &with(name, None));
        let apart = bumpmap_testkit::psnr(&plain, &cpu);
        assert!(apart < 33.0, "{case}: the detail changed the CPU's image too little ({apart:.1} dB from none)");
        let apart = bumpmap_testkit::psnr(&plain, &gpu_image);
        assert!(apart < 33.0, "{case}: the detail changed the GPU's image too little ({apart:.1} dB from none)");
        println!("{case}: CPU vs GPU {psnr:.1} dB; without the detail {apart:.1} dB");
    }
}
