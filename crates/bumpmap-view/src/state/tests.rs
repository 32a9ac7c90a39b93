//! The viewer's model without a window: every key's effect.

use std::sync::Arc;

use bumpmap::frame::FrameRequest;
use bumpmap::option_table::{SCENE, find};
use glam::Vec3;

use super::*;

/// The viewer on the scene options `--flag value` pairs give (through `render`'s option table,
/// as `bumpmap view` reads them), a coarse torus by default.
fn viewer(extra: &[&str]) -> Viewer {
    let mut words = vec!["--tessellation", "16,8"];
    words.extend_from_slice(extra);
    let mut request = FrameRequest::default();
    for pair in words.chunks(2) {
        let row = find(SCENE, pair[0].trim_start_matches("--")).expect("an option of the scene");
        row.set(&mut request, row.parse_text(pair[1]).expect("a value")).expect("sets");
    }
    Viewer::new(request.options).unwrap()
}

/// A 16² detail map of tilted normals (a checker of two slopes), written once per test run (the
/// tests run in parallel: one writing it while another read it was a flaky failure).
fn detail_map() -> String {
    static MAP: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    MAP.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("bumpmap-view-detail-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let map = dir.join("detail.png");
        let tilt = |x: u32, y: u32| {
            if (x / 2 + y / 2).is_multiple_of(2) { [200, 128, 230, 255] } else { [56, 128, 230, 255] }
        };
        image::RgbaImage::from_fn(16, 16, |x, y| image::Rgba(tilt(x, y))).save(&map).unwrap();
        map.to_str().unwrap().to_string()
    })
    .clone()
}

fn normal_texels(v: &Viewer) -> Vec<[u8; 4]> {
    v.prepared.scene.objects[0].material.normal_map.levels()[0].texels.clone()
}

#[test]
fn every_key_changes_what_it_names_and_toggles_come_back() {
    for action in Action::ALL {
        // The depth keys change heights as geometry, which the default technique has none of;
        // the shininess keys a shininess, which its combiners fix at 8.
        let detail = detail_map();
        let extra: &[&str] = match action {
            Action::DepthUp | Action::DepthDown => &["--technique", "pom"],
            Action::ShininessUp | Action::ShininessDown => &["--technique", "single-pass"],
            Action::Detail => &["--technique", "single-pass", "--detail-map", &detail],
            _ => &[],
        };
        let mut v = viewer(extra);
        let (choices, view) = (v.choices.clone(), v.view);
        let effect = v.apply(action);
        match action {
            Action::Screenshot => assert_eq!(effect, Effect::Screenshot),
            Action::Backend => assert_eq!(effect, Effect::SwitchBackend),
            Action::Quit => assert_eq!(effect, Effect::Quit),
            // At the start there is nothing to reset.
            Action::ResetView => assert_eq!(v.view, view),
            _ => {
                assert_eq!(effect, Effect::Redraw);
                assert!(v.choices != choices || v.view != view, "{action:?} changed nothing");
                assert_eq!(v.message, None, "{action:?}: {:?}", v.message);
            }
        }
        let toggle = matches!(
            action,
            Action::Pause
                | Action::Decal
                | Action::Diffuse
                | Action::Specular
                | Action::SelfShadow
                | Action::Normalize
                | Action::Filter
                | Action::Wireframe
                | Action::FrameRate
                | Action::Help
        );
        if toggle {
            v.apply(action);
            assert_eq!((&v.choices, v.view), (&choices, view), "{action:?} twice");
        }
    }
}

#[test]
fn the_depth_and_layer_keys_reach_the_marches_and_the_status_line_names_them() {
    let mut v = viewer(&["--technique", "pom", "--scene", "wall"]);
    let depth = v.depth().expect("pom carves the wall");
    // The bump scale's depth: 4 texels of the wall's 1/128.
    assert!((depth - 4.0 / 128.0).abs() < 1e-6, "{depth}");
    assert!(v.status().starts_with("pom | depth 0.0312 | layers 32 |"), "{}", v.status());
    v.apply(Action::DepthUp);
    assert!((v.depth().unwrap() - depth * 1.25).abs() < 1e-6);
    v.apply(Action::LayersDown);
    v.apply(Action::ParallaxShadow);
    let Technique::SinglePass(o) = &v.prepared.technique else { panic!("pom is a single pass") };
    let p = o.parallax.expect("pom marches");
    assert_eq!((p.options.layers, p.options.shadow), (16, ParallaxShadow::Hard));
    assert!(v.status().contains("layers 16 | hard shadows"), "{}", v.status());
    // Kilgard's passes take no heights: the depth keys say so and change nothing.
    let mut v = viewer(&[]);
    let before = v.choices.clone();
    v.apply(Action::DepthUp);
    assert_eq!(v.choices, before);
    assert!(v.message.as_deref().is_some_and(|m| m.contains("kilgard takes no heights")), "{:?}", v.message);
}

#[test]
fn the_depth_layer_and_shadow_keys_reuse_the_heights_made_from_the_same_field() {
    let mut v = viewer(&["--technique", "pom", "--scene", "wall"]);
    let heights = |v: &Viewer| v.prepared.scene.objects[0].material.heights.clone().expect("pom carves the wall");
    let first = heights(&v);
    // The bump scale remakes the normal map, not the heights (1 on the surface, whatever the scale).
    for action in [Action::DepthUp, Action::LayersDown, Action::ParallaxShadow, Action::DepthDown, Action::BumpsUp] {
        v.apply(action);
        assert!(Arc::ptr_eq(&first, &heights(&v)), "{action:?} made the heights again");
    }
    assert_eq!(v.choices.bump_scale, 5.0, "the keys were taken");
}

#[test]
fn bumps_up_rebuilds_the_normal_map_and_the_passes_change_the_material() {
    let mut v = viewer(&[]);
    let before = normal_texels(&v);
    v.apply(Action::BumpsUp);
    assert_eq!(v.choices.bump_scale, 5.0);
    assert_ne!(normal_texels(&v), before, "the normal map is made again with the new scale");
    v.apply(Action::Decal);
    v.apply(Action::Specular);
    let m = &v.prepared.scene.objects[0].material;
    assert!(m.decal.is_none() && m.specular == Vec3::ZERO && m.diffuse != Vec3::ZERO);
}

#[test]
fn a_technique_that_cannot_draw_the_scene_is_skipped_and_named() {
    let dir = std::env::temp_dir().join(format!("bumpmap-view-state-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let map = dir.join("flat.png");
    image::RgbaImage::from_pixel(16, 16, image::Rgba([128, 128, 255, 255])).save(&map).unwrap();
    let mut v = viewer(&["--normal-map", map.to_str().unwrap()]);
    let mut seen = Vec::new();
    for _ in 0..TechniqueName::ALL.len() {
        v.apply(Action::NextTechnique);
        seen.push(v.technique());
    }
    assert!(!seen.contains(&TechniqueName::Reference), "the reference needs heights: {seen:?}");
    assert!(seen.contains(&TechniqueName::SinglePass) && seen.contains(&TechniqueName::Kilgard));
    let mut v = viewer(&["--normal-map", map.to_str().unwrap(), "--technique", "no-bump"]);
    v.apply(Action::NextTechnique);
    assert!(v.message.as_deref().is_some_and(|m| m.contains("peercy-independent")), "{:?}", v.message);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_file_that_cannot_be_read_keeps_the_scene_and_says_why() {
    let mut v = viewer(&[]);
    let before = (v.choices.clone(), normal_texels(&v));
    let err = v.load(Path::new("/nonexistent/bumps.png")).unwrap_err();
    assert!(err.contains("bumps.png"), "{err}");
    assert_eq!((v.choices.clone(), normal_texels(&v)), before);
    let err = v.load(Path::new("/nonexistent/model.obj")).unwrap_err();
    assert!(err.contains("model.obj"), "{err}");
}

#[test]
fn dropped_files_go_onto_the_scene_as_what_they_are() {
    let dir = std::env::temp_dir().join(format!("bumpmap-view-drop-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // Heights: a gray image with one raised square.
    let heights = dir.join("heights.png");
    image::GrayImage::from_fn(32, 32, |x, y| {
        image::Luma([if (8..24).contains(&x) && (8..24).contains(&y) { 200 } else { 40 }])
    })
    .save(&heights)
    .unwrap();
    let mut v = viewer(&["--technique", "single-pass"]);
    let bricks = normal_texels(&v);
    let said = v.load(&heights).unwrap();
    assert!(said.ends_with("a height field"), "{said}");
    let from_heights = normal_texels(&v);
    assert_ne!(from_heights, bricks, "the scene's normal map is made from the dropped heights");
    assert_eq!(v.options.height_field, Some(HeightSource::File(heights.clone())));
    // A normal map replaces the heights, drawn at its own scale.
    let map = dir.join("map.png");
    image::RgbaImage::from_pixel(16, 16, image::Rgba([160, 128, 230, 255])).save(&map).unwrap();
    let said = v.load(&map).unwrap();
    assert!(said.ends_with("a normal map"), "{said}");
    assert_eq!((v.options.normal_map.as_deref(), v.options.height_field.as_ref()), (Some(map.as_path()), None));
    assert_eq!(v.choices.bump_scale, 1.0);
    assert_ne!(normal_texels(&v), from_heights);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_reference_refines_while_nothing_moves() {
    let mut v = viewer(&["--technique", "reference", "--spp", "32"]);
    v.apply(Action::Pause);
    let spp = |v: &mut Viewer| match v.frame().technique {
        Technique::Reference(o) => o.samples_per_pixel,
        _ => unreachable!(),
    };
    let steps: Vec<usize> = (0..5).map(|_| spp(&mut v)).collect();
    assert_eq!(steps, [1, 4, 16, 32, 32]);
    assert!(!v.animating(), "converged and paused: nothing left to draw");
    v.move_light(0.1, 0.0);
    assert!(v.animating());
    assert_eq!(spp(&mut v), 1, "a move starts over");
}

#[test]
fn the_light_orbits_and_the_camera_turns() {
    let mut v = viewer(&[]);
    let light0 = v.frame().scene.lights[0].light;
    v.advance(1.0);
    assert_ne!(v.frame().scene.lights[0].light, light0);
    let eye0 = v.frame().scene.camera.eye;
    v.orbit_camera(0.5, 0.2);
    assert_ne!(v.frame().scene.camera.eye, eye0);
    v.apply(Action::ResetView);
    assert_eq!(v.frame().scene.camera.eye, eye0);
    v.apply(Action::Pause);
    let light = v.frame().scene.lights[0].light;
    v.advance(1.0);
    assert_eq!(v.frame().scene.lights[0].light, light, "paused");
}

#[test]
fn the_horizon_technique_and_the_shadow_key_shadow_by_the_horizon_map() {
    let mut v = viewer(&["--technique", "horizon", "--scene", "wall"]);
    assert!(v.status().starts_with("horizon | depth 0.0312 | horizon shadows |"), "{}", v.status());
    let Technique::SinglePass(o) = &v.prepared.technique else { panic!("horizon is a single pass") };
    let p = o.parallax.expect("horizon reads the heights");
    assert_eq!((p.method, p.options.shadow), (ParallaxMethod::Flat, ParallaxShadow::Horizon));
    // The shadow key has nothing to change here: it says so and leaves the scene as it is.
    let before = v.choices.clone();
    v.apply(Action::ParallaxShadow);
    assert_eq!(v.choices, before);
    assert!(v.message.as_deref().is_some_and(|m| m.contains("horizon map")), "{:?}", v.message);
    // On pom the key reaches the horizon map after the marches' own shadows.
    let mut v = viewer(&["--technique", "pom", "--scene", "wall"]);
    for _ in 0..3 {
        v.apply(Action::ParallaxShadow);
    }
    let Technique::SinglePass(o) = &v.prepared.technique else { panic!("pom is a single pass") };
    assert_eq!(o.parallax.expect("pom marches").options.shadow, ParallaxShadow::Horizon);
    assert!(v.status().contains("| horizon shadows"), "{}", v.status());
}

#[test]
fn a_key_the_technique_cannot_follow_leaves_the_scene_as_it_was_and_says_why() {
    // Kilgard's combiners square three times: a shininess of 8 only.
    let mut v = viewer(&[]);
    let (choices, status) = (v.choices.clone(), v.status());
    assert_eq!(v.apply(Action::ShininessUp), Effect::Redraw);
    assert_eq!(v.choices, choices, "the choice is undone");
    assert_eq!(v.status(), status);
    let message = v.message.clone().unwrap_or_default();
    assert!(message.contains("cannot do a shininess of 12"), "{message}");
    // The frame still draws: the scene is the one before the key.
    let mut renderer = bumpmap::Renderer::new(bumpmap::BackendChoice::Cpu).unwrap();
    renderer.draw(v.frame(), 32, 32).unwrap();
}

#[test]
fn the_status_line_names_the_specular_filter_only_where_the_technique_applies_it() {
    for (technique, presses, shown) in
        [("kilgard", 3, None), ("single-pass", 3, Some("LEAN")), ("single-pass", 1, Some("toksvig"))]
    {
        let mut v = viewer(&["--technique", technique]);
        for _ in 0..presses {
            v.apply(Action::SpecularFilter);
        }
        let status = v.status();
        for name in ["toksvig", "roughness map", "LEAN", "CLEAN"] {
            assert_eq!(status.contains(&format!("| {name}")), shown == Some(name), "{technique}: {status}");
        }
    }
}

#[test]
fn the_detail_key_cycles_the_blends_then_none_and_needs_a_detail_map() {
    let detail = detail_map();
    let mut v = viewer(&["--technique", "single-pass", "--detail-map", &detail, "--detail-method", "udn"]);
    assert!(v.status().contains("| detail udn x8"), "{}", v.status());
    let drawn = |v: &Viewer| match &v.prepared.technique {
        Technique::SinglePass(o) => o.detail.as_ref().map(|d| d.method),
        _ => None,
    };
    let mut seen = vec![drawn(&v)];
    for _ in 0..BlendMethod::ALL.len() {
        v.apply(Action::Detail);
        seen.push(drawn(&v));
    }
    // udn, linear, overlay, none, then from the first: every blend once and none once.
    assert_eq!(seen[3], None, "{seen:?}");
    assert_eq!(seen.iter().flatten().count(), BlendMethod::ALL.len(), "{seen:?}");
    assert!(v.status().contains("| detail whiteout x8"), "{}", v.status());
    // kilgard draws no detail, and its status says none.
    let mut v = viewer(&["--technique", "single-pass", "--detail-map", &detail]);
    v.apply(Action::PreviousTechnique);
    assert_eq!(v.technique(), TechniqueName::Kilgard);
    assert!(!v.status().contains("| detail"), "{}", v.status());
    // Without a detail map the key says how to give one and changes nothing.
    let mut v = viewer(&["--technique", "single-pass"]);
    let before = v.choices.clone();
    v.apply(Action::Detail);
    assert_eq!(v.choices, before);
    assert!(v.message.as_deref().is_some_and(|m| m.contains("--detail-map")), "{:?}", v.message);
}
