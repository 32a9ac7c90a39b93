//! `bumpmap render`: a scene, a technique, a PNG (and, with `--passes`, one per pass).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap_io::atomic::ensure_not_input;
use bumpmap_io::image_file::{PngLayout, save_png};
use bumpmap_io::{Channel, HeightSource};
use bumpmap_math::NormalMapOptions;
use bumpmap_raster::combiners::Precision;
use bumpmap_raster::kilgard::{self, KilgardOptions, SpecularMode};
use bumpmap_raster::scene::{Scene, Spot, ViewerModel};
use bumpmap_raster::scenes::{self, SceneKind, SceneParams};
use bumpmap_raster::single_pass::{self, Gloss, HalfAngle, Normalize, SelfShadow, SinglePassOptions, SpecularShadow};
use bumpmap_raster::texture::{Sampler, Texture2d};
use bumpmap_raster::{Framebuffer, RasterError};
use glam::{Vec2, Vec3};

use crate::args::{
    FilterArg, HalfAngleArg, NormalizeArg, PrecisionArg, RenderArgs, SelfShadowArg, SpecularArg, SpecularShadowArg,
    TechniqueArg, ViewerArg,
};
use crate::error::CliError;

pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let (width, height) = match (args.width, args.height) {
        (Some(w), Some(h)) => (w, h),
        _ => (args.size, args.size),
    };
    let inputs = input_files(args);
    let input_refs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    ensure_not_input(&args.output, &input_refs)?;
    // Refuse an impossible framebuffer before any work.
    let mut fb = Framebuffer::new(width, height).map_err(raster_err)?;
    let scene = build_scene(args)?;
    let written = render_to(&scene, args, &mut fb, &args.output)?;
    eprintln!("wrote {}", written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "));
    Ok(())
}

fn raster_err(e: RasterError) -> CliError {
    CliError::Render(e.to_string())
}

/// Files the command reads, which an output must never replace.
fn input_files(args: &RenderArgs) -> Vec<PathBuf> {
    let mut files = Vec::new();
    if let Some(p) = args.scene.strip_prefix("mesh:") {
        files.push(PathBuf::from(p));
    }
    if let Some(p) = HeightSource::parse(&args.height_field).path() {
        files.push(p.to_path_buf());
    }
    if let Some(d) = args.decal.as_deref().filter(|d| *d != "none") {
        files.push(PathBuf::from(d));
    }
    files
}

/// The scene the arguments describe.
pub fn build_scene(args: &RenderArgs) -> Result<Scene, CliError> {
    let kind = match args.scene.strip_prefix("mesh:") {
        Some(path) => SceneKind::Mesh(Arc::new(crate::mesh::load_for_render(Path::new(path))?)),
        None => SceneKind::parse(&args.scene).ok_or_else(|| {
            CliError::Render(format!(
                "unknown scene '{}': use torus, wall, floor, wall-floor, patch, sphere or mesh:FILE",
                args.scene
            ))
        })?,
    };
    let source = HeightSource::parse(&args.height_field);
    let height_field = source.load(Channel::Luminance)?;
    let is_bricks = matches!(source, HeightSource::Preset { preset: bumpmap_math::HeightPreset::Bricks, .. });
    let decal = match args.decal.as_deref() {
        None | Some("none") => None,
        Some(path) => {
            let (w, h, texels) = bumpmap_io::load_rgba8(Path::new(path))?;
            Some(Texture2d::from_rgba8(w, h, texels))
        }
    };
    for (name, v) in [("--ambient", args.ambient), ("--diffuse", args.diffuse), ("--specular", args.specular)] {
        if !(0.0..=1.0).contains(&v) {
            return Err(CliError::Render(format!("{name} must be in [0, 1], got {v}")));
        }
    }
    if !(1.0..=170.0).contains(&args.fov) {
        return Err(CliError::Render(format!("--fov must be in [1, 170] degrees, got {}", args.fov)));
    }
    let (major, minor) = args.torus_radii;
    if !(major > 0.0 && minor > 0.0) {
        return Err(CliError::Render(format!("--torus-radii must be positive, got {major},{minor}")));
    }
    if !(args.shininess > 0.0 && args.shininess.is_finite()) {
        return Err(CliError::Render(format!("--shininess must be a positive number, got {}", args.shininess)));
    }
    let pattern = match args.spot_pattern.as_deref() {
        None => None,
        Some(spec) => {
            let field = HeightSource::parse(spec).load(Channel::Luminance)?;
            let bytes = field.to_u8();
            Some(Arc::new(Texture2d::from_rgba8(
                field.width(),
                field.height(),
                bytes.iter().map(|&v| [v, v, v, 255]).collect(),
            )))
        }
    };
    let mut lights = args.lights.clone();
    if lights.is_empty() && (args.attenuation.is_some() || args.spot.is_some()) {
        lights.push(bumpmap_raster::scene::SceneLight::white(bumpmap_raster::scenes::default_light(&kind)));
    }
    for light in &mut lights {
        if let Some(a) = args.attenuation {
            light.attenuation = a;
        }
        if let Some(direction) = args.spot {
            light.spot = Some(Spot {
                direction,
                cutoff_degrees: args.spot_cutoff,
                exponent: args.spot_exponent,
                pattern: pattern.clone(),
            });
        }
        single_pass::validate_light(light).map_err(raster_err)?;
    }
    let params = SceneParams {
        eye: args.eye,
        target: args.target,
        fov_y_degrees: args.fov,
        lights,
        viewer: match args.viewer {
            ViewerArg::Local => ViewerModel::Local,
            ViewerArg::Infinite => ViewerModel::Infinite,
        },
        height_field,
        normal_map: NormalMapOptions { scale: args.bump_scale, ..Default::default() },
        decal,
        default_decal: args.decal.is_none() && is_bricks,
        ambient: Vec3::splat(args.ambient),
        diffuse: Vec3::splat(args.diffuse),
        specular: Vec3::splat(args.specular),
        shininess: args.shininess,
        torus_radii: (major, minor),
        tessellation: args.tessellation,
        repeat: args.repeat.map(|(s, t)| Vec2::new(s, t)),
        object_space: args.space == crate::args::SpaceArg::Object,
    };
    if params.eye.is_some() && params.eye == params.target {
        return Err(CliError::Render("--eye and --target must differ".into()));
    }
    scenes::build(&kind, &params).map_err(raster_err)
}

/// The three-pass technique's options; refuses what its combiners cannot do.
pub fn kilgard_options(args: &RenderArgs) -> Result<KilgardOptions, CliError> {
    let unsupported = |what: &str| {
        Err(CliError::Render(format!(
            "--technique kilgard cannot do {what}: the paper's combiners have no room for it; use --technique single-pass"
        )))
    };
    if args.shininess != 8.0 {
        return unsupported("--shininess other than 8 (use --specular-mode ramp for a tighter highlight)");
    }
    if args.gloss.is_some() {
        return unsupported("--gloss");
    }
    if args.attenuation.is_some() || args.spot.is_some() {
        return unsupported("attenuation or spotlights");
    }
    if args.normalize != NormalizeArg::Math
        || args.half_angle != HalfAngleArg::Vertex
        || args.self_shadow != SelfShadowArg::Ramp
    {
        return unsupported(
            "--normalize, --half-angle or --self-shadow (it always normalizes by cube map, per vertex H, ramp or --no-self-shadow)",
        );
    }
    Ok(KilgardOptions {
        sampler: sampler(args.filter),
        self_shadow: !args.no_self_shadow,
        specular: match args.specular_mode {
            SpecularArg::Power8 => SpecularMode::EighthPower,
            SpecularArg::Ramp => SpecularMode::Ramp,
        },
        precision: match args.precision {
            PrecisionArg::Float => Precision::Float,
            PrecisionArg::Fixed9 => Precision::Fixed9,
        },
        cube_size: args.cube_size as usize,
        ..Default::default()
    })
}

/// The single-pass technique's options.
pub fn single_pass_options(args: &RenderArgs) -> Result<SinglePassOptions, CliError> {
    let gloss = match args.gloss.as_deref() {
        None | Some("none") => Gloss::None,
        Some("decal-alpha") => Gloss::DecalAlpha,
        Some("bricks") => {
            let (w, h) = (256, 256);
            let g: Vec<[u8; 4]> =
                bumpmap_math::height::bricks_gloss(w, h).into_iter().map(|v| [v, v, v, 255]).collect();
            Gloss::Map(Arc::new(Texture2d::from_rgba8(w, h, g).with_box_mipmaps()))
        }
        Some(path) => {
            let (w, h, texels) = bumpmap_io::load_rgba8(Path::new(path))?;
            Gloss::Map(Arc::new(Texture2d::from_rgba8(w, h, texels).with_box_mipmaps()))
        }
    };
    if args.specular_mode != SpecularArg::Power8 {
        return Err(CliError::Render(
            "--specular-mode ramp belongs to --technique kilgard; single-pass takes --shininess".into(),
        ));
    }
    Ok(SinglePassOptions {
        sampler: sampler(args.filter),
        normalize: match args.normalize {
            NormalizeArg::Math => Normalize::Math,
            NormalizeArg::Cube => Normalize::Cube,
        },
        self_shadow: match (args.no_self_shadow, args.self_shadow) {
            (true, _) | (_, SelfShadowArg::Off) => SelfShadow::Off,
            (_, SelfShadowArg::Ramp) => SelfShadow::Ramp,
            (_, SelfShadowArg::Step) => SelfShadow::Step,
        },
        half_angle: match args.half_angle {
            HalfAngleArg::Vertex => HalfAngle::Vertex,
            HalfAngleArg::Fragment => HalfAngle::Fragment,
        },
        specular_shadow: match args.specular_shadow {
            SpecularShadowArg::Kilgard => SpecularShadow::Kilgard,
            SpecularShadowArg::Cg => SpecularShadow::CgTutorial,
            SpecularShadowArg::Off => SpecularShadow::Off,
        },
        gloss,
        cube_size: args.cube_size as usize,
    })
}

fn sampler(filter: FilterArg) -> Sampler {
    match filter {
        FilterArg::Nearest => Sampler::NEAREST_REPEAT,
        FilterArg::Linear => Sampler::LINEAR_REPEAT,
        FilterArg::Trilinear => Sampler::TRILINEAR_REPEAT,
    }
}

/// Renders and writes `out` (and the pass images); returns the paths written.
pub fn render_to(scene: &Scene, args: &RenderArgs, fb: &mut Framebuffer, out: &Path) -> Result<Vec<PathBuf>, CliError> {
    let mut passes: Vec<(String, Vec<u8>)> = Vec::new();
    match args.technique {
        TechniqueArg::Kilgard => kilgard::render(scene, &kilgard_options(args)?, fb, |name, fb| {
            if args.passes {
                passes.push((name.to_string(), rgb(fb)));
            }
        })
        .map_err(raster_err)?,
        TechniqueArg::SinglePass => single_pass::render(scene, &single_pass_options(args)?, fb).map_err(raster_err)?,
    }
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| CliError::Path { path: dir.to_path_buf(), reason: e.to_string() })?;
    }
    let mut written = Vec::new();
    for (name, bytes) in &passes {
        let stem = out.file_stem().unwrap_or_default().to_string_lossy();
        let path = out.with_file_name(format!("{stem}.{name}.png"));
        save_png(&path, fb.width, fb.height, PngLayout::Rgb8, bytes)?;
        written.push(path);
    }
    save_png(out, fb.width, fb.height, PngLayout::Rgb8, &rgb(fb))?;
    written.push(out.to_path_buf());
    Ok(written)
}

/// The colour buffer without its alpha (which holds s_self, not coverage).
pub fn rgb(fb: &Framebuffer) -> Vec<u8> {
    fb.to_rgba8().into_iter().flat_map(|[r, g, b, _]| [r, g, b]).collect()
}
