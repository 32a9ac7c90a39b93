//! The keywords of the functions whose options are one library table each: the map functions
//! (`normal_map`, `mip_chain`, `height_mips`, `write_heights`, `horizon_maps`, `roughness_map`,
//! `lean_moments`: parts of the maps' table, as the library's `MapOptions`), `read_height_field`'s
//! channel, `write_texture`'s format, `tangents`' algorithm and split angle, how
//! `height_from_normals` integrates slopes (the library's `HeightChoices`), and `compare`'s
//! `CompareOptions`.

use bumpmap::heights::{HeightChoiceError, HeightChoices, HeightOptions};
use bumpmap::maps::MapOptions;
use bumpmap::option_table::{self, Opt};
use bumpmap_compare::CompareOptions;
use bumpmap_math::tangent::TangentOptions;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{Reader, names, read_table};

/// `function`'s keywords read through `rows` into their typed options, from the library's
/// defaults.
fn read<R: Default + 'static>(
    function: &str,
    rows: &'static [Opt<R>],
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<R> {
    let mut out = R::default();
    let taken = names(function).unwrap_or_else(|| rows.iter().map(Opt::keyword).collect());
    read_table(function, &[rows], &taken, kwargs, &mut out, &mut |_, _| Ok(None))?;
    Ok(out)
}

/// A map function's keywords (those [`map_keywords`] lists) as the maps' options.
pub fn map_request(function: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<MapOptions> {
    read(function, option_table::MAPS, kwargs)
}

/// `tangents`' keywords as the library's options.
pub fn tangent_options(function: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<TangentOptions> {
    read(function, option_table::TANGENTS, kwargs)
}

/// `bake`'s keywords as the library's request.
pub fn bake_request(function: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<bumpmap::bake::BakeRequest> {
    read(function, option_table::BAKE, kwargs)
}

/// `blend_normals`' keywords as the library's options.
pub fn blend_options(function: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<bumpmap::maps::BlendOptions> {
    read(function, option_table::BLEND, kwargs)
}

/// `compare`'s keywords as the library's options.
pub fn compare_options(function: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<CompareOptions> {
    read(function, bumpmap_compare::option_table::COMPARE, kwargs)
}

/// `height_from_normals`' keywords as the library's options, and whether the heights are
/// wanted as they are (`raw`) rather than mapped onto [0, 1].
pub fn height_options(function: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<(HeightOptions, bool)> {
    let choices: HeightChoices = read(function, option_table::HEIGHTS, kwargs)?;
    let r = Reader { function };
    let options = choices.options().map_err(|e| match e {
        HeightChoiceError::Scale(e) => r.value_error("scale", e),
        HeightChoiceError::KernelUnnamed => r.value_error(
            "method",
            "'kernel' undoes a named kernel: pass kernel= the map's (method='fft' fits one itself)",
        ),
        HeightChoiceError::KernelSpectral => r.value_error(
            "method",
            "'kernel' undoes a finite-difference kernel, and kernel='spectral' is none: use method='fft' for the spectral derivative",
        ),
    })?;
    Ok((options, choices.raw))
}

/// The one keyword of `read_height_field` (the channel) or `write_texture` (the format), read
/// through its one-row table.
pub fn one_word<T: Default + 'static>(
    function: &str,
    rows: &'static [Opt<T>],
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<T> {
    read(function, rows, kwargs)
}

/// How heights become normals: what every map function takes.
const NORMALS: [&str; 5] = ["scale", "kernel", "wrap", "encoding", "y_convention"];

/// The keywords each map function takes: the rows of the maps' table it reads.
pub fn map_keywords(function: &str) -> Option<Vec<&'static str>> {
    let extra: &[&'static str] = match function {
        "normal_map" | "horizon_maps" => &["bits"],
        "mip_chain" => &["bits", "mip_mode"],
        "height_mips" | "write_heights" => return Some(vec!["bits"]),
        "roughness_map" => &["roughness", "roughness_layout"],
        "lean_moments" => &[],
        _ => return None,
    };
    Some(NORMALS.iter().chain(extra).copied().collect())
}
