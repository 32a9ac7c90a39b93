//! `compare`'s keywords: the library's `CompareOptions`.

use bumpmap::{Named, SceneKind};
use bumpmap_compare::{CompareOptions, Study};
use bumpmap_io::HeightSource;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{Reader, given, unexpected};

/// Every keyword `compare` takes.
pub const COMPARE_KEYWORDS: [&str; 8] =
    ["scene", "height_field", "bump_scale", "size", "spp", "backend", "techniques", "studies"];

/// `compare`'s keywords as the library's options.
pub fn compare_options(function: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<CompareOptions> {
    let r = Reader { function };
    let mut o = CompareOptions::default();
    for (key, value) in given(kwargs)? {
        let v = &value;
        match key.as_str() {
            "scene" => {
                let name = r.text(&key, v)?;
                o.scene = SceneKind::parse(&name).ok_or_else(|| {
                    PyValueError::new_err(format!(
                        "{function}(): unknown scene '{name}': compare takes a built-in surface ({}), because the reference evaluates the exact surface",
                        SceneKind::built_in_names()
                    ))
                })?;
            }
            "height_field" => o.height_field = HeightSource::parse(&r.text(&key, v)?),
            "bump_scale" => o.bump_scale = r.number(&key, v)?,
            "size" => o.size = r.side(&key, v)?,
            "spp" => o.spp = r.u32(&key, v)?,
            "backend" => o.backend = r.word(&key, v)?,
            "techniques" => o.techniques = r.words(&key, v)?,
            "studies" => {
                let words = r.words(&key, v)?;
                o.studies = Study::ALL
                    .into_iter()
                    .filter(|s| words.iter().any(|w| w == "all" || w == s.name()))
                    .filter(|_| !words.iter().any(|w| w == "none"))
                    .collect();
                if let Some(w) =
                    words.iter().find(|w| !(*w == "all" || *w == "none" || <Study as Named>::parse(w).is_some()))
                {
                    let names: Vec<&str> = ["all", "none"].into_iter().chain(Study::ALL.map(Study::name)).collect();
                    return Err(PyValueError::new_err(format!(
                        "{function}(): invalid value '{w}' for studies; possible values: {}",
                        names.join(", ")
                    )));
                }
            }
            _ => return Err(unexpected(function, &key, &COMPARE_KEYWORDS)),
        }
    }
    Ok(o)
}
