//! The demo's renders: each file, what it shows, and the scene and technique that draw it.

use std::sync::Arc;

use bumpmap::{BumpSource, ParallaxOptions, ParallaxShadow, TechniqueName, TechniqueOptions};
use bumpmap_core::BumpMap;
use bumpmap_core::scene::{Attenuation, SceneLight, Spot};
use bumpmap_core::scenes::{SceneKind, SceneParams};
use bumpmap_core::technique::{Gloss, KilgardOptions, SinglePassOptions, Technique};
use bumpmap_math::lighting::Light;
use bumpmap_math::{HeightField, HeightPreset, NormalMapOptions, Rgba8Image, Rgba8Mips};
use glam::Vec3;

/// One image of the demo: its file, what it shows, and the scene and technique that make it.
pub(crate) struct DemoRender {
    pub file: &'static str,
    pub what: &'static str,
    /// Also write the framebuffer after each pass (Kilgard Figure 12).
    pub passes: bool,
    pub make: fn() -> (SceneKind, SceneParams, Technique),
}

fn kilgard() -> Technique {
    Technique::Kilgard(KilgardOptions::default())
}

fn single(options: SinglePassOptions) -> Technique {
    Technique::SinglePass(options)
}

fn at(x: f32, y: f32, z: f32) -> SceneLight {
    SceneLight::white(Light::Positional(Vec3::new(x, y, z)))
}

fn coloured(light: SceneLight, r: f32, g: f32, b: f32) -> SceneLight {
    SceneLight { color: Vec3::new(r, g, b), ..light }
}

fn preset(p: HeightPreset) -> HeightField {
    p.render(256, 256)
}

pub(crate) const RENDERS: &[DemoRender] = &[
    DemoRender {
        file: "fig11_torus.png",
        what: "Kilgard Figure 11: the bump-mapped brick torus, three passes on the emulated GeForce",
        passes: true,
        make: || (SceneKind::Torus, SceneParams::default(), kilgard()),
    },
    DemoRender {
        file: "fig14_no_self_shadow.png",
        what: "Kilgard Figure 14, left: light from the far right, no self-shadowing term",
        passes: false,
        make: || {
            let params = SceneParams { lights: vec![at(6.0, 0.0, 0.5)], ..Default::default() };
            (SceneKind::Torus, params, Technique::Kilgard(KilgardOptions { self_shadow: false, ..Default::default() }))
        },
    },
    DemoRender {
        file: "fig14_self_shadow.png",
        what: "Kilgard Figure 14, right: the same light with Eq. 12's self-shadowing",
        passes: false,
        make: || (SceneKind::Torus, SceneParams { lights: vec![at(6.0, 0.0, 0.5)], ..Default::default() }, kilgard()),
    },
    DemoRender {
        file: "fig8-4_wall_floor.png",
        what: "Cg Tutorial Figure 8-4: wall and floor lit consistently by one light",
        passes: false,
        make: || (SceneKind::WallFloor, SceneParams::default(), kilgard()),
    },
    DemoRender {
        file: "single_pass_torus.png",
        what: "The same torus in one float pass per light (Kilgard §6)",
        passes: false,
        make: || (SceneKind::Torus, SceneParams::default(), single(SinglePassOptions::default())),
    },
    DemoRender {
        file: "single_pass_two_lights.png",
        what: "Two coloured lights, single pass",
        passes: false,
        make: || {
            let lights =
                vec![coloured(at(4.0, -3.0, 3.0), 1.0, 0.35, 0.2), coloured(at(-4.0, -3.0, 3.0), 0.2, 0.45, 1.0)];
            (SceneKind::Torus, SceneParams { lights, ..Default::default() }, single(SinglePassOptions::default()))
        },
    },
    DemoRender {
        file: "single_pass_gloss.png",
        what: "Gloss map: shiny bricks, dull mortar (Cg Tutorial §8.5.2)",
        passes: false,
        make: || {
            let gloss = Rgba8Image::from_gray(256, 256, &bumpmap_math::height::bricks_gloss(256, 256));
            let options = SinglePassOptions {
                gloss: Gloss::Map(Arc::new(Rgba8Mips::with_box_mipmaps(gloss))),
                ..Default::default()
            };
            (SceneKind::Torus, SceneParams { shininess: 40.0, ..Default::default() }, single(options))
        },
    },
    DemoRender {
        file: "single_pass_spotlight.png",
        what: "A spotlight projecting a pinwheel pattern on the wall (Kilgard §5.6)",
        passes: false,
        make: || {
            let field = preset(HeightPreset::Pinwheel);
            let pattern = Rgba8Mips::single(Rgba8Image::from_gray(field.width(), field.height(), &field.to_u8()));
            let spot =
                Spot { direction: Vec3::NEG_Z, cutoff_degrees: 30.0, exponent: 2.0, pattern: Some(Arc::new(pattern)) };
            let lights = vec![SceneLight { spot: Some(spot), ..at(0.0, 0.0, 4.0) }];
            let params = SceneParams { lights, specular: Vec3::splat(0.3), ..Default::default() };
            (SceneKind::Wall, params, single(SinglePassOptions::default()))
        },
    },
    DemoRender {
        file: "single_pass_attenuation.png",
        what: "Attenuation 1/(0.2 + 0.5·d²) from a light just above the floor",
        passes: false,
        make: || {
            let attenuation = Attenuation::Polynomial { constant: 0.2, linear: 0.0, quadratic: 0.5 };
            let lights = vec![SceneLight { attenuation, ..at(0.0, 0.6, 0.0) }];
            let params = SceneParams { lights, eye: Some(Vec3::new(0.0, 3.0, 6.0)), ..Default::default() };
            (SceneKind::Floor, params, single(SinglePassOptions::default()))
        },
    },
    DemoRender {
        file: "single_pass_object_space.png",
        what: "Object-space lighting with an object-space normal map baked for the torus (Peercy §2.1)",
        passes: false,
        make: || {
            (
                SceneKind::Torus,
                SceneParams { bump_map: BumpMap::ObjectSpace, ..Default::default() },
                single(SinglePassOptions::default()),
            )
        },
    },
    DemoRender {
        file: "patch_pinwheel.png",
        what: "Peercy Figure 4's stretched bicubic patch with the pinwheel height field",
        passes: false,
        make: || {
            let params = SceneParams {
                bumps: BumpSource::Heights(Arc::new(preset(HeightPreset::Pinwheel))),
                default_decal: false,
                ..Default::default()
            };
            (SceneKind::Patch, params, kilgard())
        },
    },
    DemoRender {
        file: "sphere_dimples.png",
        what: "A golf ball: dimples on a sphere",
        passes: false,
        make: || {
            let params = SceneParams {
                bumps: BumpSource::Heights(Arc::new(preset(HeightPreset::Dimples))),
                normal_map: NormalMapOptions { scale: 8.0, ..Default::default() },
                default_decal: false,
                ..Default::default()
            };
            (SceneKind::Sphere, params, kilgard())
        },
    },
    DemoRender {
        file: "parallax_normal_mapping.png",
        what: "Heights as geometry, 1 of 2: the brick wall at a grazing angle by normal mapping (single-pass): flat bricks painted with slopes",
        passes: false,
        make: || grazing_wall(TechniqueName::SinglePass),
    },
    DemoRender {
        file: "parallax_pom.png",
        what: "Heights as geometry, 2 of 2: the same wall by parallax occlusion mapping (pom) with hard shadows: the bricks hide the mortar behind them and shade the joints",
        passes: false,
        make: || grazing_wall(TechniqueName::Pom),
    },
    DemoRender {
        file: "shadows_normal_mapping.png",
        what: "Bumps that shadow each other, 1 of 2: the brick wall head-on, lit low from the side (70° from the normal), by the single pass: Eq. 12 lights every joint, since the wall itself faces the light",
        passes: false,
        make: || low_light_wall(TechniqueName::SinglePass),
    },
    DemoRender {
        file: "shadows_horizon.png",
        what: "Bumps that shadow each other, 2 of 2: the same by the horizon map (horizon, with --ambient-occlusion): each brick shadows the joint beside it, no march",
        passes: false,
        make: || low_light_wall(TechniqueName::Horizon),
    },
];

/// The brick wall head-on, lit from the side 70° from its normal, by `name` (ambient occlusion
/// from the horizon map for the techniques that read it).
fn low_light_wall(name: TechniqueName) -> (SceneKind, SceneParams, Technique) {
    let l = 70f32.to_radians();
    let base = SceneParams {
        eye: Some(Vec3::new(0.0, 0.0, 1.8)),
        target: Some(Vec3::ZERO),
        lights: vec![SceneLight::white(Light::Directional(Vec3::new(l.sin() * 0.8, -l.sin() * 0.6, l.cos())))],
        ..Default::default()
    };
    let options = TechniqueOptions {
        parallax: ParallaxOptions { ambient_occlusion: true, ..Default::default() },
        ..Default::default()
    };
    (SceneKind::Wall, name.scene_params(&base), name.technique(&options))
}

/// The brick wall seen 65° off its normal, lit from the side, by `name` (hard shadows from the
/// heights for the techniques that take them as geometry).
fn grazing_wall(name: TechniqueName) -> (SceneKind, SceneParams, Technique) {
    let base = SceneParams {
        eye: Some(Vec3::new(0.0, -1.25, 0.55)),
        target: Some(Vec3::new(0.0, 0.1, 0.0)),
        lights: vec![SceneLight::white(Light::Directional(Vec3::new(1.0, -0.2, 0.45).normalize()))],
        ..Default::default()
    };
    let options = TechniqueOptions {
        parallax: ParallaxOptions { shadow: ParallaxShadow::Hard, ..Default::default() },
        ..Default::default()
    };
    (SceneKind::Wall, name.scene_params(&base), name.technique(&options))
}
