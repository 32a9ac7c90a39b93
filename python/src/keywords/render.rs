//! `render`'s and `Renderer.prepare`'s keywords: the scene's options, the frame's size and the
//! backend (the library's option table), with the arrays given in place of files.

use std::path::PathBuf;

use bumpmap::frame::FrameRequest;
use bumpmap::maps::Chain;
use bumpmap::option_table::{self, Value};
use bumpmap::options::Given;
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_io::{StoredLevels, StoredTexture};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};

use super::read_table;
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
pub(crate) fn prefixed(py: Python<'_>, function: &str, name: &str, e: PyErr) -> PyErr {
    let message = format!("{function}(): {name}: {}", e.value(py));
    if e.is_instance_of::<PyTypeError>(py) { PyTypeError::new_err(message) } else { PyValueError::new_err(message) }
}

/// `render`'s keywords (`backend` included where `with_backend`) as the request they make and
/// the arrays given in place of files. Each keyword is a row of the library's option table
/// (`bumpmap::option_table::render`): read as the row's kind, checked and set by the row, in
/// the table's order, after the options given together are checked.
pub fn render_request(
    py: Python<'_>,
    function: &str,
    kwargs: Option<&Bound<'_, PyDict>>,
    with_backend: bool,
) -> PyResult<(FrameRequest, Given)> {
    let mut request = FrameRequest::default();
    let mut arrays = Given::default();
    let taken = keywords(with_backend);
    let mut special = |key: &str, v: &Bound<'_, PyAny>| -> PyResult<Option<Value>> {
        Ok(Some(match key {
            "scene" if !v.is_instance_of::<PyString>() && !v.hasattr("__fspath__")? => {
                arrays.mesh = Some(crate::renderer::mesh_object(
                    function,
                    ("scene", "a built-in scene's name, \"mesh:FILE\""),
                    v,
                )?);
                Value::Text("mesh:the scene's Mesh".into())
            }
            "height_field" if is_arrays(v)? => {
                arrays.height_field = Some(arrays::height_field(v).map_err(|e| prefixed(py, function, key, e))?);
                Value::Text("<height_field array>".into())
            }
            "normal_map" | "detail_map" if is_arrays(v)? => {
                let (levels, format) = match arrays::to_chain(v).map_err(|e| prefixed(py, function, key, e))? {
                    Chain::Rgba8(c) => (StoredLevels::Rgba8(c.levels), TextureFormat::Rgba8),
                    Chain::Rgba16(c) => (StoredLevels::Rgba16(c.levels), TextureFormat::Rgba16),
                };
                let texture = Some(StoredTexture { levels, format });
                match key {
                    "normal_map" => arrays.normal_map = texture,
                    _ => arrays.detail_map = texture,
                }
                Value::Path(PathBuf::from(format!("<{key} array>")))
            }
            "decal" if is_arrays(v)? => {
                match arrays::to_chain(v).map_err(|e| prefixed(py, function, key, e))? {
                    Chain::Rgba8(mut c) if c.levels.len() == 1 => arrays.decal = c.levels.pop(),
                    _ => {
                        return Err(PyTypeError::new_err(format!(
                            "{function}(): decal must be one (H, W, 4) uint8 image (its mipmaps are made from it)"
                        )));
                    }
                }
                Value::Text("<decal array>".into())
            }
            _ => return Ok(None),
        }))
    };
    read_table(function, &[option_table::SCENE, option_table::FRAME], &taken, kwargs, &mut request, &mut special)?;
    Ok((request, arrays))
}

/// Every keyword `render` takes (`prepare` all but `backend`).
pub fn keywords(with_backend: bool) -> Vec<String> {
    option_table::render().filter(|o| with_backend || o.name != "backend").map(|o| o.keyword()).collect()
}
