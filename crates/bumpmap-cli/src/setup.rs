//! The option groups `render` and `bench render` share, turned into what the front door
//! takes: a [`SceneSpec`] (with the user's own assets loaded), a technique of the catalogue and
//! its options. Values out of range are usage errors (status 2); options that belong to another
//! technique are refused by name.
//!
//! What this module does not do: draw (`bumpmap::Renderer`), or decide what a technique can do
//! (the catalogue and the core refuse that, and `crate::render::core_err` names the flag).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap::assets::{MeshLoad, load_mesh, load_normal_map, mesh_asset};
use bumpmap::bumpmap_core::combiners::Precision;
use bumpmap::bumpmap_core::parallax::ParallaxOptions;
use bumpmap::bumpmap_core::scenes;
use bumpmap::bumpmap_core::state::Sampler;
use bumpmap::bumpmap_core::technique::single_pass;
use bumpmap::{
    BumpSource, Gloss, HalfAngle, ImportOptions, KilgardOptions, MipMode, Normalize, ReferenceOptions, Rgba8Image,
    Rgba8Mips, SceneKind, SceneLight, SceneSpec, SelfShadow, SpecularMode, SpecularShadow, Spot, Technique,
    TechniqueName, TechniqueOptions, ViewerModel,
};
use bumpmap_io::{Channel, HeightSource, MeshOptions};
use glam::{Vec2, Vec3};

use crate::args::{
    FilterArg, HalfAngleArg, NormalizeArg, PrecisionArg, SceneSetup, SelfShadowArg, SpecularArg, SpecularFilterArg,
    SpecularShadowArg, TechniqueGroup, ViewerArg,
};
use crate::error::CliError;
use crate::render::{core_err, lib_err};

mod files;

use files::{decal_mips, files_beside, load_roughness_map, texture_file};

/// What the options describe.
pub struct Setup {
    /// The scene, with the user's assets in it.
    pub spec: SceneSpec,
    /// The options of `--technique`'s family (and every other family's, at the values the
    /// options give).
    pub options: TechniqueOptions,
    /// Every file read: no output may replace one.
    pub inputs: Vec<PathBuf>,
    /// What the assets brought and what they left out, a line each for stderr.
    pub notes: Vec<String>,
}

/// The largest |--bump-scale| a normal map takes (a height field takes up to 1e6).
const MAX_NORMAL_SCALE: f32 = bumpmap::bumpmap_math::imported::MAX_SCALE;

/// The largest side of a spotlight pattern as it is sampled. The pattern has no mip levels (the
/// fixed-function projective texture had none either), so texels past what any framebuffer
/// shows only cost memory: a 16384² pattern took 3.1 GB and 27 s for a 64² render.
const MAX_SPOT_PATTERN: usize = 2048;

/// Files the options name, before anything is read: an output must replace none of them.
pub fn named_inputs(s: &SceneSetup) -> Vec<PathBuf> {
    let mut files = Vec::new();
    if let Some(p) = s.scene.scene.strip_prefix("mesh:") {
        files.push(PathBuf::from(p));
    }
    if let Some(p) = s.scene.height_field.as_deref().and_then(|h| HeightSource::parse(h).path().map(Path::to_path_buf))
    {
        files.push(p);
    }
    files.extend(s.scene.normal_map.clone());
    if let Some(d) = s.scene.decal.as_deref().filter(|d| *d != "none") {
        files.push(PathBuf::from(d));
    }
    files.extend(s.material.roughness_map.clone());
    if let Some(h) = &s.heights.height_map {
        files.push(h.clone());
        files.push(bumpmap_io::height_file::minmax_path(h));
    }
    for spec in [&s.lights.spot_pattern, &s.material.gloss].into_iter().flatten() {
        if let Some(p) =
            HeightSource::parse(spec).path().filter(|_| !matches!(spec.as_str(), "bricks" | "decal-alpha" | "none"))
        {
            files.push(p.to_path_buf());
        }
    }
    files
}

/// Inputs given in memory instead of read from files (the Python package's arrays): each
/// stands where the file its option names would, and is used exactly as that file's contents
/// would be. The option must still be given (its value names the input in messages).
#[derive(Clone, Debug, Default)]
pub struct Given {
    /// `--normal-map`'s texture, as the file would load.
    pub normal_map: Option<bumpmap_io::StoredTexture>,
    /// `--height-field`'s heights.
    pub height_field: Option<bumpmap::HeightField>,
    /// `--decal`'s image.
    pub decal: Option<Rgba8Image>,
    /// The mesh `--scene mesh:NAME` draws, in place of reading the file NAME (no material: the
    /// scene's bumps and decal, as for an OBJ). Its normals are made from the faces where it
    /// has none, its tangents where it has none.
    pub mesh: Option<bumpmap_io::LoadedMesh>,
}

/// Reads the options: checks their ranges, loads the files they name and builds the scene
/// description, the technique and its options.
pub fn setup(s: &SceneSetup) -> Result<Setup, CliError> {
    setup_given(s, &Given::default())
}

/// [`setup`], with the inputs `given` in memory in place of the files their options name.
pub fn setup_given(s: &SceneSetup, given: &Given) -> Result<Setup, CliError> {
    let (scene, camera, m) = (&s.scene, &s.camera, &s.material);
    check_ranges(s)?;
    let mut inputs = named_inputs(s);
    let mut notes = Vec::new();
    let bump_scale = scene.bump_scale;
    let own_bumps = scene.height_field.is_some() || scene.normal_map.is_some();

    // The geometry, with a mesh's own material unless options replace it.
    let mut spec = match scene.scene.strip_prefix("mesh:") {
        Some(path) => {
            let path = Path::new(path);
            let load = MeshLoad {
                mesh: MeshOptions {
                    allow_outside_paths: scene.allow_outside_paths,
                    obj_texcoords: scene.obj_v.into(),
                    read_normal_texture: !own_bumps,
                    read_base_color_texture: scene.decal.is_none(),
                },
                normal_scale: bump_scale,
                mip_mode: MipMode::LengthInAlpha,
            };
            let asset = match &given.mesh {
                Some(loaded) => {
                    let mut loaded = loaded.clone();
                    // Not a file's fault: a value error, named as the caller named the mesh.
                    loaded.mesh.validate().map_err(|e| CliError::Render(format!("{}: {e}", path.display())))?;
                    if !loaded.had_normals {
                        loaded.mesh.compute_normals();
                    }
                    mesh_asset(loaded, path, &load).map_err(lib_err)?
                }
                None => load_mesh(path, &load).map_err(lib_err)?,
            };
            // Every vertex at one point: no extent to frame or to see (not a usage error).
            let p0 = asset.mesh.positions.first().copied().unwrap_or_default();
            if asset.mesh.positions.iter().all(|p| *p == p0) {
                return Err(CliError::Path {
                    path: path.to_path_buf(),
                    reason: format!("every vertex is at {p0}: the mesh has no extent, so there is nothing to draw"),
                });
            }
            inputs.extend(asset.sources.iter().cloned());
            notes.extend(asset.describe().into_iter().map(|line| format!("{}: {line}", path.display())));
            notes.extend(asset.warnings.iter().map(|w| format!("warning: {w}")));
            if !asset.materials.is_empty() {
                if asset.materials.iter().all(|m| m.normal_map.is_none()) && !own_bumps && bump_scale.is_some() {
                    notes.push(format!(
                        "{}: --bump-scale has nothing to scale: the material has no normalTexture (--height-field or --normal-map add bumps)",
                        path.display()
                    ));
                }
                if scene.height_field.is_some() {
                    notes.push(format!("{}: --height-field replaces the material's bumps", path.display()));
                }
                if scene.normal_map.is_some() {
                    notes.push(format!("{}: --normal-map replaces the material's normal map", path.display()));
                }
                if scene.decal.is_some() {
                    notes.push(format!("{}: --decal replaces the material's base colour", path.display()));
                }
            }
            asset.spec()
        }
        None => SceneSpec::new(SceneKind::parse(&scene.scene).ok_or_else(|| {
            CliError::Usage(format!(
                "unknown scene '{}': use {} or mesh:FILE",
                scene.scene,
                SceneKind::built_in_names()
            ))
        })?),
    };
    let has_material_bumps =
        matches!(spec.kind, SceneKind::Mesh(_)) && matches!(spec.params.bumps, BumpSource::NormalMap(_));

    // The bumps: a normal map as it is, a height field, the material's, or the bricks.
    if let Some(path) = &scene.normal_map {
        let options = ImportOptions {
            y_convention: scene.y_convention.into(),
            scale: bump_scale.unwrap_or(1.0),
            mip_mode: MipMode::LengthInAlpha,
            rebuild_mips: scene.rebuild_mips,
        };
        let map = match &given.normal_map {
            Some(texture) => bumpmap::assets::normal_map_from_texture(texture, path, &options),
            None => load_normal_map(path, &options),
        }
        .map_err(lib_err)?;
        notes.push(format!(
            "{}: {} as the normal map (green {})",
            path.display(),
            map.describe(),
            if options.y_convention == bumpmap::YConvention::YUp { "up: opengl" } else { "down: directx" }
        ));
        notes.extend(map.warnings().iter().map(|w| format!("warning: {w}")));
        spec.use_bumps(map.bumps(), false);
    } else if !has_material_bumps || scene.height_field.is_some() {
        let source = HeightSource::parse(scene.height_field.as_deref().unwrap_or("bricks"));
        let field = match &given.height_field {
            Some(field) => field.clone(),
            None => source.load(Channel::Luminance)?,
        };
        let is_bricks = given.height_field.is_none()
            && matches!(source, HeightSource::Preset { preset: bumpmap::HeightPreset::Bricks, .. });
        spec.use_bumps(BumpSource::Heights(Arc::new(field)), is_bricks);
        spec.params.normal_map.scale = bump_scale.unwrap_or(4.0);
    }

    // The decal: the option's, or none, or what the scene already has.
    match scene.decal.as_deref() {
        Some("none") => spec.use_decal(None),
        Some(path) => spec.use_decal(Some(match &given.decal {
            Some(image) => decal_mips(image.clone(), Path::new(path))?,
            None => texture_file(Path::new(path))?,
        })),
        None => {}
    }

    // Heights as geometry: a file's, and how deep.
    if let Some(path) = &s.heights.height_map {
        let heights = bumpmap_io::height_file::load_heights(path)?;
        let (hs, ns) = ((heights.width(), heights.height()), spec.params.bumps.size());
        if hs != ns {
            return Err(CliError::Path {
                path: path.clone(),
                reason: format!(
                    "is {}x{}, but the normal map is {}x{}: heights are read at the normal map's texture coordinates and levels",
                    hs.0, hs.1, ns.0, ns.1
                ),
            });
        }
        let technique = s.technique.technique.0;
        if technique.parallax_method() == Some(bumpmap::ParallaxMethod::Exact) && heights.minmax().is_none() {
            return Err(CliError::Path {
                path: path.clone(),
                reason: format!(
                    "has no min–max levels beside it ({} not found), and --technique {technique} walks them: \
                     write the heights again with `bumpmap normalmap --mips --height-out H`, or use --technique pom",
                    bumpmap_io::height_file::minmax_path(path).display()
                ),
            });
        }
        notes.push(format!(
            "{}: heights as geometry, {}x{}, {} levels, {}",
            path.display(),
            hs.0,
            hs.1,
            heights.levels().len(),
            if heights.minmax().is_some() {
                "with min–max levels"
            } else {
                "without min–max levels (height-exact needs them)"
            }
        ));
        spec.params.height_mips = Some(Arc::new(heights));
    }
    if let Some(path) = &s.heights.horizon_map {
        let horizons = bumpmap_io::horizon_file::load_horizons(path)?;
        let (hs, ns) = ((horizons.width(), horizons.height()), spec.params.bumps.size());
        if hs != ns {
            return Err(CliError::Path {
                path: path.clone(),
                reason: format!(
                    "is {}x{}, but the normal map is {}x{}: horizons are read at the normal map's texture coordinates and levels",
                    hs.0, hs.1, ns.0, ns.1
                ),
            });
        }
        notes.push(format!(
            "{}: horizon map, {}x{}, {} directions, {} levels",
            path.display(),
            hs.0,
            hs.1,
            bumpmap::bumpmap_math::horizon::AZIMUTHS,
            horizons.levels().len()
        ));
        spec.params.horizon_map = Some(Arc::new(horizons));
    }
    spec.params.depth = s.heights.depth;

    let p = &mut spec.params;
    p.eye = camera.eye;
    p.target = camera.target;
    p.up = camera.up;
    p.fov_y_degrees = camera.fov;
    p.viewer = match camera.viewer {
        ViewerArg::Local => ViewerModel::Local,
        ViewerArg::Infinite => ViewerModel::Infinite,
    };
    p.ambient = Vec3::splat(m.ambient);
    p.diffuse = Vec3::splat(m.diffuse);
    p.specular = Vec3::splat(m.specular);
    p.shininess = m.shininess;
    p.torus_radii = scene.torus_radii;
    p.tessellation = scene.tessellation;
    p.repeat = scene.repeat.map(|(s, t)| Vec2::new(s, t));
    spec.params.lights = lights(s, &spec)?;

    let options = technique_options(s, s.technique.technique.0)?;
    inputs.extend(files_beside(s)?);
    Ok(Setup { spec, options, inputs, notes })
}

/// Values out of their ranges, found after parsing: usage errors, named by flag.
fn check_ranges(s: &SceneSetup) -> Result<(), CliError> {
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
fn lights(s: &SceneSetup, spec: &SceneSpec) -> Result<Vec<SceneLight>, CliError> {
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
fn technique_options(s: &SceneSetup, name: TechniqueName) -> Result<TechniqueOptions, CliError> {
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
