//! The GPU backend against the CPU pipeline on the same scenes and techniques: PSNR ≥ 40 dB
//! over RGB, with the actual, expected and difference images written on failure
//! (`bumpmap_testkit::assert_psnr`).
//!
//! Why 40 dB: the two backends rasterize the same triangles and share every texture byte and
//! the vertex stage, but a GPU computes its own mipmap λ (from per-pixel derivatives, not the
//! CPU's once-per-quad GL 1.2 formula), its own bilinear weights (8 bits of sub-texel
//! precision on lavapipe) and may fuse multiply-adds, so texels near a filter boundary differ
//! by a few steps. The CPU renderer matches an OpenGL render of the llvmpipe peer's scene at
//! 48.5 dB; 40 dB (an RMS error of 2.5/255) leaves room for that and still fails on any real
//! difference of lighting, orientation or blending (a wrong sign or blend is below 25 dB).

mod common;

use std::sync::Arc;

use bumpmap_core::combiners::Precision;
use bumpmap_core::scene::{Attenuation, SceneLight, Spot};
use bumpmap_core::scenes::{self, SceneKind, SceneParams};
use bumpmap_core::technique::{
    Gloss, HalfAngle, KilgardOptions, Normalize, SelfShadow, SinglePassOptions, SpecularFilter, SpecularShadow,
    Technique,
};
use bumpmap_core::{BumpMap, BumpSource};
use bumpmap_gpu::GpuRenderer;
use bumpmap_math::lighting::Light;
use bumpmap_math::tangent::TangentDecode;
use bumpmap_math::{HeightPreset, Rgba8Image, Rgba8Mips};
use glam::Vec3;

const SIZE: usize = 160;
const MIN_PSNR: f64 = 40.0;
const REASON: &str = "same bytes, GPU's own λ and filter weights (see the module docs)";

fn cpu(kind: &SceneKind, params: &SceneParams, technique: &Technique) -> Rgba8Image {
    let scene = scenes::build(kind, params).unwrap();
    let mut fb = bumpmap_cpu::Framebuffer::new(SIZE, SIZE).unwrap();
    bumpmap_cpu::render(&scene, technique, &mut fb).unwrap();
    Rgba8Image::new(SIZE, SIZE, fb.to_rgba8())
}

fn check(gpu: &mut GpuRenderer, name: &str, kind: SceneKind, params: SceneParams, technique: Technique) -> f64 {
    let scene = scenes::build(&kind, &params).unwrap();
    let actual = gpu.render(&scene, &technique, SIZE, SIZE, |_, _| {}).unwrap();
    let expected = cpu(&kind, &params, &technique);
    bumpmap_testkit::assert_psnr(name, &expected, &actual, MIN_PSNR, REASON)
}

fn kilgard() -> Technique {
    Technique::Kilgard(KilgardOptions::default())
}

fn single(options: SinglePassOptions) -> Technique {
    Technique::SinglePass(options)
}

/// A real mesh file (the MikkTSpace test cube, loaded and given tangents as `render` does).
fn mesh() -> SceneKind {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/cube.obj");
    let loaded = bumpmap_io::load_mesh(std::path::Path::new(path)).unwrap();
    let (mesh, _) = bumpmap_math::tangent::generate_tangents(&loaded.mesh, &Default::default()).unwrap();
    SceneKind::Mesh(Arc::new(mesh))
}

#[test]
fn both_techniques_match_the_cpu_on_every_kind_of_scene() {
    let Some(mut gpu) = common::renderer() else { return };
    let sp = || single(SinglePassOptions::default());
    let flat = || SceneParams { default_decal: true, ..Default::default() };
    let pinwheel = || SceneParams {
        bumps: BumpSource::Heights(Arc::new(HeightPreset::Pinwheel.render(256, 256))),
        ..Default::default()
    };
    let cases: Vec<(&str, SceneKind, SceneParams)> = vec![
        ("torus", SceneKind::Torus, SceneParams::default()),
        ("wall_floor", SceneKind::WallFloor, flat()),
        ("patch", SceneKind::Patch, pinwheel()),
        ("mesh", mesh(), SceneParams::default()),
    ];
    for (name, kind, params) in cases {
        check(&mut gpu, &format!("gpu_kilgard_{name}"), kind.clone(), params.clone(), kilgard());
        check(&mut gpu, &format!("gpu_single_pass_{name}"), kind, params, sp());
    }
}

#[test]
fn the_single_pass_model_matches_the_cpu_feature_by_feature() {
    let Some(mut gpu) = common::renderer() else { return };
    let at = |x, y, z| SceneLight::white(Light::Positional(Vec3::new(x, y, z)));
    let two = SceneParams {
        lights: vec![
            SceneLight { color: Vec3::new(1.0, 0.35, 0.2), ..at(4.0, -3.0, 3.0) },
            SceneLight {
                color: Vec3::new(0.2, 0.45, 1.0),
                ..SceneLight::white(Light::Directional(Vec3::new(-1.0, -1.0, 1.0).normalize()))
            },
        ],
        ..Default::default()
    };
    check(&mut gpu, "gpu_sp_two_lights", SceneKind::Torus, two, single(SinglePassOptions::default()));
    let gloss = Rgba8Image::from_gray(256, 256, &bumpmap_math::height::bricks_gloss(256, 256));
    let options =
        SinglePassOptions { gloss: Gloss::Map(Arc::new(Rgba8Mips::with_box_mipmaps(gloss))), ..Default::default() };
    check(
        &mut gpu,
        "gpu_sp_gloss",
        SceneKind::Torus,
        SceneParams { shininess: 40.0, ..Default::default() },
        single(options),
    );
    let field = HeightPreset::Pinwheel.render(64, 64);
    let pattern = Rgba8Mips::single(Rgba8Image::from_gray(64, 64, &field.to_u8()));
    let spot = Spot { direction: Vec3::NEG_Z, cutoff_degrees: 30.0, exponent: 2.0, pattern: Some(Arc::new(pattern)) };
    let spot = SceneParams {
        lights: vec![SceneLight { spot: Some(spot), ..at(0.0, 0.0, 4.0) }],
        specular: Vec3::splat(0.3),
        ..Default::default()
    };
    check(&mut gpu, "gpu_sp_spotlight", SceneKind::Wall, spot, single(SinglePassOptions::default()));
    for (name, attenuation) in [
        ("polynomial", Attenuation::Polynomial { constant: 0.2, linear: 0.0, quadratic: 0.5 }),
        ("exp", Attenuation::Exponential { density: 0.4 }),
        ("exp2", Attenuation::ExponentialSquared { density: 0.4 }),
    ] {
        let params = SceneParams {
            lights: vec![SceneLight { attenuation, ..at(0.0, 0.6, 0.5) }],
            eye: Some(Vec3::new(0.0, 3.0, 6.0)),
            ..Default::default()
        };
        check(
            &mut gpu,
            &format!("gpu_sp_attenuation_{name}"),
            SceneKind::Floor,
            params,
            single(SinglePassOptions::default()),
        );
    }
    // MikkTSpace's per-pixel decode: the frame's varyings and the decode on both backends.
    for (name, kind) in [("mesh", mesh()), ("torus", SceneKind::Torus)] {
        let params = SceneParams { decode: Some(TangentDecode::MikkTSpace), shininess: 20.0, ..Default::default() };
        let options = SinglePassOptions { specular_filter: SpecularFilter::Toksvig, ..Default::default() };
        check(&mut gpu, &format!("gpu_sp_per_pixel_decode_{name}"), kind, params, single(options));
    }
    let object = SceneParams { bump_map: BumpMap::ObjectSpace, ..Default::default() };
    check(&mut gpu, "gpu_sp_object_space", SceneKind::Torus, object, single(SinglePassOptions::default()));
    let variants = [
        ("cube", SinglePassOptions { normalize: Normalize::Cube, ..Default::default() }),
        ("fragment_h", SinglePassOptions { half_angle: HalfAngle::Fragment, ..Default::default() }),
        (
            "step_cg",
            SinglePassOptions {
                self_shadow: SelfShadow::Step,
                specular_shadow: SpecularShadow::CgTutorial,
                ..Default::default()
            },
        ),
        (
            "off",
            SinglePassOptions {
                self_shadow: SelfShadow::Off,
                specular_shadow: SpecularShadow::Off,
                ..Default::default()
            },
        ),
    ];
    for (name, options) in variants {
        let params = SceneParams { shininess: 13.5, ..Default::default() };
        check(&mut gpu, &format!("gpu_sp_{name}"), SceneKind::Torus, params, single(options));
    }
    // The specular filters, each with its own textures on the GPU (a roughness map; LEAN's two
    // half-float moment textures; CLEAN's one), at a shininess where they act.
    for filter in [SpecularFilter::Toksvig, SpecularFilter::RoughnessMap, SpecularFilter::Lean, SpecularFilter::Clean] {
        let params = SceneParams { shininess: 32.0, ..Default::default() };
        let options = SinglePassOptions { specular_filter: filter, ..Default::default() };
        check(&mut gpu, &format!("gpu_sp_{filter:?}"), SceneKind::Torus, params, single(options));
    }
}

#[test]
fn every_parallax_technique_matches_the_cpu() {
    // The marches themselves agree exactly (parallax_parity.rs); here the whole pipeline: the
    // texture-space varyings, the heights' textures and level choice, the late depth test.
    use bumpmap_core::catalogue::{TechniqueName, TechniqueOptions};
    use bumpmap_core::parallax::{ParallaxOptions, ParallaxShadow};
    let Some(mut gpu) = common::renderer() else { return };
    let grazing = Vec3::new(0.0, -75f32.to_radians().sin(), 75f32.to_radians().cos()) * 1.2;
    let cases: Vec<(&str, SceneKind, SceneParams, ParallaxOptions)> = vec![
        (
            "wall_75_hard",
            SceneKind::Wall,
            SceneParams {
                eye: Some(grazing),
                depth: Some(0.06),
                lights: vec![SceneLight::white(Light::Directional(Vec3::new(0.8, -0.3, 0.5).normalize()))],
                ..Default::default()
            },
            ParallaxOptions { shadow: ParallaxShadow::Hard, ..Default::default() },
        ),
        (
            "torus_silhouettes_soft",
            SceneKind::Torus,
            SceneParams { depth: Some(0.15), ..Default::default() },
            ParallaxOptions { silhouettes: true, shadow: ParallaxShadow::Soft, ..Default::default() },
        ),
        (
            "wall_low_light_horizon_occlusion",
            SceneKind::Wall,
            SceneParams {
                lights: vec![SceneLight::white(Light::Directional(Vec3::new(0.9, 0.3, 0.34).normalize()))],
                ..Default::default()
            },
            ParallaxOptions { shadow: ParallaxShadow::Horizon, ambient_occlusion: true, ..Default::default() },
        ),
        (
            "wall_floor_write_depth",
            SceneKind::WallFloor,
            SceneParams { depth: Some(0.1), ..Default::default() },
            ParallaxOptions { write_depth: true, layers: 16, ..Default::default() },
        ),
    ];
    for name in TechniqueName::ALL.into_iter().filter(|n| n.parallax_method().is_some()) {
        for (case, kind, params, parallax) in &cases {
            let technique = name.technique(&TechniqueOptions { parallax: *parallax, ..Default::default() });
            let label = format!("gpu_{}_{case}", name.name());
            // Two black images would agree: the CPU's must show the lit surface.
            bumpmap_testkit::assert_has_content(&label, &cpu(kind, &name.scene_params(params), &technique));
            check(&mut gpu, &label, kind.clone(), name.scene_params(params), technique);
        }
    }
}

#[test]
fn the_three_passes_match_the_cpu_in_every_variant() {
    let Some(mut gpu) = common::renderer() else { return };
    let fixed9 = Technique::Kilgard(KilgardOptions { precision: Precision::Fixed9, ..Default::default() });
    check(&mut gpu, "gpu_kilgard_fixed9", SceneKind::Torus, SceneParams::default(), fixed9);
    let ramp = Technique::Kilgard(KilgardOptions {
        specular: bumpmap_core::technique::SpecularMode::Ramp,
        self_shadow: false,
        ..Default::default()
    });
    check(&mut gpu, "gpu_kilgard_ramp_unshadowed", SceneKind::Torus, SceneParams::default(), ramp);
    // Further lights: decal-modulated diffuse by a constant blend colour, s_self into alpha
    // alone (colour mask), specular by destination alpha.
    let lights = vec![
        SceneLight::white(Light::Positional(Vec3::new(4.0, -3.0, 3.0))),
        SceneLight {
            color: Vec3::new(0.3, 0.5, 1.0),
            ..SceneLight::white(Light::Positional(Vec3::new(-4.0, -3.0, 3.0)))
        },
    ];
    check(
        &mut gpu,
        "gpu_kilgard_two_lights",
        SceneKind::Torus,
        SceneParams { lights, ..Default::default() },
        kilgard(),
    );
    let no_decal = SceneParams { default_decal: false, ..Default::default() };
    check(&mut gpu, "gpu_kilgard_no_decal", SceneKind::Sphere, no_decal, kilgard());
}

#[test]
fn embossing_matches_the_cpu_forced_and_unforced() {
    // Two height fetches (one at the vertex stage's shifted coordinates), the cube map's L_z in
    // the alpha portion, two general combiners, MODULATE over the decal.
    let Some(mut gpu) = common::renderer() else { return };
    use bumpmap_core::technique::{BackFacing, EmbossOptions};
    let side = SceneParams {
        lights: vec![SceneLight::white(Light::Directional(Vec3::new(1.0, 0.0, 0.2)))],
        ..Default::default()
    };
    check(
        &mut gpu,
        "gpu_emboss",
        SceneKind::Torus,
        SceneParams::default(),
        Technique::Emboss(EmbossOptions::default()),
    );
    let unforced = Technique::Emboss(EmbossOptions { back_facing: BackFacing::Unforced, ..Default::default() });
    check(&mut gpu, "gpu_emboss_unforced", SceneKind::Sphere, side, unforced);
}

#[test]
fn an_offset_map_matches_the_cpu() {
    // Kilgard Eq. 7 per fragment after filtering: lit.wgsl's offset_to_normal against the core's.
    let Some(mut gpu) = common::renderer() else { return };
    let params = SceneParams { bump_map: BumpMap::Offset, ..Default::default() };
    check(&mut gpu, "gpu_offset_map", SceneKind::Torus, params, single(SinglePassOptions::default()));
    // Peercy Figure 2: the same texels as slopes, Blinn per fragment from the interpolated
    // surface derivatives (var::PARAM_FRAME), on the sheared patch.
    let params = SceneParams { bump_map: BumpMap::Derivatives, ..Default::default() };
    check(&mut gpu, "gpu_per_pixel_blinn", SceneKind::Patch, params, single(SinglePassOptions::default()));
    // Peercy Figure 6: a tangent-space map made for the patch, addressed across it once
    // (NormalSpace::SurfaceTangent's coordinate scale), lit in tangent space.
    let params = SceneParams {
        bump_map: BumpMap::SurfaceDependent,
        repeat: Some(glam::Vec2::new(2.0, 1.0)),
        ..Default::default()
    };
    check(&mut gpu, "gpu_surface_dependent", SceneKind::Patch, params, single(SinglePassOptions::default()));
}

#[test]
fn pass_snapshots_are_the_figure_12_passes() {
    let Some(mut gpu) = common::renderer() else { return };
    let scene = scenes::build(&SceneKind::Torus, &SceneParams::default()).unwrap();
    let mut names = Vec::new();
    let mut shots = Vec::new();
    let last = gpu
        .render(&scene, &kilgard(), SIZE, SIZE, |name, image| {
            names.push(name.to_string());
            shots.push(image.clone());
        })
        .unwrap();
    assert_eq!(names, ["decal", "diffuse", "specular"]);
    assert_eq!(shots[2], last, "the last snapshot is the frame");
    let mean = |i: &Rgba8Image| i.texels.iter().map(|p| p[0] as f64).sum::<f64>() / i.texels.len() as f64;
    assert!(mean(&shots[1]) < mean(&shots[0]), "pass 2 modulates the decal by light ≤ 1");
    assert!(mean(&shots[2]) > mean(&shots[1]), "pass 3 adds the specular");
}

#[test]
fn the_threshold_catches_a_wrong_bump_direction() {
    // A negative control: the bumps inverted (scale −4 instead of 4) must fall well below the
    // threshold, or 40 dB would prove nothing.
    let Some(mut gpu) = common::renderer() else { return };
    let inverted = SceneParams {
        normal_map: bumpmap_math::NormalMapOptions { scale: -4.0, ..Default::default() },
        ..Default::default()
    };
    let scene = scenes::build(&SceneKind::Torus, &inverted).unwrap();
    let wrong = gpu.render(&scene, &kilgard(), SIZE, SIZE, |_, _| {}).unwrap();
    let right = cpu(&SceneKind::Torus, &SceneParams::default(), &kilgard());
    let db = bumpmap_testkit::psnr(&right, &wrong);
    println!("inverted bumps: {db:.2} dB");
    assert!(db < MIN_PSNR - 5.0, "inverted bumps give {db:.2} dB");
}
