//! The GPU backend's failure paths: each is an error value with a message, never a panic.

mod common;

use std::sync::Arc;

use bumpmap_core::scenes::{self, SceneKind, SceneParams};
use bumpmap_core::technique::{KilgardOptions, SinglePassOptions, Technique};
use bumpmap_gpu::GpuError;
use bumpmap_math::{Rgba8Image, Rgba8Mips};

#[test]
fn a_lost_device_is_an_error_not_a_panic() {
    let Some(mut gpu) = common::renderer() else { return };
    let scene = scenes::build(&SceneKind::Torus, &SceneParams::default()).unwrap();
    let technique = Technique::Kilgard(KilgardOptions::default());
    gpu.render(&scene, &technique, 32, 32, |_, _| {}).expect("renders before the loss");
    gpu.context().lose_device();
    let err = gpu.render(&scene, &technique, 32, 32, |_, _| {}).expect_err("a lost device cannot render");
    assert!(matches!(err, GpuError::DeviceLost(_)), "{err:?}");
    assert!(err.to_string().contains("device was lost"), "{err}");
}

#[test]
fn textures_and_framebuffers_past_the_adapters_limit_are_refused() {
    let Some(mut gpu) = common::renderer() else { return };
    let max = gpu.context().max_texture_side() as usize;
    let technique = Technique::SinglePass(SinglePassOptions::default());
    let scene = scenes::build(&SceneKind::Wall, &SceneParams::default()).unwrap();
    let err = gpu.render(&scene, &technique, max + 1, 4, |_, _| {}).expect_err("too wide a framebuffer");
    assert!(matches!(err, GpuError::TooLarge { what: "the framebuffer", .. }), "{err:?}");
    // A decal one texel wider than the adapter allows (one row: small in memory).
    let mut scene = scene;
    scene.objects[0].material.decal =
        Some(Arc::new(Rgba8Mips::single(Rgba8Image::new(max + 1, 1, vec![[200; 4]; max + 1]))));
    let err = gpu.render(&scene, &technique, 32, 32, |_, _| {}).expect_err("too wide a texture");
    assert!(matches!(err, GpuError::TooLarge { what: "a texture", .. }), "{err:?}");
    assert!(err.to_string().contains(&format!("limit of {max}")), "{err}");
    let err = gpu.render(&scene, &technique, 0, 32, |_, _| {}).expect_err("an empty framebuffer");
    assert!(matches!(err, GpuError::EmptyFramebuffer { .. }), "{err:?}");
    // The renderer still works after refusing.
    let ok = scenes::build(&SceneKind::Wall, &SceneParams::default()).unwrap();
    gpu.render(&ok, &technique, 32, 32, |_, _| {}).expect("renders after the refusals");
}
