//! The scene built from options: the geometry (a built-in surface, or a mesh with its own
//! material unless the options replace it), the bumps, the decal, heights as geometry, the
//! camera, material and lights. What this module does not do: check ranges or make a
//! technique's options (`technique`).

use std::path::Path;
use std::sync::Arc;

use bumpmap_core::{BumpSource, SceneKind, SceneSpec};
use bumpmap_io::{Channel, HeightSource, MeshOptions};
use bumpmap_math::imported::ImportOptions;
use bumpmap_math::{HeightPreset, MipMode};
use glam::Vec3;

use super::detail;
use super::error::BesideMap;
use super::files::{decal_mips, files_beside, named_inputs, texture_file};
use super::technique::{check_ranges, lights, technique_options};
use super::{DecalChoice, Given, SceneChoice, SceneOption, SceneOptions, SetUp, SetupError, SetupNote};
use crate::assets::{MeshLoad, given_or_load_normal_map, green_way, load_mesh, mesh_asset};

pub(super) fn set_up(o: &SceneOptions, given: &Given) -> Result<SetUp, SetupError> {
    check_ranges(o)?;
    let mut inputs = named_inputs(o);
    let mut notes = Vec::new();
    let own_bumps = o.height_field.is_some() || o.normal_map.is_some();

    // The geometry, with a mesh's own material unless options replace it.
    let mut spec = match &o.scene {
        SceneChoice::Mesh(path) => mesh_spec(o, given, path, own_bumps, &mut inputs, &mut notes)?,
        SceneChoice::BuiltIn(kind) => SceneSpec::new(kind.clone()),
    };
    let has_material_bumps =
        matches!(spec.kind, SceneKind::Mesh(_)) && matches!(spec.params.bumps, BumpSource::NormalMap(_));

    // The bumps: a normal map as it is, a height field, the material's, or the bricks.
    if let Some(path) = &o.normal_map {
        let options = ImportOptions {
            y_convention: o.y_convention,
            scale: o.bump_scale.unwrap_or(1.0),
            mip_mode: MipMode::LengthInAlpha,
            rebuild_mips: o.rebuild_mips,
        };
        let map = given_or_load_normal_map(path, given.normal_map.as_ref(), &options)?;
        notes.push(SetupNote::About {
            path: path.clone(),
            line: format!("{} as the normal map (green {})", map.describe(), green_way(options.y_convention)),
        });
        notes.extend(map.warnings().iter().map(|w| SetupNote::Warning(w.to_string())));
        spec.use_bumps(map.bumps(), false);
    } else if !has_material_bumps || o.height_field.is_some() {
        let bricks = HeightSource::Preset { preset: HeightPreset::Bricks, size: HeightPreset::DEFAULT_SIZE };
        let source = o.height_field.as_ref().unwrap_or(&bricks);
        let field = match &given.height_field {
            Some(field) => field.clone(),
            None => source.load(Channel::Luminance)?,
        };
        let is_bricks =
            given.height_field.is_none() && matches!(source, HeightSource::Preset { preset: HeightPreset::Bricks, .. });
        spec.use_bumps(BumpSource::Heights(Arc::new(field)), is_bricks);
        spec.params.normal_map.scale = o.bump_scale.unwrap_or(4.0);
    }

    // The decal: the option's, or none, or what the scene already has.
    match &o.decal {
        Some(DecalChoice::None) => spec.use_decal(None),
        Some(DecalChoice::File(path)) => spec.use_decal(Some(match &given.decal {
            Some(image) => decal_mips(image.clone(), path)?,
            None => texture_file(path)?,
        })),
        None => {}
    }

    heights_as_geometry(o, &mut spec, &mut notes)?;

    let (camera, m) = (&o.camera, &o.material);
    let p = &mut spec.params;
    p.eye = camera.eye;
    p.target = camera.target;
    p.up = camera.up;
    p.fov_y_degrees = camera.fov_y_degrees;
    p.viewer = camera.viewer;
    p.ambient = Vec3::splat(m.ambient);
    p.diffuse = Vec3::splat(m.diffuse);
    p.specular = Vec3::splat(m.specular);
    p.shininess = m.shininess;
    p.torus_radii = o.torus_radii;
    p.tessellation = o.tessellation;
    p.repeat = o.repeat;
    p.decode = o.technique.decode;
    spec.params.lights = lights(o, &spec)?;

    let mut options = technique_options(o, &mut notes)?;
    options.single_pass.detail = detail::detail_layer(o, given, &mut notes)?;
    inputs.extend(files_beside(o)?);
    Ok(SetUp { spec, options, inputs, notes })
}

/// A mesh's scene, with its material's maps unless the options replace them.
fn mesh_spec(
    o: &SceneOptions,
    given: &Given,
    path: &Path,
    own_bumps: bool,
    inputs: &mut Vec<std::path::PathBuf>,
    notes: &mut Vec<SetupNote>,
) -> Result<SceneSpec, SetupError> {
    let load = MeshLoad {
        mesh: MeshOptions {
            allow_outside_paths: o.allow_outside_paths,
            obj_texcoords: o.obj_texcoords,
            read_normal_texture: !own_bumps,
            read_base_color_texture: o.decal.is_none(),
        },
        normal_scale: o.bump_scale,
        mip_mode: MipMode::LengthInAlpha,
    };
    let asset = match &given.mesh {
        Some(loaded) => {
            let mut loaded = loaded.clone();
            // Not a file's fault: a value error, named as the caller named the mesh.
            loaded
                .mesh
                .validate()
                .map_err(|e| SetupError::MeshValues { path: path.to_path_buf(), reason: e.to_string() })?;
            if !loaded.had_normals {
                loaded.mesh.compute_normals();
            }
            mesh_asset(loaded, path, &load)?
        }
        None => load_mesh(path, &load)?,
    };
    // Every vertex at one point: no extent to frame or to see.
    let p0 = asset.mesh.positions.first().copied().unwrap_or_default();
    if asset.mesh.positions.iter().all(|p| *p == p0) {
        return Err(SetupError::NoExtent { path: path.to_path_buf(), at: p0 });
    }
    inputs.extend(asset.sources.iter().cloned());
    notes.extend(asset.describe().into_iter().map(|line| SetupNote::About { path: path.to_path_buf(), line }));
    notes.extend(asset.warnings.iter().map(|w| SetupNote::Warning(w.to_string())));
    if !asset.materials.is_empty() {
        if asset.materials.iter().all(|m| m.normal_map.is_none()) && !own_bumps && o.bump_scale.is_some() {
            notes.push(SetupNote::NothingToScale { path: path.to_path_buf() });
        }
        let names_filters = asset.materials.iter().any(|m| m.sampler.min.is_some() || m.sampler.mag.is_some());
        for (given, option) in [
            (o.height_field.is_some(), SceneOption::HeightField),
            (o.normal_map.is_some(), SceneOption::NormalMap),
            (o.decal.is_some(), SceneOption::Decal),
            (o.technique.filter.is_some() && names_filters, SceneOption::Filter),
        ] {
            if given {
                notes.push(SetupNote::Replaces { path: path.to_path_buf(), option });
            }
        }
    }
    let mut spec = asset.spec();
    // A filter the caller chose wins over the file's samplers (their wrap modes stay).
    if let (Some(_), Some(parts)) = (o.technique.filter, &mut spec.params.parts) {
        Arc::make_mut(parts).replace_filters();
    }
    Ok(spec)
}

/// Heights as geometry: a heights file's and a horizon file's maps (each the normal map's
/// size), and how deep.
fn heights_as_geometry(o: &SceneOptions, spec: &mut SceneSpec, notes: &mut Vec<SetupNote>) -> Result<(), SetupError> {
    let normal_map = spec.params.bumps.size();
    let mismatch =
        |path: &Path, map, size| SetupError::SizeMismatch { path: path.to_path_buf(), map, size, normal_map };
    // Each file's size from its header, against the normal map's, before it is decoded.
    // (A missing file is left to the reader's own message.)
    let declared = |path: &Path, map| {
        let what = if map == BesideMap::Heights { "heights" } else { "horizon maps" };
        bumpmap_io::height_file::check_container(path, what)?;
        match std::fs::metadata(path).is_ok().then(|| bumpmap_io::declared_size(path)).transpose()? {
            Some(size) if size != normal_map => Err(mismatch(path, map, size)),
            _ => Ok(()),
        }
    };
    if let Some(path) = &o.heights.height_map {
        declared(path, BesideMap::Heights)?;
        let heights = bumpmap_io::height_file::load_heights(path)?;
        let size = (heights.width(), heights.height());
        let technique = o.technique.technique;
        if technique.parallax_method() == Some(bumpmap_core::parallax::ParallaxMethod::Exact)
            && heights.minmax().is_none()
        {
            return Err(SetupError::NoMinMax {
                path: path.clone(),
                minmax: bumpmap_io::height_file::minmax_path(path),
                technique,
            });
        }
        notes.push(SetupNote::About {
            path: path.clone(),
            line: format!(
                "heights as geometry, {}x{}, {} levels, {}",
                size.0,
                size.1,
                heights.levels().len(),
                if heights.minmax().is_some() {
                    "with min–max levels"
                } else {
                    "without min–max levels (height-exact needs them)"
                }
            ),
        });
        spec.params.height_mips = Some(Arc::new(heights));
    }
    if let Some(path) = &o.heights.horizon_map {
        declared(path, BesideMap::Horizons)?;
        let horizons = bumpmap_io::horizon_file::load_horizons(path)?;
        let size = (horizons.width(), horizons.height());
        notes.push(SetupNote::About {
            path: path.clone(),
            line: format!(
                "horizon map, {}x{}, {} directions, {} levels",
                size.0,
                size.1,
                bumpmap_math::horizon::AZIMUTHS,
                horizons.levels().len()
            ),
        });
        spec.params.horizon_map = Some(Arc::new(horizons));
    }
    spec.params.depth = o.heights.depth;
    Ok(())
}
