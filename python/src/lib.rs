//! `bumpmap._bumpmap`: the native half of the `bumpmap` Python package.
//!
//! Every function reads its keywords as typed Python values straight into the library's typed
//! options (`keywords`: `bumpmap::frame::FrameRequest`, `bumpmap_compare::CompareOptions`,
//! `bumpmap::maps::MapOptions`, `TangentOptions`, a `TextureFormat`, `HeightOptions`) and calls
//! the library's functions the command calls too (`bumpmap::frame`, `bumpmap::maps`,
//! `bumpmap_compare`, …), so a script and `bumpmap` make the same bytes from the same options.
//! What the libraries refuse and note is said in `bumpmap_words`' words, which the command line
//! shows too, each flag named as its keyword. The package's `__init__.py` wraps each function
//! with keyword arguments and a docstring made from the options' help texts (`options`).
//!
//! - `keywords`: keywords → typed options;
//! - `options`: every function's option table for the docstrings;
//! - `arrays`: NumPy arrays in and out, their dtype, shape and byte order checked;
//! - `interrupt`: long work with the GIL released, Ctrl-C honoured;
//! - `errors`: the libraries' errors, worded, as Python exceptions;
//! - `pool`: the threads the work runs on, one pool per process (so a forked child works);
//! - `renderer`: `Renderer` and `Scene`, kept between frames, and a `Mesh` given as the scene;
//! - `maps`: heights → the normal map, its chain and the maps written beside it;
//! - `compare`: every technique measured against the reference;
//! - `bake`: a high-poly mesh baked onto a low-poly one's UV layout.
//!
//! What it does not do: any image, mesh or rendering work of its own.

mod arrays;
mod bake;
mod compare;
mod errors;
mod interrupt;
mod keywords;
mod maps;
mod options;
mod pool;
mod renderer;

use std::path::PathBuf;

use bumpmap::maps::Chain;
use bumpmap_io::HeightSource;
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_words::Error;

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::errors::to_py;

/// A height field from an image file or a preset (`bricks@512`), as the command line reads it.
#[pyfunction]
#[pyo3(signature = (path, options = None))]
fn read_height_field<'py>(
    py: Python<'py>,
    path: PathBuf,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let spec = path
        .to_str()
        .ok_or_else(|| PyValueError::new_err(format!("read_height_field(): {} is not UTF-8", path.display())))?
        .to_string();
    let channel = keywords::one_word("read_height_field", bumpmap::option_table::CHANNEL, options)?;
    let field = interrupt::run(py, move |_| HeightSource::parse(&spec).load(channel).map_err(Error::from))?
        .map_err(|e| to_py("read_height_field", e))?;
    arrays::from_height_field(py, &field)
}

/// Writes levels (one (H, W, 4) array or a list, level 0 first) as `normalmap -o PATH` writes a
/// chain; returns the paths written.
#[pyfunction]
#[pyo3(signature = (path, levels, options = None))]
fn write_texture(
    py: Python<'_>,
    path: PathBuf,
    levels: &Bound<'_, PyAny>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Vec<PathBuf>> {
    let asked = keywords::one_word("write_texture", bumpmap::option_table::FORMAT, options)?;
    let chain = arrays::to_chain(levels)?;
    let sixteen = matches!(chain, bumpmap::maps::Chain::Rgba16(_));
    let format = match (asked, sixteen) {
        (TextureFormat::Rgba8 | TextureFormat::Rgba16, true) => TextureFormat::Rgba16,
        (TextureFormat::Rgba16, false) => {
            return Err(PyTypeError::new_err(
                "write_texture(): format rgba16 needs uint16 levels (these are uint8: give format rgba8, or levels.astype(numpy.uint16) * 257)",
            ));
        }
        (f, true) => {
            return Err(PyValueError::new_err(format!(
                "write_texture(): uint16 levels cannot be stored as format {}: BC5 and BC7 hold 8 bits a channel (give uint8 levels)",
                f.dxgi_name()
            )));
        }
        (f, false) => f,
    };
    let written = interrupt::run(py, move |cancel| {
        let mut set = bumpmap_io::atomic::FileSet::new(&[]);
        bumpmap::maps::write_chain_into(&mut set, &path, &chain, format).map_err(bumpmap_words::maps::save_error)?;
        cancel.commit(set)
    })?
    .map_err(|e| to_py("write_texture", e))?;
    Ok(written)
}

/// A texture file read back: its levels as (H, W, 4) arrays (uint8, or uint16 for a 16-bit
/// file), level 0 first — a DDS's or KTX2's own, a PNG's with the `NAME.mipK.png` files beside
/// it — the format it stores them in, and the Y convention its texels show (the curl test
/// `inspect` runs; `None` where it cannot decide). The inverse of `write_texture`.
#[pyfunction]
fn read_texture<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let (texture, convention) = interrupt::run(py, move |_| {
        let texture = bumpmap_io::load_texture_chain(&path)?;
        let convention = bumpmap::inspect::stored_convention(&texture.levels);
        Ok::<_, bumpmap_io::IoError>((texture, convention))
    })?
    .map_err(|e| to_py("read_texture", Error::from(e)))?;
    // By the name `write_texture(format=)` takes.
    let format = bumpmap::Named::name(texture.format);
    let chain = match texture.levels {
        bumpmap_io::StoredLevels::Rgba8(levels) => {
            Chain::Rgba8(bumpmap_math::MipChain { levels, encoding: Default::default() })
        }
        bumpmap_io::StoredLevels::Rgba16(levels) => {
            Chain::Rgba16(bumpmap_math::MipChain { levels, encoding: Default::default() })
        }
    };
    let out = PyDict::new(py);
    out.set_item("levels", PyList::new(py, arrays::from_chain(py, chain)?)?)?;
    out.set_item("format", format)?;
    out.set_item("y_convention", convention.map(bumpmap::Named::name))?;
    Ok(out)
}

/// Tangents for a mesh given as arrays, made as `bumpmap tangents` makes them; returns the mesh
/// out (vertices may be split) as its glTF file has it: normals and tangents unit length (rebuilt
/// where they cannot be), tangents perpendicular to the normals, glTF's `w`.
#[pyfunction]
#[pyo3(signature = (positions, normals, uvs, indices, options = None))]
fn tangents<'py>(
    py: Python<'py>,
    positions: &Bound<'py, PyAny>,
    normals: &Bound<'py, PyAny>,
    uvs: &Bound<'py, PyAny>,
    indices: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let options = keywords::tangent_options("tangents", options)?;
    let (mut mesh, had_normals, _) = arrays::mesh("tangents", positions, normals, uvs, None, indices)?;
    let computed = !had_normals;
    // Checked on the worker's pool too: the check's loops are parallel.
    let (out, report) = interrupt::run(py, move |_| {
        mesh.validate().map_err(|e| PyValueError::new_err(format!("tangents(): {e}")))?;
        if computed {
            mesh.compute_normals();
        }
        bumpmap_math::tangent::generate_tangents(&mesh, &options)
            .map_err(|e| to_py("tangents", bumpmap_words::maps::tangent_error(e)))
    })??;
    // What the command writes into its glTF: unit vectors, tangents perpendicular to the normals.
    let (normals, tangents, repairs) = bumpmap_io::mesh_file::gltf_normals_and_tangents(&out);
    let dict = PyDict::new(py);
    dict.set_item("positions", arrays::from_rows(py, out.positions.iter().map(|v| v.to_array()).collect())?)?;
    dict.set_item("normals", arrays::from_rows(py, normals.iter().map(|v| v.to_array()).collect())?)?;
    dict.set_item("uvs", arrays::from_rows(py, out.texcoords.iter().map(|v| v.to_array()).collect())?)?;
    let gltf = |t: &glam::Vec4| [t.x, t.y, t.z, bumpmap_io::mesh_file::gltf_handedness(t.w)];
    dict.set_item("tangents", arrays::from_rows(py, tangents.iter().map(gltf).collect())?)?;
    let flat: Vec<u32> = out.indices.iter().flatten().copied().collect();
    let indices = numpy::ndarray::Array2::from_shape_vec((out.indices.len(), 3), flat)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    dict.set_item("indices", numpy::IntoPyArray::into_pyarray(indices, py))?;
    let r = PyDict::new(py);
    r.set_item("degenerate_uv", report.degenerate_uv)?;
    r.set_item("degenerate_geometry", report.degenerate_geometry)?;
    // Mirrored as the image is displayed (glTF's w = −1), as `bumpmap tangents` says it.
    r.set_item("mirrored", bumpmap_io::mesh_file::mirrored_as_displayed(&out))?;
    r.set_item("vertices_split", report.vertices_split)?;
    r.set_item("normals_computed", computed)?;
    r.set_item("normals_repaired", repairs.normals)?;
    r.set_item("tangents_repaired", repairs.tangents)?;
    dict.set_item("report", r)?;
    Ok(dict)
}

/// Keyword arguments, and the `progress=` function taken out of them.
pub(crate) type WithProgress<'py> = (Option<Bound<'py, PyDict>>, Option<Bound<'py, PyAny>>);

/// The options without `progress`, and the function it names (None: no reports); anything else
/// callable or None is a `TypeError`.
pub(crate) fn take_progress<'py>(function: &str, options: Option<&Bound<'py, PyDict>>) -> PyResult<WithProgress<'py>> {
    let Some(options) = options else { return Ok((None, None)) };
    let options = options.copy()?;
    let Some(progress) = options.get_item("progress")? else { return Ok((Some(options), None)) };
    options.del_item("progress")?;
    if progress.is_none() {
        return Ok((Some(options), None));
    }
    if !progress.is_callable() {
        return Err(PyTypeError::new_err(format!(
            "{function}(): progress: a function of (done, total) or None, not {}",
            progress.get_type().name()?
        )));
    }
    Ok((Some(options), Some(progress)))
}

/// Renders a scene as `bumpmap render` does; returns an (H, W, 4) uint8 array, alpha 255.
#[pyfunction]
#[pyo3(signature = (options = None))]
fn render<'py>(py: Python<'py>, options: Option<&Bound<'py, PyDict>>) -> PyResult<Bound<'py, PyAny>> {
    let (options, progress) = take_progress("render", options)?;
    let (request, given) = keywords::render_request(py, "render", options.as_ref(), true)?;
    let drawn =
        interrupt::run_reporting(py, move |_, shown| renderer::draw(&request, &given, shown), progress.as_ref())?
            .map_err(|e| to_py("render", e))?;
    renderer::frame_array(py, drawn.image)
}

/// What a normal map is, as `bumpmap inspect --json` says it, as a dict: a file (`source` a
/// path) or an array ((H, W, 3|4) of uint8, uint16 or float32).
#[pyfunction]
fn inspect<'py>(py: Python<'py>, source: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let report = if source.cast::<numpy::PyUntypedArray>().is_ok() {
        let map = arrays::normal_texels(source)?;
        interrupt::run(py, move |_| bumpmap::inspect::inspect_map("array", &map))?
    } else {
        let path: PathBuf = source.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "inspect(): source must be a path or a numpy array, got {}",
                source.get_type().name().map(|n| n.to_string()).unwrap_or_default()
            ))
        })?;
        interrupt::run(py, move |_| bumpmap::inspect::inspect_file(&path))?
            .map_err(|e| to_py("inspect", bumpmap_words::frame::lib_err(e)))?
    };
    py.import("json")?.call_method1("loads", (report.to_json().to_string(),))
}

/// Heights from a normal map ((H, W, 3|4) of uint8, uint16 or float32), as `bumpmap height`
/// makes them: an (H, W) float32 array, mapped onto [0, 1] unless `raw`.
#[pyfunction]
#[pyo3(signature = (normals, options = None))]
fn height_from_normals<'py>(
    py: Python<'py>,
    normals: &Bound<'py, PyAny>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (height_options, raw) = keywords::height_options("height_from_normals", options)?;
    let map = arrays::normal_texels(normals)?;
    let heights = interrupt::run(py, move |_| {
        let level0 = map.levels.first().cloned().ok_or_else(|| Error::Render("the map has no texels".into()))?;
        bumpmap::heights::heights_from_normals(&level0, &height_options).map_err(|e| Error::Render(e.to_string()))
    })?
    .map_err(|e| to_py("height_from_normals", e))?;
    let texels = if raw { heights.texels.clone() } else { heights.normalized() };
    arrays::from_plane(py, heights.height, heights.width, &texels)
}

/// Each option `function` takes: `(keyword, default as the command line writes it or None,
/// help, choices, is a flag)`. The wrappers' docstrings and the tests read it.
#[pyfunction(name = "options")]
fn option_table(function: &str) -> PyResult<Vec<options::OptionRow>> {
    options::FUNCTIONS
        .contains(&function)
        .then(|| options::describe(function))
        .flatten()
        .ok_or_else(|| PyValueError::new_err(format!("no function {function} takes options")))
}

/// Each option `function` takes with its kind (`flag`, `number`, `whole`, `numbers:N`, `word`,
/// `text`, `path`, `lights`, `attenuation`, `list`): what the stubs' types are made from.
#[pyfunction]
fn option_kinds(function: &str) -> PyResult<Vec<(String, String)>> {
    options::FUNCTIONS
        .contains(&function)
        .then(|| options::kinds(function))
        .flatten()
        .ok_or_else(|| PyValueError::new_err(format!("no function {function} takes options")))
}

/// Every keyword `function` reads.
#[pyfunction(name = "keywords")]
fn keyword_names(function: &str) -> PyResult<Vec<String>> {
    keywords::names(function).ok_or_else(|| PyValueError::new_err(format!("{function} reads no keywords")))
}

/// The techniques of the catalogue: `(name, description, what it needs)`.
#[pyfunction]
fn techniques() -> Vec<(String, String, Vec<String>)> {
    bumpmap::TechniqueName::ALL
        .iter()
        .map(|t| {
            (
                t.name().to_string(),
                t.description().to_string(),
                t.requirements().iter().map(|r| r.brief().to_string()).collect(),
            )
        })
        .collect()
}

/// The x86-64 level this build of the native module was compiled for (`x86-64` or `x86-64-v3`).
#[pyfunction]
fn built_for() -> &'static str {
    bumpmap::cpu::built_for().name()
}

/// Whether this processor runs a build for x86-64-v3 (the wheel's faster module).
#[pyfunction]
fn runs_x86_64_v3() -> bool {
    bumpmap::cpu::has(bumpmap::cpu::Level::X86_64V3)
}

/// The native module.
#[pymodule]
fn _bumpmap(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(maps::normal_map, m)?)?;
    m.add_function(wrap_pyfunction!(maps::blend_normals, m)?)?;
    m.add_function(wrap_pyfunction!(maps::mip_chain, m)?)?;
    m.add_function(wrap_pyfunction!(maps::height_mips, m)?)?;
    m.add_function(wrap_pyfunction!(maps::write_heights, m)?)?;
    m.add_function(wrap_pyfunction!(maps::horizon_maps, m)?)?;
    m.add_function(wrap_pyfunction!(maps::roughness_map, m)?)?;
    m.add_function(wrap_pyfunction!(maps::lean_moments, m)?)?;
    m.add_function(wrap_pyfunction!(read_height_field, m)?)?;
    m.add_function(wrap_pyfunction!(write_texture, m)?)?;
    m.add_function(wrap_pyfunction!(read_texture, m)?)?;
    m.add_function(wrap_pyfunction!(tangents, m)?)?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(compare::compare, m)?)?;
    m.add_function(wrap_pyfunction!(bake::bake, m)?)?;
    m.add_function(wrap_pyfunction!(option_table, m)?)?;
    m.add_function(wrap_pyfunction!(option_kinds, m)?)?;
    m.add_function(wrap_pyfunction!(techniques, m)?)?;
    m.add_function(wrap_pyfunction!(keyword_names, m)?)?;
    m.add_function(wrap_pyfunction!(inspect, m)?)?;
    m.add_function(wrap_pyfunction!(height_from_normals, m)?)?;
    m.add_function(wrap_pyfunction!(built_for, m)?)?;
    m.add_function(wrap_pyfunction!(runs_x86_64_v3, m)?)?;
    m.add("BumpmapWarning", m.py().get_type::<errors::BumpmapWarning>())?;
    m.add_class::<renderer::Renderer>()?;
    m.add_class::<renderer::Scene>()?;
    // Files an interrupted call staged, when the interpreter exits before its work ends.
    let abandon = wrap_pyfunction!(interrupt::abandon_all, m)?;
    m.py().import("atexit")?.call_method1("register", (abandon,))?;
    Ok(())
}
