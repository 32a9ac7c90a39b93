//! The reference renderer's promises: it converges, it agrees with the normal map where the
//! normal map is exact, and it refuses what it cannot evaluate.

use bumpmap_core::scenes::{SceneKind, SceneParams, build};
use bumpmap_reference::{LinearImage, ReferenceError, ReferenceOptions, render};

fn rmse(a: &LinearImage, b: &LinearImage) -> f32 {
    let sum: f32 = a.pixels.iter().zip(&b.pixels).map(|(p, q)| (*p - *q).length_squared()).sum();
    (sum / (3 * a.pixels.len()) as f32).sqrt()
}

fn reference(kind: SceneKind, size: usize, spp: usize) -> LinearImage {
    let scene = build(&kind, &SceneParams::default()).unwrap();
    render(&scene, size, size, &ReferenceOptions { samples_per_pixel: spp, ..Default::default() }, &|_, _| {}).unwrap()
}

#[test]
fn the_error_between_k_and_4k_samples_falls_as_k_grows() {
    let images: Vec<LinearImage> = [1, 4, 16, 64].map(|k| reference(SceneKind::Torus, 48, k)).into();
    let errors: Vec<f32> = images.windows(2).map(|w| rmse(&w[0], &w[1])).collect();
    // Stratified samples: each quadrupling should cut the error well below 1/√4 = 0.5 of the
    // last; 0.8 leaves room for the silhouette pixels that converge more slowly.
    assert!(errors[1] < 0.8 * errors[0] && errors[2] < 0.8 * errors[1], "{errors:?}");
    // Not a black image: the torus covers a good part of the frame, lit.
    let mean: f32 = images[3].pixels.iter().map(|c| c.x + c.y + c.z).sum::<f32>() / (3 * 48 * 48) as f32;
    assert!(mean > 0.1, "mean {mean}");
}

#[test]
fn another_seed_is_an_independent_estimate_of_the_same_image() {
    let scene = build(&SceneKind::Torus, &SceneParams::default()).unwrap();
    let at = |spp, seed| {
        let options = ReferenceOptions { samples_per_pixel: spp, seed, ..Default::default() };
        render(&scene, 48, 48, &options, &|_, _| {}).unwrap()
    };
    let (zero, one, two) = (at(4, 0), at(4, 1), at(4, 2));
    assert_eq!(zero, at(4, 0), "a seed is the same image every run");
    assert_ne!(zero, one, "another seed, other samples");
    // Both estimate the same image: each as near the 256-sample one as seed 0's is, within a
    // third (the silhouette pixels are the noisy ones and differ from seed to seed).
    let truth = at(256, 7);
    let (e0, e1, e2) = (rmse(&zero, &truth), rmse(&one, &truth), rmse(&two, &truth));
    assert!(e1 < 1.33 * e0 && e2 < 1.33 * e0 && e0 < 1.33 * e1, "{e0} {e1} {e2}");
    // Independent: two seeds differ by about as much as each differs from the truth (√2 as much
    // for independent errors), not by next to nothing.
    let between = rmse(&one, &two);
    assert!(between > 0.8 * e1, "{between} against {e1}");
}

#[test]
fn progress_reaches_every_tile_once() {
    let scene = build(&SceneKind::Wall, &SceneParams::default()).unwrap();
    let calls = std::sync::Mutex::new(Vec::new());
    render(&scene, 40, 20, &ReferenceOptions { samples_per_pixel: 1, ..Default::default() }, &|d, t| {
        calls.lock().unwrap().push((d, t))
    })
    .unwrap();
    let mut calls = calls.into_inner().unwrap();
    calls.sort();
    assert_eq!(calls, (1..=6).map(|d| (d, 6)).collect::<Vec<_>>(), "3×2 tiles of 16²");
}

#[test]
fn what_the_reference_cannot_evaluate_is_refused() {
    let scene = build(&SceneKind::Wall, &SceneParams::default()).unwrap();
    let opts = |k| ReferenceOptions { samples_per_pixel: k, ..Default::default() };
    assert_eq!(render(&scene, 8, 8, &opts(0), &|_, _| {}), Err(ReferenceError::SamplesPerPixel { got: 0, max: 4096 }));
    assert!(matches!(render(&scene, 0, 8, &opts(1), &|_, _| {}), Err(ReferenceError::Size { .. })));
    let mesh = bumpmap_math::surface::Surface::default_torus().tessellate(8, 4, glam::Vec2::ONE);
    let scene = build(&SceneKind::Mesh(std::sync::Arc::new(mesh)), &SceneParams::default()).unwrap();
    assert_eq!(render(&scene, 8, 8, &opts(1), &|_, _| {}), Err(ReferenceError::NoSurface { object: 0 }));
}
