//! The options' values checked and turned into what the scene and the technique take: ranges
//! (usage errors named by flag), the lights, and every technique family's options, refusing a
//! flag that belongs to another family than the one asked for.
//!
//! What this module does not do: load a file (`files`) or build the scene (`super`).

use std::path::Path;
use std::sync::Arc;

use bumpmap::bumpmap_core::combiners::Precision;
use bumpmap::bumpmap_core::parallax::ParallaxOptions;
use bumpmap::bumpmap_core::scenes;
use bumpmap::bumpmap_core::state::Sampler;
use bumpmap::bumpmap_core::technique::single_pass;
use bumpmap::{
    Gloss, HalfAngle, KilgardOptions, Normalize, ReferenceOptions, Rgba8Image, Rgba8Mips, SceneLight, SceneSpec,
    SelfShadow, SpecularMode, SpecularShadow, Spot, Technique, TechniqueName, TechniqueOptions,
};
use bumpmap_io::{Channel, HeightSource};
use glam::Vec3;

use super::files::{load_roughness_map, texture_file};
use super::{MAX_NORMAL_SCALE, MAX_SPOT_PATTERN};
use crate::args::{
    FilterArg, HalfAngleArg, NormalizeArg, PrecisionArg, SceneSetup, SelfShadowArg, SpecularArg, SpecularFilterArg,
    SpecularShadowArg, TechniqueGroup,
};
use crate::error::CliError;
use crate::render::core_err;

/// Values out of their ranges, found after parsing: usage errors, named by flag.
pub(super) fn check_ranges(s: &SceneSetup) -> Result<(), CliError> {
    let (camera, m) = (&s.camera, &s.material);
    for (name, v) in [("--ambient", m.ambient), ("--diffuse", m.diffuse), ("--specular", m.specular)] {
        if !(0.0..=1.0).contains(&v) {
            return Err(CliError::Usage(format!("{name} must be in [0, 1], got {v}")));
        }
    }
    if !(1.0..=170.0).contains(&camera.fov) {
        return Err(CliError::Usage(format!("--fov must be in [1, 170] degrees, got {}", camera.fov)));
    }
    let (major, minor) = s.scene.torus_radii;
    if !(major > 0.0 && minor > 0.0) {
        return Err(CliError::Usage(format!("--torus-radii must be positive, got {major},{minor}")));
    }
    if !(m.shininess > 0.0 && m.shininess.is_finite()) {
        return Err(CliError::Usage(format!("--shininess must be a positive number, got {}", m.shininess)));
    }
    if let Some(up) = camera.up
        && up.normalize_or_zero() == Vec3::ZERO
    {
        return Err(CliError::Usage(format!(
            "--up must be a direction, got {:?},{:?},{:?} (zero, or too short to normalize)",
            up.x, up.y, up.z
        )));
    }
    if let Some(b) = s.scene.bump_scale {
        // It scales a normal map's slopes (--normal-map, or a glTF material's) or a height
        // field's heights (everything else: an OBJ gets the bricks).
        let gltf = [".gltf", ".glb"].iter().any(|e| s.scene.scene.to_ascii_lowercase().ends_with(e));
        let max = if s.scene.normal_map.is_some() || s.scene.height_field.is_none() && gltf {
            MAX_NORMAL_SCALE
        } else {
            bumpmap::bumpmap_math::normalmap::MAX_SCALE
        };
        if !(b.is_finite() && b.abs() <= max) {
            return Err(CliError::Usage(format!("--bump-scale must be a number in [-{max}, {max}], got {b}")));
        }
    }
    Ok(())
}

/// The lights: the options', or the scene's default one when attenuation or a spotlight is
/// asked of it, each with the attenuation and spotlight the options give.
pub(super) fn lights(s: &SceneSetup, spec: &SceneSpec) -> Result<Vec<SceneLight>, CliError> {
    let l = &s.lights;
    let pattern = match l.spot_pattern.as_deref() {
        None => None,
        Some(p) => {
            // A preset is rendered no larger than the cap; a file is box-halved down to it.
            let source = match HeightSource::parse(p) {
                HeightSource::Preset { preset, size } => {
                    HeightSource::Preset { preset, size: size.min(MAX_SPOT_PATTERN) }
                }
                file => file,
            };
            let field = source.load(Channel::Luminance)?;
            let mut image = Rgba8Image::from_gray(field.width(), field.height(), &field.to_u8());
            drop(field);
            while image.width > MAX_SPOT_PATTERN || image.height > MAX_SPOT_PATTERN {
                image = image.box_halved();
            }
            Some(Arc::new(Rgba8Mips::single(image)))
        }
    };
    // The count first: a list too long is refused before any light is looked at.
    single_pass::validate_lights(&l.lights).map_err(core_err)?;
    let mut lights = l.lights.clone();
    if lights.is_empty() && (l.attenuation.is_some() || l.spot.is_some()) {
        lights.push(SceneLight::white(scenes::default_light(&spec.kind, &spec.params)));
    }
    for light in &mut lights {
        if let Some(a) = l.attenuation {
            light.attenuation = a;
        }
        if let Some(direction) = l.spot {
            light.spot = Some(Spot {
                direction,
                cutoff_degrees: l.spot_cutoff,
                exponent: l.spot_exponent,
                pattern: pattern.clone(),
            });
        }
        single_pass::validate_light(light).map_err(core_err)?;
    }
    Ok(lights)
}

fn sampler(filter: FilterArg) -> Sampler {
    match filter {
        FilterArg::Nearest => Sampler::NEAREST_REPEAT,
        FilterArg::Linear => Sampler::LINEAR_REPEAT,
        FilterArg::Trilinear => Sampler::TRILINEAR_REPEAT,
    }
}

fn self_shadow(t: &TechniqueGroup) -> SelfShadow {
    match (t.no_self_shadow, t.self_shadow) {
        (true, _) | (_, SelfShadowArg::Off) => SelfShadow::Off,
        (_, SelfShadowArg::Ramp) => SelfShadow::Ramp,
        (_, SelfShadowArg::Step) => SelfShadow::Step,
    }
}

fn specular_shadow(t: &TechniqueGroup) -> SpecularShadow {
    match t.specular_shadow {
        SpecularShadowArg::Kilgard => SpecularShadow::Kilgard,
        SpecularShadowArg::Cg => SpecularShadow::CgTutorial,
        SpecularShadowArg::Off => SpecularShadow::Off,
    }
}

/// Every family's options as the flags give them; flags that belong to another technique than
/// `name`'s family are refused, naming both.
pub(super) fn technique_options(s: &SceneSetup, name: TechniqueName) -> Result<TechniqueOptions, CliError> {
    let (t, m) = (&s.technique, &s.material);
    let family = name.technique(&TechniqueOptions::default());
    let kilgard_only = |flag: &str| {
        CliError::Render(format!(
            "{flag} belongs to --technique kilgard's register combiners; --technique {name} takes --shininess and computes in float"
        ))
    };
    let refuse = |feature| Err(core_err(bumpmap::CoreError::Unsupported { technique: "kilgard", feature }));
    if t.specular_filter != SpecularFilterArg::None && !matches!(family, Technique::SinglePass(_)) {
        return Err(CliError::Render(format!(
            "--specular-filter shapes the single pass's float specular; --technique {name} does not draw with it (use --technique toksvig, or single-pass and its family)"
        )));
    }
    match family {
        Technique::Kilgard(_) => {
            use bumpmap::bumpmap_core::Feature;
            if m.gloss.is_some() {
                return refuse(Feature::Gloss);
            }
            if t.normalize == Some(NormalizeArg::Math) {
                return refuse(Feature::NormalizeByMath);
            }
            if t.half_angle != HalfAngleArg::Vertex {
                return refuse(Feature::FragmentHalfAngle);
            }
            if t.self_shadow != SelfShadowArg::Ramp {
                return refuse(Feature::SelfShadowStep);
            }
        }
        Technique::SinglePass(_) => {
            if t.specular_mode != SpecularArg::Power8 {
                return Err(kilgard_only("--specular-mode ramp"));
            }
            if t.precision != PrecisionArg::Float {
                return Err(kilgard_only("--precision"));
            }
            if name == TechniqueName::SinglePassCube && t.normalize == Some(NormalizeArg::Math) {
                return Err(CliError::Usage(
                    "--technique single-pass-cube normalizes by the cube map: drop --normalize math, or use --technique single-pass".into(),
                ));
            }
        }
        Technique::Emboss(_) | Technique::Reference(_) => {}
    }
    let gloss = match m.gloss.as_deref() {
        None | Some("none") => Gloss::None,
        Some("decal-alpha") => Gloss::DecalAlpha,
        Some("bricks") => {
            let g = Rgba8Image::from_gray(256, 256, &bumpmap::bumpmap_math::height::bricks_gloss(256, 256));
            Gloss::Map(Arc::new(Rgba8Mips::with_box_mipmaps(g)))
        }
        Some(path) => Gloss::Map(texture_file(Path::new(path))?),
    };
    let roughness_map = match &m.roughness_map {
        None => None,
        Some(path) if name == TechniqueName::RoughnessMap || t.specular_filter == SpecularFilterArg::RoughnessMap => {
            Some(Arc::new(load_roughness_map(path, m.roughness_layout)?))
        }
        Some(_) => {
            return Err(CliError::Usage(format!(
                "--roughness-map is read by the roughness-map specular filter: add --technique roughness-map (or --specular-filter roughness-map), not --technique {name}{}",
                match t.specular_filter {
                    SpecularFilterArg::None => String::new(),
                    f => format!(
                        " with --specular-filter {}",
                        clap::ValueEnum::to_possible_value(&f).map(|v| v.get_name().to_owned()).unwrap_or_default()
                    ),
                }
            )));
        }
    };
    let sampler = sampler(t.filter);
    let cube_size = t.cube_size as usize;
    Ok(TechniqueOptions {
        kilgard: KilgardOptions {
            sampler,
            self_shadow: !t.no_self_shadow,
            specular: match t.specular_mode {
                SpecularArg::Power8 => SpecularMode::EighthPower,
                SpecularArg::Ramp => SpecularMode::Ramp,
            },
            precision: match t.precision {
                PrecisionArg::Float => Precision::Float,
                PrecisionArg::Fixed9 => Precision::Fixed9,
            },
            cube_size,
            ..Default::default()
        },
        single_pass: bumpmap::SinglePassOptions {
            sampler,
            normalize: match t.normalize {
                None | Some(NormalizeArg::Math) => Normalize::Math,
                Some(NormalizeArg::Cube) => Normalize::Cube,
            },
            self_shadow: self_shadow(t),
            half_angle: match t.half_angle {
                HalfAngleArg::Vertex => HalfAngle::Vertex,
                HalfAngleArg::Fragment => HalfAngle::Fragment,
            },
            specular_shadow: specular_shadow(t),
            gloss,
            cube_size,
            parallax: None,
            specular_filter: match t.specular_filter {
                SpecularFilterArg::None => bumpmap::SpecularFilter::None,
                SpecularFilterArg::Toksvig => bumpmap::SpecularFilter::Toksvig,
                SpecularFilterArg::RoughnessMap => bumpmap::SpecularFilter::RoughnessMap,
                SpecularFilterArg::Lean => bumpmap::SpecularFilter::Lean,
                SpecularFilterArg::Clean => bumpmap::SpecularFilter::Clean,
            },
            roughness_map,
        },
        emboss: bumpmap::EmbossOptions { sampler, cube_size, ..Default::default() },
        reference: ReferenceOptions {
            samples_per_pixel: t.spp as usize,
            self_shadow: self_shadow(t),
            specular_shadow: specular_shadow(t),
            ..Default::default()
        },
        parallax: ParallaxOptions {
            layers: s.heights.layers,
            shadow: s.heights.parallax_shadow.0,
            silhouettes: s.heights.silhouettes,
            write_depth: s.heights.write_depth,
            ambient_occlusion: s.heights.ambient_occlusion,
        },
    })
}
