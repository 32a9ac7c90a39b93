//! The options' values checked and turned into what the scene and the technique take: ranges,
//! the lights, and every technique family's options, refusing an option that belongs to another
//! family than the one asked for.
//!
//! What this module does not do: load the scene's assets or build it (`build`).

use std::sync::Arc;

use bumpmap_core::parallax::{MAX_LAYERS, ParallaxOptions};
use bumpmap_core::scene::{SceneLight, Spot};
use bumpmap_core::scenes;
use bumpmap_core::technique::{
    EmbossOptions, Gloss, KilgardOptions, Normalize, ReferenceOptions, SelfShadow, SinglePassOptions, SpecularFilter,
    single_pass,
};
use bumpmap_core::{CoreError, Feature, SceneSpec, Technique, TechniqueName, TechniqueOptions};
use bumpmap_io::{Channel, HeightSource};
use bumpmap_math::{Rgba8Image, Rgba8Mips};
use glam::Vec3;

use super::files::{load_roughness_map, texture_file};
use super::{GlossChoice, SceneOption, SceneOptions, SetupError, SetupNote};

/// The largest |bump_scale| a normal map takes (a height field takes up to 1e6).
const MAX_NORMAL_SCALE: f32 = bumpmap_math::imported::MAX_SCALE;

/// The largest side of a spotlight pattern as it is sampled. The pattern has no mip levels (the
/// fixed-function projective texture had none either), so texels past what any framebuffer
/// shows only cost memory: a 16384² pattern took 3.1 GB and 27 s for a 64² render.
const MAX_SPOT_PATTERN: usize = 2048;

/// The most quads along u or v. 2048² quads (8.4 M triangles, a few pixels each even on the
/// largest framebuffer) draw a 512² image in 2.0 GB; 4096² took 7.9 GB.
pub const MAX_TESSELLATION: usize = 2048;

/// The most samples per pixel the reference takes.
pub const MAX_SAMPLES_PER_PIXEL: u32 = 4096;

/// The largest face of the normalization cube map.
pub const MAX_CUBE_SIZE: u32 = 1024;

/// Values out of their ranges.
pub(super) fn check_ranges(o: &SceneOptions) -> Result<(), SetupError> {
    let (camera, m) = (&o.camera, &o.material);
    let out = |option, expected: &str, got: String| {
        Err(SetupError::OutOfRange { option, expected: expected.to_string(), got })
    };
    for (option, v) in
        [(SceneOption::Ambient, m.ambient), (SceneOption::Diffuse, m.diffuse), (SceneOption::Specular, m.specular)]
    {
        if !(0.0..=1.0).contains(&v) {
            return out(option, "in [0, 1]", v.to_string());
        }
    }
    if !(1.0..=170.0).contains(&camera.fov_y_degrees) {
        return out(SceneOption::Fov, "in [1, 170] degrees", camera.fov_y_degrees.to_string());
    }
    let (major, minor) = o.torus_radii;
    if !(major > 0.0 && minor > 0.0) {
        return out(SceneOption::TorusRadii, "positive", format!("{major},{minor}"));
    }
    if !(m.shininess > 0.0 && m.shininess.is_finite()) {
        return out(SceneOption::Shininess, "a positive number", m.shininess.to_string());
    }
    if let Some((u, v)) = o.tessellation
        && !((1..=MAX_TESSELLATION).contains(&u) && (1..=MAX_TESSELLATION).contains(&v))
    {
        return out(SceneOption::Tessellation, &format!("two counts in 1..={MAX_TESSELLATION}"), format!("{u},{v}"));
    }
    if let Some(r) = o.repeat
        && !(r.is_finite() && r.x != 0.0 && r.y != 0.0 && r.abs().max_element() <= 1024.0)
    {
        return out(SceneOption::Repeat, "two numbers, non-zero and within ±1024", format!("{:?},{:?}", r.x, r.y));
    }
    for (option, v) in
        [(SceneOption::Eye, camera.eye), (SceneOption::Target, camera.target), (SceneOption::Spot, o.lights.spot)]
    {
        if let Some(v) = v
            && !v.is_finite()
        {
            return out(option, "three finite numbers", format!("{:?},{:?},{:?}", v.x, v.y, v.z));
        }
    }
    let t = &o.technique;
    if !(1..=MAX_SAMPLES_PER_PIXEL).contains(&t.samples_per_pixel) {
        return out(SceneOption::Spp, &format!("in 1..={MAX_SAMPLES_PER_PIXEL}"), t.samples_per_pixel.to_string());
    }
    if !(1..=MAX_CUBE_SIZE).contains(&t.cube_size) {
        return out(SceneOption::CubeSize, &format!("in 1..={MAX_CUBE_SIZE}"), t.cube_size.to_string());
    }
    let h = &o.heights;
    if let Some(d) = h.depth
        && !(d.is_finite() && d > 0.0)
    {
        return out(SceneOption::Depth, "a positive number of the scene's units", d.to_string());
    }
    if !(1..=MAX_LAYERS).contains(&h.layers) {
        return out(SceneOption::Layers, &format!("in 1..={MAX_LAYERS}"), h.layers.to_string());
    }
    if let Some(up) = camera.up
        && up.normalize_or_zero() == Vec3::ZERO
    {
        return out(
            SceneOption::Up,
            "a direction",
            format!("{:?},{:?},{:?} (zero, or too short to normalize)", up.x, up.y, up.z),
        );
    }
    if let Some(b) = o.bump_scale {
        // It scales a normal map's slopes (a normal map's, or a glTF material's) or a height
        // field's heights (everything else: an OBJ gets the bricks).
        let max = if o.normal_map.is_some() || o.height_field.is_none() && o.scene.is_gltf() {
            MAX_NORMAL_SCALE
        } else {
            bumpmap_math::normalmap::MAX_SCALE
        };
        if !(b.is_finite() && b.abs() <= max) {
            return out(SceneOption::BumpScale, &format!("a number in [-{max}, {max}]"), b.to_string());
        }
    }
    Ok(())
}

/// The lights: the options', or the scene's default one when attenuation or a spotlight is
/// asked of it, each with the attenuation and spotlight the options give.
pub(super) fn lights(o: &SceneOptions, spec: &SceneSpec) -> Result<Vec<SceneLight>, SetupError> {
    let l = &o.lights;
    let pattern = match &l.spot_pattern {
        None => None,
        Some(source) => {
            // A preset is rendered no larger than the cap; a file is box-halved down to it.
            let source = match source {
                HeightSource::Preset { preset, size } => {
                    HeightSource::Preset { preset: *preset, size: (*size).min(MAX_SPOT_PATTERN) }
                }
                file => file.clone(),
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
    single_pass::validate_lights(&l.lights)?;
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
                cutoff_degrees: l.spot_cutoff_degrees,
                exponent: l.spot_exponent,
                pattern: pattern.clone(),
            });
        }
        single_pass::validate_light(light)?;
    }
    Ok(lights)
}

/// Every family's options as `o` gives them; options that belong to another family than the
/// technique's are refused, naming both.
pub(super) fn technique_options(o: &SceneOptions, notes: &mut Vec<SetupNote>) -> Result<TechniqueOptions, SetupError> {
    let (t, m) = (&o.technique, &o.material);
    let name = t.technique;
    let family = name.technique(&TechniqueOptions::default());
    let refuse = |feature| Err(SetupError::from(CoreError::Unsupported { technique: "kilgard", feature }));
    if t.specular_filter != SpecularFilter::None && !matches!(family, Technique::SinglePass(_)) {
        return Err(SetupError::SpecularFilterNotDrawn { technique: name });
    }
    match family {
        Technique::Kilgard(_) => {
            if m.gloss != GlossChoice::None {
                return refuse(Feature::Gloss);
            }
            if t.normalize == Some(Normalize::Math) {
                return refuse(Feature::NormalizeByMath);
            }
            if t.half_angle != bumpmap_core::technique::HalfAngle::Vertex {
                return refuse(Feature::FragmentHalfAngle);
            }
            if t.self_shadow == SelfShadow::Step {
                return refuse(Feature::SelfShadowStep);
            }
        }
        Technique::SinglePass(_) => {
            if t.specular_mode != bumpmap_core::technique::SpecularMode::EighthPower {
                return Err(SetupError::KilgardOnly { option: SceneOption::SpecularMode, technique: name });
            }
            if t.precision != bumpmap_core::combiners::Precision::Float {
                return Err(SetupError::KilgardOnly { option: SceneOption::Precision, technique: name });
            }
            if name == TechniqueName::SinglePassCube && t.normalize == Some(Normalize::Math) {
                return Err(SetupError::CubeNormalizes);
            }
        }
        Technique::Emboss(_) | Technique::Reference(_) => {}
    }
    let gloss = match &m.gloss {
        GlossChoice::None => Gloss::None,
        GlossChoice::DecalAlpha => Gloss::DecalAlpha,
        GlossChoice::Bricks => {
            let g = Rgba8Image::from_gray(256, 256, &bumpmap_math::height::bricks_gloss(256, 256));
            Gloss::Map(Arc::new(Rgba8Mips::with_box_mipmaps(g)))
        }
        GlossChoice::File(path) => Gloss::Map(texture_file(path)?),
    };
    let roughness_map = match &m.roughness_map {
        None => None,
        Some(path) if name == TechniqueName::RoughnessMap || t.specular_filter == SpecularFilter::RoughnessMap => {
            Some(Arc::new(load_roughness_map(path, m.roughness_layout, notes)?))
        }
        Some(_) => {
            return Err(SetupError::RoughnessMapUnread { technique: name, specular_filter: t.specular_filter });
        }
    };
    let sampler = t.filter.unwrap_or_default().sampler();
    let cube_size = t.cube_size as usize;
    Ok(TechniqueOptions {
        kilgard: KilgardOptions {
            sampler,
            self_shadow: t.self_shadow != SelfShadow::Off,
            specular: t.specular_mode,
            precision: t.precision,
            cube_size,
            ..Default::default()
        },
        single_pass: SinglePassOptions {
            sampler,
            normalize: t.normalize.unwrap_or(Normalize::Math),
            self_shadow: t.self_shadow,
            half_angle: t.half_angle,
            specular_shadow: t.specular_shadow,
            gloss,
            cube_size,
            parallax: None,
            specular_filter: t.specular_filter,
            roughness_map,
            // Read from its file by `detail::detail_layer`.
            detail: None,
        },
        emboss: EmbossOptions { sampler, cube_size, ..Default::default() },
        reference: ReferenceOptions {
            samples_per_pixel: t.samples_per_pixel as usize,
            seed: t.seed,
            self_shadow: t.self_shadow,
            specular_shadow: t.specular_shadow,
            ..Default::default()
        },
        parallax: ParallaxOptions {
            layers: o.heights.layers,
            shadow: o.heights.parallax_shadow,
            silhouettes: o.heights.silhouettes,
            write_depth: o.heights.write_depth,
            ambient_occlusion: o.heights.ambient_occlusion,
            hit_normal: o.heights.hit_normal,
        },
    })
}
