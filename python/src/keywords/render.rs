//! `render`'s and `Renderer.prepare`'s keywords: the scene's options, the frame's size and the
//! backend, with the arrays given in place of files.

use std::path::PathBuf;

use bumpmap::frame::FrameRequest;
use bumpmap::maps::Chain;
use bumpmap::options::Given;
use bumpmap::options::{DecalChoice, GlossChoice, SceneChoice, SceneOptions};
use bumpmap::{SceneKind, SelfShadow, TechniqueName};
use bumpmap_io::HeightSource;
use glam::Vec2;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyString, PyTuple};

use super::{Reader, given, unexpected};
use crate::arrays;

/// An array, or a list or tuple of arrays (a normal map's chain).
fn is_arrays(value: &Bound<'_, PyAny>) -> PyResult<bool> {
    let is_array = |v: &Bound<'_, PyAny>| v.cast::<numpy::PyUntypedArray>().is_ok();
    if is_array(value) {
        return Ok(true);
    }
    Ok((value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>())
        && value.len()? > 0
        && value.try_iter()?.all(|v| v.is_ok_and(|v| is_array(&v))))
}

/// A Python error raised while reading `name`'s array, prefixed with the function and keyword.
fn prefixed(py: Python<'_>, function: &str, name: &str, e: PyErr) -> PyErr {
    let message = format!("{function}(): {name}: {}", e.value(py));
    if e.is_instance_of::<PyTypeError>(py) { PyTypeError::new_err(message) } else { PyValueError::new_err(message) }
}

/// `render`'s keywords (`backend` included where `with_backend`) as the request they make and
/// the arrays given in place of files.
pub fn render_request(
    py: Python<'_>,
    function: &str,
    kwargs: Option<&Bound<'_, PyDict>>,
    with_backend: bool,
) -> PyResult<(FrameRequest, Given)> {
    let r = Reader { function };
    let mut request = FrameRequest::default();
    let mut arrays = Given::default();
    let mut no_self_shadow = false;
    let (mut size, mut width, mut height) = (None, None, None);
    let mut present: Vec<String> = Vec::new();
    let o: &mut SceneOptions = &mut request.options;
    for (key, value) in given(kwargs)? {
        let v = &value;
        match key.as_str() {
            "scene" => {
                if v.is_instance_of::<PyString>() {
                    let name: String = v.extract()?;
                    o.scene = SceneChoice::parse(&name).ok_or_else(|| {
                        PyValueError::new_err(format!(
                            "{function}(): unknown scene '{name}': use {} or mesh:FILE",
                            SceneKind::built_in_names()
                        ))
                    })?;
                } else if v.hasattr("__fspath__")? {
                    o.scene = SceneChoice::Mesh(r.path(&key, v)?);
                } else {
                    arrays.mesh = Some(crate::renderer::mesh_scene(function, v)?);
                    o.scene = SceneChoice::Mesh(PathBuf::from("the scene's Mesh"));
                }
            }
            "height_field" => {
                if is_arrays(v)? {
                    arrays.height_field = Some(arrays::height_field(v).map_err(|e| prefixed(py, function, &key, e))?);
                    o.height_field = Some(HeightSource::File(PathBuf::from("<height_field array>")));
                } else {
                    o.height_field = Some(HeightSource::parse(&r.text(&key, v)?));
                }
            }
            "normal_map" => {
                if is_arrays(v)? {
                    let (levels, format) = match arrays::to_chain(v).map_err(|e| prefixed(py, function, &key, e))? {
                        Chain::Rgba8(c) => {
                            (bumpmap_io::StoredLevels::Rgba8(c.levels), bumpmap_io::texture_file::TextureFormat::Rgba8)
                        }
                        Chain::Rgba16(c) => (
                            bumpmap_io::StoredLevels::Rgba16(c.levels),
                            bumpmap_io::texture_file::TextureFormat::Rgba16,
                        ),
                    };
                    arrays.normal_map = Some(bumpmap_io::StoredTexture { levels, format });
                    o.normal_map = Some(PathBuf::from("<normal_map array>"));
                } else {
                    o.normal_map = Some(r.path(&key, v)?);
                }
            }
            "decal" => {
                if is_arrays(v)? {
                    match arrays::to_chain(v).map_err(|e| prefixed(py, function, &key, e))? {
                        Chain::Rgba8(mut c) if c.levels.len() == 1 => arrays.decal = c.levels.pop(),
                        _ => {
                            return Err(PyTypeError::new_err(format!(
                                "{function}(): decal must be one (H, W, 4) uint8 image (its mipmaps are made from it)"
                            )));
                        }
                    }
                    o.decal = Some(DecalChoice::File(PathBuf::from("<decal array>")));
                } else {
                    o.decal = Some(match r.text(&key, v)?.as_str() {
                        "none" => DecalChoice::None,
                        path => DecalChoice::File(PathBuf::from(path)),
                    });
                }
            }
            "rebuild_mips" => o.rebuild_mips = r.flag(&key, v)?,
            "y_convention" => o.y_convention = r.word(&key, v)?,
            "bump_scale" => o.bump_scale = Some(r.number(&key, v)?),
            "torus_radii" => o.torus_radii = r.numbers::<2>(&key, v)?.into(),
            "tessellation" => {
                let [u, w] = r.numbers::<2>(&key, v)?;
                let whole = |x: f32| x.fract() == 0.0 && x >= 0.0;
                if !(whole(u) && whole(w)) {
                    return Err(r.value_error(&key, format!("takes two whole numbers, got {u}, {w}")));
                }
                o.tessellation = Some((u as usize, w as usize));
            }
            "repeat" => o.repeat = Some(Vec2::from(r.numbers::<2>(&key, v)?)),
            "allow_outside_paths" => o.allow_outside_paths = r.flag(&key, v)?,
            "obj_v" => o.obj_texcoords = r.word(&key, v)?,
            "eye" => o.camera.eye = Some(r.vec3(&key, v)?),
            "target" => o.camera.target = Some(r.vec3(&key, v)?),
            "up" => o.camera.up = Some(r.vec3(&key, v)?),
            "fov" => o.camera.fov_y_degrees = r.number(&key, v)?,
            "viewer" => o.camera.viewer = r.word(&key, v)?,
            "light" => o.lights.lights = r.lights(v)?,
            "attenuation" => o.lights.attenuation = Some(r.attenuation(v)?),
            "spot" => o.lights.spot = Some(r.vec3(&key, v)?),
            "spot_cutoff" => o.lights.spot_cutoff_degrees = r.number(&key, v)?,
            "spot_exponent" => o.lights.spot_exponent = r.number(&key, v)?,
            "spot_pattern" => o.lights.spot_pattern = Some(HeightSource::parse(&r.text(&key, v)?)),
            "ambient" => o.material.ambient = r.number(&key, v)?,
            "diffuse" => o.material.diffuse = r.number(&key, v)?,
            "specular" => o.material.specular = r.number(&key, v)?,
            "shininess" => o.material.shininess = r.number(&key, v)?,
            "gloss" => {
                o.material.gloss = match r.text(&key, v)?.as_str() {
                    "none" => GlossChoice::None,
                    "decal-alpha" => GlossChoice::DecalAlpha,
                    "bricks" => GlossChoice::Bricks,
                    path => GlossChoice::File(PathBuf::from(path)),
                }
            }
            "roughness_map" => o.material.roughness_map = Some(r.path(&key, v)?),
            "roughness_layout" => o.material.roughness_layout = r.word(&key, v)?,
            "technique" => o.technique.technique = r.word::<TechniqueName>(&key, v)?,
            "spp" => o.technique.samples_per_pixel = r.u32(&key, v)?,
            "filter" => o.technique.filter = r.word(&key, v)?,
            "no_self_shadow" => no_self_shadow = r.flag(&key, v)?,
            "precision" => o.technique.precision = r.word(&key, v)?,
            "specular_mode" => o.technique.specular_mode = r.word(&key, v)?,
            "cube_size" => o.technique.cube_size = r.u32(&key, v)?,
            "normalize" => o.technique.normalize = Some(r.word(&key, v)?),
            "self_shadow" => o.technique.self_shadow = r.word(&key, v)?,
            "half_angle" => o.technique.half_angle = r.word(&key, v)?,
            "specular_shadow" => o.technique.specular_shadow = r.word(&key, v)?,
            "specular_filter" => o.technique.specular_filter = r.word(&key, v)?,
            "depth" => o.heights.depth = Some(r.number(&key, v)?),
            "height_map" => o.heights.height_map = Some(r.path(&key, v)?),
            "horizon_map" => o.heights.horizon_map = Some(r.path(&key, v)?),
            "layers" => o.heights.layers = r.u32(&key, v)?,
            "parallax_shadow" => o.heights.parallax_shadow = r.word(&key, v)?,
            "silhouettes" => o.heights.silhouettes = r.flag(&key, v)?,
            "write_depth" => o.heights.write_depth = r.flag(&key, v)?,
            "ambient_occlusion" => o.heights.ambient_occlusion = r.flag(&key, v)?,
            "backend" if with_backend => request.backend = r.word(&key, v)?,
            "size" => size = Some(r.side(&key, v)?),
            "width" => width = Some(r.side(&key, v)?),
            "height" => height = Some(r.side(&key, v)?),
            _ => {
                let taken: Vec<&str> = KEYWORDS.iter().copied().filter(|k| with_backend || *k != "backend").collect();
                return Err(unexpected(function, &key, &taken));
            }
        }
        // A flag set False is a flag not given.
        if !value.is_instance_of::<PyBool>() || value.is_truthy()? {
            present.push(key);
        }
    }
    if no_self_shadow {
        o.technique.self_shadow = SelfShadow::Off;
    }
    needs(function, &present)?;
    request.size = match (size, width, height) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
            return Err(PyValueError::new_err(format!(
                "{function}(): size is a square's side; give it or width and height, not both"
            )));
        }
        (Some(s), None, None) => (s, s),
        (None, Some(w), Some(h)) => (w, h),
        (None, None, None) => request.size,
        (None, _, _) => {
            return Err(PyValueError::new_err(format!("{function}(): width and height are given together")));
        }
    };
    Ok((request, arrays))
}

/// Keywords that mean something only beside another: refused alone, as the command line
/// refuses them, rather than ignored.
fn needs(function: &str, present: &[String]) -> PyResult<()> {
    const NEEDS: [(&str, &str); 7] = [
        ("rebuild_mips", "normal_map"),
        ("y_convention", "normal_map"),
        ("spot_cutoff", "spot"),
        ("spot_exponent", "spot"),
        ("spot_pattern", "spot"),
        ("roughness_layout", "roughness_map"),
        ("height_field", "!normal_map"),
    ];
    let has = |k: &str| present.iter().any(|p| p == k);
    for (key, other) in NEEDS {
        if !has(key) {
            continue;
        }
        match other.strip_prefix('!') {
            Some(conflict) if has(conflict) => {
                return Err(PyValueError::new_err(format!(
                    "{function}(): {key} and {conflict} cannot both be given (each is where the bumps come from)"
                )));
            }
            None if !has(other) => {
                return Err(PyValueError::new_err(format!("{function}(): {key} is given only with {other}")));
            }
            _ => {}
        }
    }
    Ok(())
}

/// Every keyword `render` takes (`prepare` all but `backend`).
pub const KEYWORDS: [&str; 54] = [
    "scene",
    "height_field",
    "normal_map",
    "rebuild_mips",
    "y_convention",
    "bump_scale",
    "decal",
    "torus_radii",
    "tessellation",
    "repeat",
    "allow_outside_paths",
    "obj_v",
    "eye",
    "target",
    "up",
    "fov",
    "viewer",
    "light",
    "attenuation",
    "spot",
    "spot_cutoff",
    "spot_exponent",
    "spot_pattern",
    "ambient",
    "diffuse",
    "specular",
    "shininess",
    "gloss",
    "roughness_map",
    "roughness_layout",
    "technique",
    "spp",
    "filter",
    "no_self_shadow",
    "precision",
    "specular_mode",
    "cube_size",
    "normalize",
    "self_shadow",
    "half_angle",
    "specular_shadow",
    "specular_filter",
    "depth",
    "height_map",
    "horizon_map",
    "layers",
    "parallax_shadow",
    "silhouettes",
    "write_depth",
    "ambient_occlusion",
    "backend",
    "size",
    "width",
    "height",
];
