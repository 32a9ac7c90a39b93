//! Heights → the maps `bumpmap normalmap` writes, as arrays: the normal map and its chain, the
//! heights the parallax techniques read, the horizon map with ambient occlusion and bent
//! normals, the roughness map and LEAN's moments; and the heights written as their files. Each reads its keywords as typed values
//! (`keywords::map_request`) and calls the library's function (`bumpmap::maps`), which the
//! command calls too.

use std::path::PathBuf;

use bumpmap::maps::{self, Chain, MapOptions};
use bumpmap_io::atomic::FileSet;
use bumpmap_words::maps::{map_error, outputs_error};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::errors::to_py;
use crate::{arrays, interrupt, keywords, take_progress};

/// `function`'s keywords as the request they make.
fn request(function: &str, options: Option<&Bound<'_, PyDict>>) -> PyResult<MapOptions> {
    keywords::map_request(function, options)
}

/// `normalmap`'s chain for an array of heights: level 0, or every level with `mips`.
fn chain_of<'py>(
    py: Python<'py>,
    function: &str,
    mips: bool,
    heights: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let map = request(function, options)?;
    let field = arrays::height_field(heights)?;
    let chain = interrupt::run(py, move |_| maps::normal_map(&map, mips, &field).map_err(|e| map_error(e, "heights")))?
        .map_err(|e| to_py(function, e))?;
    arrays::from_chain(py, chain)
}

/// Heights → normal map: level 0 as an (H, W, 4) array (uint8, or uint16 with bits=16).
#[pyfunction]
#[pyo3(signature = (heights, options = None))]
pub fn normal_map<'py>(
    py: Python<'py>,
    heights: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(chain_of(py, "normal_map", false, heights, options)?.swap_remove(0))
}

/// Heights → normal map and every smaller level down to 1×1, level 0 first.
#[pyfunction]
#[pyo3(signature = (heights, options = None))]
pub fn mip_chain<'py>(
    py: Python<'py>,
    heights: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyList>> {
    PyList::new(py, chain_of(py, "mip_chain", true, heights, options)?)
}

/// Heights → what the parallax techniques read: the levels (float32 (H, W), level 0 first)
/// and the min–max levels (float32 (H, W, 2): lower, upper bound), as `normalmap --height-out`
/// stores them.
#[pyfunction]
#[pyo3(signature = (heights, options = None))]
pub fn height_mips<'py>(
    py: Python<'py>,
    heights: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<(Bound<'py, PyList>, Bound<'py, PyList>)> {
    let map = request("height_mips", options)?;
    let field = arrays::height_field(heights)?;
    let mips = interrupt::run(py, move |_| {
        let stored = maps::height_mips(&map, &field).map_err(|e| map_error(e, "heights"))?;
        if let Some(clamped) = stored.clamped {
            bumpmap_words::report::warn(format!("heights: {clamped}"));
        }
        Ok(stored.mips)
    })?
    .map_err(|e| to_py("height_mips", e))?;
    let levels: Vec<_> =
        mips.levels().iter().map(|l| arrays::from_plane(py, l.height, l.width, &l.texels)).collect::<PyResult<_>>()?;
    let minmax: Vec<_> = mips
        .minmax()
        .unwrap_or_default()
        .iter()
        .map(|l| arrays::from_pairs(py, l.height, l.width, &l.texels))
        .collect::<PyResult<_>>()?;
    Ok((PyList::new(py, levels)?, PyList::new(py, minmax)?))
}

/// Heights → the files `normalmap --height-out PATH` writes (every level rounded to `bits` and
/// the min–max levels, by PATH's extension), all or none; returns the paths written.
#[pyfunction]
#[pyo3(signature = (path, heights, options = None))]
pub fn write_heights(
    py: Python<'_>,
    path: PathBuf,
    heights: &Bound<'_, PyAny>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Vec<PathBuf>> {
    let map = request("write_heights", options)?;
    let field = arrays::height_field(heights)?;
    let written = interrupt::run(py, move |cancel| {
        let mut set = FileSet::new(&[]);
        let clamped =
            maps::write_heights_into(&mut set, &path, &map, &field).map_err(|e| outputs_error(e, "heights"))?;
        if let Some(clamped) = clamped {
            bumpmap_words::report::warn(format!("heights: {clamped}"));
        }
        cancel.commit(set)
    })?
    .map_err(|e| to_py("write_heights", e))?;
    Ok(written)
}

/// Heights → the horizon map (every level, float32 (H, W, 8): atan(rise)/90° per direction),
/// ambient occlusion (float32 (H, W)) and bent normals (encoded as `normal_map` encodes normals),
/// as `normalmap --horizon-out --ao-out --bent-normals-out` makes them; the rows of level 0 told
/// to a `progress=` function.
#[pyfunction]
#[pyo3(signature = (heights, options = None))]
pub fn horizon_maps<'py>(
    py: Python<'py>,
    heights: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (options, progress) = take_progress("horizon_maps", options)?;
    let request = request("horizon_maps", options.as_ref())?;
    let field = arrays::height_field(heights)?;
    let asked = request;
    let map = interrupt::run_reporting(
        py,
        move |_, report| {
            let rows = |done: usize, total: usize| {
                if let Some(f) = &report {
                    f(done as u64, total as u64);
                }
            };
            maps::horizon_map(&asked, &field, &rows).map_err(|e| map_error(e, "heights"))
        },
        progress.as_ref(),
    )?
    .map_err(|e| to_py("horizon_maps", e))?;
    let depth = request.normals.scale.abs();
    let levels: Vec<_> = map
        .levels()
        .iter()
        .map(|l| arrays::from_plane_channels(py, l.height, l.width, l.texels.as_flattened(), 8))
        .collect::<PyResult<_>>()?;
    let (w, h) = (map.width(), map.height());
    let ao = arrays::from_plane(py, h, w, &map.ambient_occlusion(depth))?;
    let bent = maps::bent_normals(&request, &map);
    let out = PyDict::new(py);
    out.set_item("horizons", PyList::new(py, levels)?)?;
    out.set_item("ambient_occlusion", ao)?;
    out.set_item("bent_normals", arrays::from_chain(py, bent)?.swap_remove(0))?;
    Ok(out)
}

/// Heights → the roughness map, every level (RGBA8 (H, W, 4), level 0 first), as
/// `normalmap --mips --roughness-out` writes it.
#[pyfunction]
#[pyo3(signature = (heights, options = None))]
pub fn roughness_map<'py>(
    py: Python<'py>,
    heights: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyList>> {
    let map = request("roughness_map", options)?;
    let field = arrays::height_field(heights)?;
    let chain = interrupt::run(py, move |_| maps::roughness_map(&map, &field).map_err(|e| map_error(e, "heights")))?
        .map_err(|e| to_py("roughness_map", e))?;
    PyList::new(py, arrays::from_chain(py, Chain::Rgba8(chain))?)
}

/// Heights → LEAN mapping's moments, every level, as the two files of `normalmap --lean-out`
/// hold them: float32 (H, W, 4) levels of (Bx, By, Mxx, Myy) and of (Mxy, J, 0, 0).
#[pyfunction]
#[pyo3(signature = (heights, options = None))]
pub fn lean_moments<'py>(
    py: Python<'py>,
    heights: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<(Bound<'py, PyList>, Bound<'py, PyList>)> {
    let map = request("lean_moments", options)?;
    let field = arrays::height_field(heights)?;
    let planes =
        interrupt::run(py, move |_| maps::lean_moments(&map, &field, None).map_err(|e| map_error(e, "heights")))?
            .map_err(|e| to_py("lean_moments", e))?;
    let [first, second] = planes.map(|levels| {
        levels
            .iter()
            .map(|l| arrays::from_plane_channels(py, l.height, l.width, l.texels.as_flattened(), 4))
            .collect::<PyResult<Vec<_>>>()
    });
    Ok((PyList::new(py, first?)?, PyList::new(py, second?)?))
}

/// A detail normal map laid over a base one, as `bumpmap blend` does (`bumpmap::maps::blend_maps`):
/// both (H, W, 3|4) arrays of uint8, uint16 or float32; returns the result's levels (level 0
/// at the base's size, every level with `mips`), uint8 or uint16. What was converted for mixed
/// inputs is said as a `BumpmapWarning`.
#[pyfunction]
#[pyo3(signature = (base, detail, options = None))]
pub fn blend_normals<'py>(
    py: Python<'py>,
    base: &Bound<'py, PyAny>,
    detail: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyList>> {
    let options = keywords::blend_options("blend_normals", options)?;
    let base = arrays::normal_texels(base).map_err(|e| keywords::prefixed(py, "blend_normals", "base", e))?;
    let detail = arrays::normal_texels(detail).map_err(|e| keywords::prefixed(py, "blend_normals", "detail", e))?;
    let chain = interrupt::run(py, move |_| {
        let blended = maps::blend_maps(&base, &detail, &options).map_err(bumpmap_words::maps::blend_error)?;
        for note in &blended.notes {
            bumpmap_words::report::warn(note.clone());
        }
        maps::blended_chain(&blended, options.mips).map_err(bumpmap_words::maps::blend_error)
    })?
    .map_err(|e| to_py("blend_normals", e))?;
    PyList::new(py, arrays::from_chain(py, chain)?)
}
