//! `bake()`: a high-poly mesh's normals baked onto a low-poly mesh's UV layout, as `bumpmap
//! bake` bakes them (`bumpmap::bake`), returned as arrays; its rows told to a `progress=`
//! function.
//!
//! What it does not do: bake or write anything itself.

use std::path::PathBuf;

use bumpmap::bake::{BakeFileError, BakeRequest, bake_from_meshes, tangent_chain};
use bumpmap_io::LoadedMesh;
use bumpmap_words::Error;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::errors::to_py;
use crate::{arrays, interrupt, keywords, take_progress};

/// Bakes `high` onto `low` (mesh files or `bumpmap.Mesh` objects); returns the normal map's levels, the object-space
/// normals, the displacement, HIGH's curvature and which texels were hit.
#[pyfunction]
#[pyo3(signature = (high, low, options = None))]
pub fn bake<'py>(
    py: Python<'py>,
    high: &Bound<'py, PyAny>,
    low: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (options, progress) = take_progress("bake", options)?;
    let mut request: BakeRequest = keywords::bake_request("bake", options.as_ref())?;
    // Python gets every map the bake makes.
    request.options.curvature = true;
    let (high, high_mesh) = mesh_or_file(high, "high", "<high Mesh>")?;
    let (low, low_mesh) = mesh_or_file(low, "low", "<low Mesh>")?;
    let (baked, chain) = interrupt::run_reporting(
        py,
        move |_, report| {
            // A Mesh given as arrays is the caller's value, not a file: ValueError, not OSError.
            let err = |e| match bumpmap_words::bake::bake_error(e, &high, &low) {
                Error::Path { path, reason } if path.to_string_lossy().starts_with('<') => {
                    Error::Render(format!("{}: {reason}", path.display()))
                }
                other => other,
            };
            let rows = |done: usize, total: usize| {
                if let Some(f) = &report {
                    f(done as u64, total as u64);
                }
            };
            let read = |path: &PathBuf, given: Option<LoadedMesh>| match given {
                Some(mesh) => Ok(mesh),
                None => bumpmap_io::load_mesh(path).map_err(BakeFileError::from),
            };
            let meshes = read(&high, high_mesh).and_then(|h| Ok((h, read(&low, low_mesh)?)));
            let done = meshes.and_then(|(h, l)| bake_from_meshes(h, (l, &low), &request, &rows)).map_err(err)?;
            let chain = tangent_chain(&done.baked, &request).map_err(err)?;
            Ok::<_, Error>((done.baked, chain))
        },
        progress.as_ref(),
    )?
    .map_err(|e| to_py("bake", e))?;
    let (w, h) = (baked.width, baked.height);
    let out = PyDict::new(py);
    out.set_item("levels", PyList::new(py, arrays::from_chain(py, chain)?)?)?;
    let object: Vec<[f32; 3]> = baked.object.iter().map(|n| n.to_array()).collect();
    out.set_item("object_space", arrays::from_rows(py, object)?.call_method1("reshape", (h, w, 3))?)?;
    out.set_item("displacement", arrays::from_plane(py, h, w, &baked.displacement)?)?;
    out.set_item("curvature", arrays::from_plane(py, h, w, &baked.curvature)?)?;
    if !baked.occlusion.is_empty() {
        out.set_item("occlusion", arrays::from_plane(py, h, w, &baked.occlusion)?)?;
    }
    let flags = |v: &[bool]| -> PyResult<Bound<'py, PyAny>> {
        let ones: Vec<f32> = v.iter().map(|&b| b as u8 as f32).collect();
        arrays::from_plane(py, h, w, &ones)?.call_method1("astype", ("bool",))
    };
    out.set_item("hit", flags(&baked.hit)?)?;
    out.set_item("covered", flags(&baked.covered)?)?;
    Ok(out)
}

/// `given` as a mesh file's path, or as the mesh a `bumpmap.Mesh` holds (named `stand_in` in
/// messages).
fn mesh_or_file(given: &Bound<'_, PyAny>, keyword: &str, stand_in: &str) -> PyResult<(PathBuf, Option<LoadedMesh>)> {
    if given.is_instance_of::<pyo3::types::PyString>() || given.hasattr("__fspath__")? {
        return Ok((given.extract()?, None));
    }
    let mesh = crate::renderer::mesh_object("bake", (keyword, "a mesh file's path"), given)?;
    Ok((PathBuf::from(stand_in), Some(mesh)))
}
