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
use bumpmap::{BumpSource, ImportOptions, MipMode, Rgba8Image, SceneKind, SceneSpec, TechniqueOptions, ViewerModel};
use bumpmap_io::{Channel, HeightSource, MeshOptions};
use glam::{Vec2, Vec3};

use crate::args::{SceneSetup, ViewerArg};
use crate::error::CliError;
use crate::render::lib_err;

mod files;
mod options;

use files::{decal_mips, files_beside, texture_file};
use options::{check_ranges, lights, technique_options};

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
