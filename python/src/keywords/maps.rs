//! The map functions' keywords (`normal_map`, `mip_chain`, `height_mips`, `horizon_maps`,
//! `roughness_map`, `lean_moments`): how heights become normals and what else is made, as the
//! library's `MapOptions`; `read_height_field`'s channel; `tangents`' algorithm and split angle;
//! and how `height_from_normals` integrates slopes, as the library's `HeightOptions`.

use bumpmap::Named;
use bumpmap::heights::{HeightChoiceError, HeightMethod, HeightOptions};
use bumpmap::maps::MapOptions;
use bumpmap_math::tangent::TangentOptions;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{Reader, given, unexpected};

/// The keywords `function` takes, and the options they make from the library's defaults.
pub fn map_request(function: &str, taken: &[&str], kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<MapOptions> {
    let r = Reader { function };
    let mut m = MapOptions::default();
    for (key, value) in given(kwargs)? {
        if !taken.contains(&key.as_str()) {
            return Err(unexpected(function, &key, taken));
        }
        let v = &value;
        match key.as_str() {
            "scale" => m.normals.scale = r.number(&key, v)?,
            "kernel" => m.normals.kernel = r.word(&key, v)?,
            "wrap" => m.normals.wrap = r.word(&key, v)?,
            "encoding" => m.normals.encoding = r.word(&key, v)?,
            "y_convention" => m.normals.y_convention = r.word(&key, v)?,
            "bits" => {
                let bits = r.count(&key, v)?;
                if !matches!(bits, 8 | 16) {
                    return Err(r.value_error(&key, format!("{bits} is not 8 or 16")));
                }
                m.bits = bits as u8;
            }
            "mip_mode" => m.mip_mode = r.word(&key, v)?,
            "roughness" => m.roughness = r.number(&key, v)?,
            "roughness_layout" => m.roughness_layout = r.word(&key, v)?,
            _ => unreachable!("every keyword a map function takes is read here: {key}"),
        }
    }
    Ok(m)
}

/// Every keyword `tangents` takes.
pub const TANGENT_KEYWORDS: [&str; 2] = ["mode", "split_angle"];

/// `tangents`' keywords as the library's options.
pub fn tangent_options(function: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<TangentOptions> {
    let r = Reader { function };
    let mut o = TangentOptions::default();
    for (key, value) in given(kwargs)? {
        match key.as_str() {
            "mode" => o.mode = r.word(&key, &value)?,
            "split_angle" => o.split_angle_degrees = r.number(&key, &value)?,
            _ => return Err(unexpected(function, &key, &TANGENT_KEYWORDS)),
        }
    }
    Ok(o)
}

/// Every keyword `height_from_normals` takes.
pub const HEIGHT_KEYWORDS: [&str; 5] = ["method", "kernel", "scale", "y_convention", "raw"];

/// `height_from_normals`' keywords as the library's options, and whether the heights are
/// wanted as they are (`raw`) rather than mapped onto [0, 1].
pub fn height_options(function: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<(HeightOptions, bool)> {
    let r = Reader { function };
    let (mut method, mut derivative, mut y_convention, mut scale, mut raw) =
        (HeightMethod::Auto, None, None, 1.0, false);
    for (key, value) in given(kwargs)? {
        let v = &value;
        match key.as_str() {
            "method" => method = r.word(&key, v)?,
            "kernel" => derivative = r.word_or_auto(&key, v)?,
            "y_convention" => y_convention = r.word_or_auto(&key, v)?,
            "scale" => scale = r.number(&key, v)?,
            "raw" => raw = r.flag(&key, v)?,
            _ => return Err(unexpected(function, &key, &HEIGHT_KEYWORDS)),
        }
    }
    let options = HeightOptions::from_choices(method, derivative, y_convention, scale).map_err(|e| match e {
        HeightChoiceError::Scale(e) => r.value_error("scale", e),
        HeightChoiceError::KernelUnnamed => r.value_error(
            "method",
            "'kernel' undoes a named kernel: pass kernel= the map's (method='fft' fits one itself)",
        ),
    })?;
    Ok((options, raw))
}

/// The one keyword `key` of a function that takes only it, a word of `T`, or `default` when it
/// is not given (`read_height_field`'s channel, `write_texture`'s format).
pub fn one_word<T: Named>(function: &str, key: &str, default: T, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<T> {
    let r = Reader { function };
    let mut word = default;
    for (given_key, value) in given(kwargs)? {
        if given_key != key {
            return Err(unexpected(function, &given_key, &[key]));
        }
        word = r.word(key, &value)?;
    }
    Ok(word)
}

/// How heights become normals: what every map function takes.
const NORMALS: [&str; 5] = ["scale", "kernel", "wrap", "encoding", "y_convention"];

/// The keywords each map function takes.
pub fn map_keywords(function: &str) -> Option<Vec<&'static str>> {
    let extra: &[&'static str] = match function {
        "normal_map" | "horizon_maps" => &["bits"],
        "mip_chain" => &["bits", "mip_mode"],
        "height_mips" => return Some(vec!["bits"]),
        "roughness_map" => &["roughness", "roughness_layout"],
        "lean_moments" => &[],
        "read_height_field" => return Some(vec!["channel"]),
        _ => return None,
    };
    Some(NORMALS.iter().chain(extra).copied().collect())
}
