//! `bumpmap render`: the option groups turned into a scene and a technique, drawn by a backend
//! into a PNG (and, with `--passes`, one PNG per pass).
//!
//! The library refuses what a technique cannot do with typed errors; this module is where they
//! get the names of the flags that caused them.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap_core::combiners::Precision;
use bumpmap_core::scene::{Scene, SceneLight, Spot, ViewerModel};
use bumpmap_core::scenes::{self, SceneKind, SceneParams};
use bumpmap_core::state::Sampler;
use bumpmap_core::technique::{
    Gloss, HalfAngle, KilgardOptions, Normalize, SelfShadow, SinglePassOptions, SpecularMode, SpecularShadow,
    Technique, single_pass,
};
use bumpmap_core::{BumpMap, CoreError, Feature};
use bumpmap_io::atomic::{FileSet, ensure_not_input};
use bumpmap_io::image_file::{PngLayout, save_png_into};
use bumpmap_io::{Channel, HeightSource};
use bumpmap_math::{NormalMapOptions, Rgba8Image, Rgba8Mips};
use glam::{Vec2, Vec3};

use crate::backend::{Backend, Frame};
use crate::error::CliError;
use crate::render_args::{
    FilterArg, HalfAngleArg, NormalizeArg, PrecisionArg, RenderArgs, SceneSetup, SelfShadowArg, SpaceArg, SpecularArg,
    SpecularShadowArg, TechniqueArg, ViewerArg,
};

pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let (width, height) = match (args.width, args.height) {
        (Some(w), Some(h)) => (w, h),
        _ => (args.size, args.size),
    };
    let mut inputs = input_files(&args.setup);
    ensure_not_input(&args.output, &inputs.iter().map(PathBuf::as_path).collect::<Vec<_>>())?;
    // Refuse an impossible framebuffer before any work.
    crate::backend::check_size(width, height)?;
    let (scene, read) = build_scene(&args.setup)?;
    // The mesh's buffer files are inputs too.
    inputs.extend(read);
    let input_refs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    if args.setup.technique.technique == TechniqueArg::Reference {
        if args.passes {
            return Err(CliError::Usage("--passes shows the three passes of --technique kilgard".into()));
        }
        let image = reference(&scene, &args.setup, width, height, true)?;
        let frame = Frame { image: image.to_rgba8(), snapshots: Vec::new() };
        let written = write_frame(&frame, &args.output, &input_refs)?;
        eprintln!("wrote {} (reference, {} samples per pixel)", written[0].display(), args.setup.technique.spp);
        return Ok(());
    }
    let technique = technique(&args.setup)?;
    if args.passes && !matches!(technique, Technique::Kilgard(_)) {
        return Err(CliError::Render(
            "--passes shows the three passes of --technique kilgard; single-pass draws one pass per light".into(),
        ));
    }
    let mut backend = Backend::new(args.setup.backend.backend)?;
    let frame = backend.render(&scene, &technique, width, height, args.passes)?;
    let written = write_frame(&frame, &args.output, &input_refs)?;
    eprintln!(
        "wrote {} ({})",
        written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "),
        backend.name()
    );
    Ok(())
}

/// A library error in the words of the command line: what the user typed that caused it.
pub fn core_err(e: CoreError) -> CliError {
    let flag = |f: &Feature| {
        match f {
        Feature::Shininess(s) => format!("--shininess {s} (its combiners square three times: 8 only; --specular-mode ramp gives a tighter highlight)"),
        Feature::Gloss => "--gloss".into(),
        Feature::Attenuation => "--attenuation".into(),
        Feature::Spotlight => "--spot".into(),
        Feature::NormalizeByMath | Feature::FragmentHalfAngle | Feature::SelfShadowStep => {
            "--normalize, --half-angle or --self-shadow (it always normalizes by the cube map, with per-vertex H, the ramp or --no-self-shadow)".into()
        }
        Feature::ObjectSpace => "--space object (its self-shadowing reads tangent-space L_z)".into(),
        Feature::SpecularColor => "--specular other than 0 or 1 (its specular is white)".into(),
        Feature::MultipleLights => "more than one --light".into(),
        Feature::BumpScale(s) => format!("--bump-scale {s} (its combiners scale by 1, 2 or 4)"),
        Feature::HeightMap => "a scene without its height field".into(),
        Feature::OffsetMap => "an offset map (its combiners cannot renormalize N + D per pixel)".into(),
        Feature::SurfaceMap => "a normal map made for one surface (its passes read every texture with the repeating coordinates)".into(),
    }
    };
    match e {
        CoreError::Unsupported { technique, feature } => CliError::Render(format!(
            "--technique {technique} cannot do {}: the paper's combiners have no room for it; use --technique single-pass",
            flag(&feature)
        )),
        CoreError::MapNeedsSurface(BumpMap::ObjectSpace) => CliError::Render(
            "--space object needs a built-in surface (the map is made from its exact frames), not a mesh".into(),
        ),
        CoreError::GlossNeedsDecal => CliError::Render(
            "--gloss decal-alpha needs a decal (--decal FILE, or the bricks height field's own)".into(),
        ),
        other => CliError::Render(other.to_string()),
    }
}

/// Files the command reads, which an output must never replace.
fn input_files(setup: &SceneSetup) -> Vec<PathBuf> {
    let mut files = Vec::new();
    if let Some(p) = setup.scene.scene.strip_prefix("mesh:") {
        files.push(PathBuf::from(p));
    }
    if let Some(p) = HeightSource::parse(&setup.scene.height_field).path() {
        files.push(p.to_path_buf());
    }
    if let Some(d) = setup.scene.decal.as_deref().filter(|d| *d != "none") {
        files.push(PathBuf::from(d));
    }
    for spec in [&setup.lights.spot_pattern, &setup.material.gloss].into_iter().flatten() {
        if let Some(p) =
            HeightSource::parse(spec).path().filter(|_| !matches!(spec.as_str(), "bricks" | "decal-alpha" | "none"))
        {
            files.push(p.to_path_buf());
        }
    }
    files
}

/// The scene the options describe, and the mesh files it read (none for a built-in surface).
pub fn build_scene(setup: &SceneSetup) -> Result<(Scene, Vec<PathBuf>), CliError> {
    let (s, camera, l, m) = (&setup.scene, &setup.camera, &setup.lights, &setup.material);
    let mut read = Vec::new();
    let kind = match s.scene.strip_prefix("mesh:") {
        Some(path) => {
            let options =
                bumpmap_io::MeshOptions { allow_outside_paths: s.allow_outside_paths, obj_texcoords: s.obj_v.into() };
            let (mesh, sources) = crate::mesh::load_for_render(Path::new(path), &options)?;
            read = sources;
            SceneKind::Mesh(Arc::new(mesh))
        }
        None => SceneKind::parse(&s.scene).ok_or_else(|| {
            CliError::Render(format!(
                "unknown scene '{}': use torus, wall, floor, wall-floor, patch, sphere or mesh:FILE",
                s.scene
            ))
        })?,
    };
    let source = HeightSource::parse(&s.height_field);
    let height_field = source.load(Channel::Luminance)?;
    let is_bricks = matches!(source, HeightSource::Preset { preset: bumpmap_math::HeightPreset::Bricks, .. });
    let decal = match s.decal.as_deref() {
        None | Some("none") => None,
        Some(path) => Some(bumpmap_io::load_rgba8(Path::new(path))?),
    };
    for (name, v) in [("--ambient", m.ambient), ("--diffuse", m.diffuse), ("--specular", m.specular)] {
        if !(0.0..=1.0).contains(&v) {
            return Err(CliError::Usage(format!("{name} must be in [0, 1], got {v}")));
        }
    }
    if !(1.0..=170.0).contains(&camera.fov) {
        return Err(CliError::Usage(format!("--fov must be in [1, 170] degrees, got {}", camera.fov)));
    }
    let (major, minor) = s.torus_radii;
    if !(major > 0.0 && minor > 0.0) {
        return Err(CliError::Usage(format!("--torus-radii must be positive, got {major},{minor}")));
    }
    if !(m.shininess > 0.0 && m.shininess.is_finite()) {
        return Err(CliError::Usage(format!("--shininess must be a positive number, got {}", m.shininess)));
    }
    let pattern = match l.spot_pattern.as_deref() {
        None => None,
        Some(spec) => {
            let field = HeightSource::parse(spec).load(Channel::Luminance)?;
            let image = Rgba8Image::from_gray(field.width(), field.height(), &field.to_u8());
            Some(Arc::new(Rgba8Mips::single(image)))
        }
    };
    let mut lights = l.lights.clone();
    if lights.is_empty() && (l.attenuation.is_some() || l.spot.is_some()) {
        lights.push(SceneLight::white(scenes::default_light(&kind)));
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
    let params = SceneParams {
        eye: camera.eye,
        target: camera.target,
        fov_y_degrees: camera.fov,
        lights,
        viewer: match camera.viewer {
            ViewerArg::Local => ViewerModel::Local,
            ViewerArg::Infinite => ViewerModel::Infinite,
        },
        height_field,
        normal_map: NormalMapOptions { scale: s.bump_scale, ..Default::default() },
        decal,
        default_decal: s.decal.is_none() && is_bricks,
        ambient: Vec3::splat(m.ambient),
        diffuse: Vec3::splat(m.diffuse),
        specular: Vec3::splat(m.specular),
        shininess: m.shininess,
        torus_radii: (major, minor),
        tessellation: s.tessellation,
        repeat: s.repeat.map(|(s, t)| Vec2::new(s, t)),
        bump_map: if s.space == SpaceArg::Object { BumpMap::ObjectSpace } else { BumpMap::Tangent },
        mip_mode: bumpmap_math::MipMode::LengthInAlpha,
    };
    if params.eye.is_some() && params.eye == params.target {
        return Err(CliError::Usage("--eye and --target must differ".into()));
    }
    Ok((scenes::build(&kind, &params).map_err(core_err)?, read))
}

/// The options of `--technique reference` the other options imply.
pub fn reference_options(setup: &SceneSetup) -> bumpmap_reference::ReferenceOptions {
    let t = &setup.technique;
    bumpmap_reference::ReferenceOptions {
        samples_per_pixel: t.spp as usize,
        self_shadow: self_shadow(t),
        specular_shadow: specular_shadow(t),
    }
}

/// Renders the reference image of `scene`, with a progress bar when `bar` is set.
pub fn reference(
    scene: &Scene,
    setup: &SceneSetup,
    width: usize,
    height: usize,
    bar: bool,
) -> Result<bumpmap_reference::LinearImage, CliError> {
    let options = reference_options(setup);
    let progress = indicatif::ProgressBar::new(0).with_style(
        indicatif::ProgressStyle::with_template("reference {bar:40} {pos}/{len} tiles {elapsed}")
            .expect("valid template"),
    );
    if !bar {
        progress.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let image = bumpmap_reference::render(scene, width, height, &options, &|done, total| {
        progress.set_length(total as u64);
        progress.set_position(done as u64);
    });
    progress.finish_and_clear();
    image.map_err(|e| CliError::Render(reference_err(e)))
}

/// A reference error in the words of the command line.
pub fn reference_err(e: bumpmap_reference::ReferenceError) -> String {
    use bumpmap_reference::ReferenceError;
    match e {
        ReferenceError::NoSurface { .. } => {
            "--technique reference needs a built-in surface (torus, wall, floor, wall-floor, patch, sphere), not a mesh"
                .into()
        }
        ReferenceError::SpotPattern { .. } => "--technique reference does not sample --spot-pattern".into(),
        other => other.to_string(),
    }
}

fn self_shadow(t: &crate::render_args::TechniqueGroup) -> SelfShadow {
    match (t.no_self_shadow, t.self_shadow) {
        (true, _) | (_, SelfShadowArg::Off) => SelfShadow::Off,
        (_, SelfShadowArg::Ramp) => SelfShadow::Ramp,
        (_, SelfShadowArg::Step) => SelfShadow::Step,
    }
}

fn specular_shadow(t: &crate::render_args::TechniqueGroup) -> SpecularShadow {
    match t.specular_shadow {
        SpecularShadowArg::Kilgard => SpecularShadow::Kilgard,
        SpecularShadowArg::Cg => SpecularShadow::CgTutorial,
        SpecularShadowArg::Off => SpecularShadow::Off,
    }
}

/// The technique the options name, with its options; refuses options that belong to the other
/// technique.
pub fn technique(setup: &SceneSetup) -> Result<Technique, CliError> {
    let (t, m) = (&setup.technique, &setup.material);
    let sampler = sampler(t.filter);
    match t.technique {
        TechniqueArg::Emboss => Ok(Technique::Emboss(bumpmap_core::technique::EmbossOptions {
            sampler,
            cube_size: t.cube_size as usize,
            ..Default::default()
        })),
        TechniqueArg::Reference => Err(CliError::Usage(
            "--technique reference renders on the CPU alone and is not a pass list: use it with `render` or `compare`"
                .into(),
        )),
        TechniqueArg::Kilgard => {
            let refuse = |feature| Err(core_err(CoreError::Unsupported { technique: "kilgard", feature }));
            if m.gloss.is_some() {
                return refuse(Feature::Gloss);
            }
            if t.normalize != NormalizeArg::Math {
                return refuse(Feature::NormalizeByMath);
            }
            if t.half_angle != HalfAngleArg::Vertex {
                return refuse(Feature::FragmentHalfAngle);
            }
            if t.self_shadow != SelfShadowArg::Ramp {
                return refuse(Feature::SelfShadowStep);
            }
            Ok(Technique::Kilgard(KilgardOptions {
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
                cube_size: t.cube_size as usize,
                ..Default::default()
            }))
        }
        TechniqueArg::SinglePass => {
            if t.specular_mode != SpecularArg::Power8 {
                return Err(CliError::Render(
                    "--specular-mode ramp belongs to --technique kilgard; single-pass takes --shininess".into(),
                ));
            }
            if t.precision != PrecisionArg::Float {
                return Err(CliError::Render(
                    "--precision belongs to --technique kilgard's register combiners; single-pass computes in float"
                        .into(),
                ));
            }
            let gloss = match m.gloss.as_deref() {
                None | Some("none") => Gloss::None,
                Some("decal-alpha") => Gloss::DecalAlpha,
                Some("bricks") => {
                    let g = Rgba8Image::from_gray(256, 256, &bumpmap_math::height::bricks_gloss(256, 256));
                    Gloss::Map(Arc::new(Rgba8Mips::with_box_mipmaps(g)))
                }
                Some(path) => {
                    Gloss::Map(Arc::new(Rgba8Mips::with_box_mipmaps(bumpmap_io::load_rgba8(Path::new(path))?)))
                }
            };
            Ok(Technique::SinglePass(SinglePassOptions {
                sampler,
                normalize: match t.normalize {
                    NormalizeArg::Math => Normalize::Math,
                    NormalizeArg::Cube => Normalize::Cube,
                },
                self_shadow: self_shadow(t),
                half_angle: match t.half_angle {
                    HalfAngleArg::Vertex => HalfAngle::Vertex,
                    HalfAngleArg::Fragment => HalfAngle::Fragment,
                },
                specular_shadow: specular_shadow(t),
                gloss,
                cube_size: t.cube_size as usize,
            }))
        }
    }
}

fn sampler(filter: FilterArg) -> Sampler {
    match filter {
        FilterArg::Nearest => Sampler::NEAREST_REPEAT,
        FilterArg::Linear => Sampler::LINEAR_REPEAT,
        FilterArg::Trilinear => Sampler::TRILINEAR_REPEAT,
    }
}

/// Writes `out` and, for each pass image of the frame, `OUT.NAME.png` beside it, all or none,
/// none of them replacing one of `inputs`; returns the paths written. The colour buffer's alpha
/// (s_self, not coverage) is left out.
pub fn write_frame(frame: &Frame, out: &Path, inputs: &[&Path]) -> Result<Vec<PathBuf>, CliError> {
    // The set makes a missing folder, and takes it away again if anything fails.
    let mut set = FileSet::new(inputs);
    for (name, image) in &frame.snapshots {
        let stem = out.file_stem().unwrap_or_default().to_string_lossy();
        let path = out.with_file_name(format!("{stem}.{name}.png"));
        save_png_into(&mut set, &path, image.width, image.height, PngLayout::Rgb8, &rgb(image))?;
    }
    save_png_into(&mut set, out, frame.image.width, frame.image.height, PngLayout::Rgb8, &rgb(&frame.image))?;
    Ok(set.commit()?)
}

/// An image's RGB bytes without alpha.
pub fn rgb(image: &Rgba8Image) -> Vec<u8> {
    image.texels.iter().flat_map(|&[r, g, b, _]| [r, g, b]).collect()
}
