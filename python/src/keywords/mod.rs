//! Keywords as typed values: each keyword's Python value — a number, a tuple for a vector, a word
//! of a closed set, a path, an array — set straight into the field of the options it stands for
//! (the library's [`SceneOptions`](bumpmap::options::SceneOptions) with the frame's size and
//! backend, [`CompareOptions`](bumpmap_compare::CompareOptions), `TangentOptions`, a
//! `TextureFormat`, the maps' `MapOptions`). No text is put together for a command line: the
//! words of closed sets are the library's ([`Named`]), the ranges are checked by the library, and
//! the defaults are its own.
//!
//! - `render`: `render`'s and `Renderer.prepare`'s keywords → a `Request` and its arrays;
//! - `compare`: `compare`'s keywords → `CompareOptions`;
//! - `maps`: the map functions' keywords → `MapOptions`; `tangents`', `write_texture`'s and
//!   `height_from_normals`' (→ the library's `HeightOptions`).
//!
//! What it does not do: document the keywords (the docstrings read the command's help, which
//! reads the same library names), or set anything up (`bumpmap::options`).

mod maps;
mod render;

pub use maps::{
    bake_request, blend_options, compare_options, height_options, map_keywords, map_request, one_word, tangent_options,
};
pub(crate) use render::prefixed;
pub use render::render_request;

use std::path::PathBuf;

use bumpmap::option_table::{self, Kind, Opt, Together, Value, check_together};
use bumpmap::{Attenuation, SceneLight};
use glam::Vec3;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyString, PyTuple};

/// Every keyword `function` reads, or `None` for a function that reads none: the keywords of
/// its option table's rows (the map functions each a part of the maps' table).
pub fn names(function: &str) -> Option<Vec<String>> {
    fn of<R>(rows: &[Opt<R>]) -> Vec<String> {
        rows.iter().map(Opt::keyword).collect()
    }
    match function {
        "render" => Some(render::keywords(true)),
        "compare" => Some(of(bumpmap_compare::option_table::COMPARE)),
        "tangents" => Some(of(option_table::TANGENTS)),
        "bake" => Some(of(option_table::BAKE)),
        "blend_normals" => Some(of(option_table::BLEND)),
        "height_from_normals" => Some(of(option_table::HEIGHTS)),
        "write_texture" => Some(of(option_table::FORMAT)),
        "read_height_field" => Some(of(option_table::CHANNEL)),
        f => map_keywords(f).map(|k| k.iter().map(|k| k.to_string()).collect()),
    }
}

/// Reads a keyword's value where the option's kind does not (`Ok(None)`: read it as the kind).
pub(super) type Special<'a> = dyn FnMut(&str, &Bound<'_, PyAny>) -> PyResult<Option<Value>> + 'a;

/// Reads `function`'s keywords into `target` through the rows of `tables` that `taken` lists:
/// each value read as its row's kind (or by `special`, for what a row's kind does not cover,
/// such as arrays in place of files), the options given together checked, then each set by its
/// row in the tables' order.
pub(super) fn read_table<R: Default + 'static>(
    function: &str,
    tables: &[&'static [Opt<R>]],
    taken: &[String],
    kwargs: Option<&Bound<'_, PyDict>>,
    target: &mut R,
    special: &mut Special<'_>,
) -> PyResult<()> {
    let r = Reader { function };
    let mut values: Vec<(&'static Opt<R>, String, Value)> = Vec::new();
    for (key, value) in given(kwargs)? {
        let row = tables.iter().flat_map(|t| t.iter()).find(|o| o.keyword() == key && taken.contains(&key));
        let Some(row) = row else {
            return Err(unexpected(function, &key, &taken.iter().map(String::as_str).collect::<Vec<_>>()));
        };
        let read = match special(&key, &value)? {
            Some(read) => read,
            None => r.value(&key, &row.kind(), &value)?,
        };
        // A flag set False is a flag not given.
        if read != Value::Flag(false) {
            values.push((row, key, read));
        }
    }
    let present: Vec<&str> = values.iter().map(|(row, _, _)| row.name).collect();
    for table in tables {
        check_together(table, &present).map_err(|e| together(function, e))?;
    }
    for row in tables.iter().flat_map(|t| t.iter()) {
        for (_, key, value) in values.iter().filter(|(given, _, _)| std::ptr::eq(*given, row)) {
            row.set(target, value.clone()).map_err(|e| r.value_error(key, e))?;
        }
    }
    Ok(())
}

/// Options given together that cannot be, in keywords.
fn together(function: &str, e: Together) -> PyErr {
    let k = |name: &str| name.replace('-', "_");
    PyValueError::new_err(match e {
        Together::Needs { option, needs } => format!("{function}(): {} is given only with {}", k(option), k(needs)),
        Together::Excludes { option, other } => {
            format!("{function}(): {} and {} cannot both be given", k(option), k(other))
        }
    })
}

/// The most lights one keyword reads from a sequence or iterator: past the 64 a scene takes,
/// and a bound on an iterator that never ends.
pub(super) const MAX_VALUES: usize = 4096;

/// One call's keywords, read: the function's name for messages.
pub(super) struct Reader<'a> {
    pub(super) function: &'a str,
}

impl Reader<'_> {
    pub(super) fn type_error(&self, key: &str, wants: &str, value: &Bound<'_, PyAny>) -> PyErr {
        let kind = value.get_type().name().map(|n| n.to_string()).unwrap_or_default();
        PyTypeError::new_err(format!("{}(): {key} takes {wants}, got {kind}", self.function))
    }

    pub(super) fn value_error(&self, key: &str, message: impl std::fmt::Display) -> PyErr {
        PyValueError::new_err(format!("{}(): {key}: {message}", self.function))
    }

    /// True or False, nothing else.
    pub(super) fn flag(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<bool> {
        match value.cast::<PyBool>() {
            Ok(b) => Ok(b.is_true()),
            Err(_) => Err(PyTypeError::new_err(format!(
                "{}(): {key} is True or False, got {}",
                self.function,
                value.get_type().name()?
            ))),
        }
    }

    /// A real number (an int, a float or a NumPy scalar; not a bool or a string).
    pub(super) fn number(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<f32> {
        if value.is_instance_of::<PyBool>() || value.is_instance_of::<PyString>() || value.hasattr("__len__")? {
            return Err(self.type_error(key, "a number", value));
        }
        let v: f64 = value.extract().map_err(|_| self.type_error(key, "a number", value))?;
        if v.is_finite() && v.abs() > f32::MAX as f64 {
            return Err(self.value_error(key, format!("{v} is beyond single precision (about ±3.4e38)")));
        }
        Ok(v as f32)
    }

    /// A whole number, not negative (an int or a NumPy integer; not a float or a bool).
    pub(super) fn count(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<u64> {
        if value.is_instance_of::<PyBool>() || value.is_instance_of::<PyFloat>() || !value.hasattr("__index__")? {
            return Err(self.type_error(key, "a whole number", value));
        }
        let v: i128 = value.extract().map_err(|_| self.type_error(key, "a whole number", value))?;
        u64::try_from(v).map_err(|_| self.value_error(key, format!("{v} is not a count (0 or more)")))
    }

    /// `N` numbers: a tuple, a list or an array of them.
    pub(super) fn numbers<const N: usize>(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<[f32; N]> {
        let wants = format!("{N} numbers (a tuple)");
        if value.is_instance_of::<PyString>() || !value.hasattr("__len__")? {
            return Err(self.type_error(key, &wants, value));
        }
        if value.len()? != N {
            return Err(self.value_error(key, format!("takes {N} numbers, got {}", value.len()?)));
        }
        let mut out = [0.0; N];
        for (slot, item) in out.iter_mut().zip(value.try_iter()?) {
            *slot = self.number(key, &item?)?;
        }
        Ok(out)
    }

    pub(super) fn vec3(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec3> {
        self.numbers::<3>(key, value).map(Vec3::from)
    }

    /// A string or a path (`os.PathLike`).
    pub(super) fn text(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
        if let Ok(s) = value.cast::<PyString>() {
            return s.extract();
        }
        if value.hasattr("__fspath__")? {
            let path = value.py().import("os")?.call_method1("fspath", (value,))?;
            return path.extract().map_err(|_| self.type_error(key, "a str path", value));
        }
        Err(self.type_error(key, "a string or a path", value))
    }

    pub(super) fn path(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
        self.text(key, value).map(PathBuf::from)
    }

    /// One light: `"[dir:]X,Y,Z[@R,G,B]"`, a position `(x, y, z)` (white), or a dict with
    /// `position` or `direction` and, optionally, `color`.
    pub(super) fn light(&self, value: &Bound<'_, PyAny>) -> PyResult<SceneLight> {
        let key = "light";
        if let Ok(s) = value.cast::<PyString>() {
            return SceneLight::parse(&s.extract::<String>()?).map_err(|e| self.value_error(key, e));
        }
        if let Ok(d) = value.cast::<PyDict>() {
            let color = match d.get_item("color")? {
                Some(c) => self.vec3("light's color", &c)?,
                None => Vec3::ONE,
            };
            let light = match (d.get_item("position")?, d.get_item("direction")?) {
                (Some(p), None) => SceneLight::positional(self.vec3("light's position", &p)?, color),
                (None, Some(dir)) => SceneLight::directional(self.vec3("light's direction", &dir)?, color),
                _ => {
                    return Err(self.value_error(
                        key,
                        "a light as a dict has a \"position\" or a \"direction\" (and may have a \"color\")",
                    ));
                }
            };
            return light.map_err(|e| self.value_error(key, e));
        }
        let at = self.vec3(key, value).map_err(|_| {
            self.type_error(key, "a light (\"[dir:]X,Y,Z[@R,G,B]\", (x, y, z) or a dict) or a list of them", value)
        })?;
        SceneLight::positional(at, Vec3::ONE).map_err(|e| self.value_error(key, e))
    }

    /// One light or a list (or iterable) of them.
    pub(super) fn lights(&self, value: &Bound<'_, PyAny>) -> PyResult<Vec<SceneLight>> {
        let one = value.is_instance_of::<PyString>() || value.is_instance_of::<PyDict>() || self.all_numbers(value)?;
        if one {
            return Ok(vec![self.light(value)?]);
        }
        let items = value.try_iter().map_err(|_| self.type_error("light", "a light or a list of them", value))?;
        let mut lights = Vec::new();
        for item in items {
            // An iterator may never end: read no further than any scene could use.
            if lights.len() == MAX_VALUES {
                return Err(PyValueError::new_err(format!(
                    "{}(): light takes at most {MAX_VALUES} values; this one gave more (an endless iterator?)",
                    self.function
                )));
            }
            lights.push(self.light(&item?)?);
        }
        Ok(lights)
    }

    /// A tuple, list or array whose items are all numbers.
    pub(super) fn all_numbers(&self, value: &Bound<'_, PyAny>) -> PyResult<bool> {
        if !(value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() || value.hasattr("__array__")?) {
            return Ok(false);
        }
        for item in value.try_iter()? {
            let item = item?;
            if item.is_instance_of::<PyString>() || !item.hasattr("__float__")? || item.hasattr("__len__")? {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// `"none"`, `"C,L,Q"`, `"exp:D"`, `"exp2:D"`, or `(C, L, Q)`.
    pub(super) fn attenuation(&self, value: &Bound<'_, PyAny>) -> PyResult<Attenuation> {
        if let Ok(s) = value.cast::<PyString>() {
            return Attenuation::parse(&s.extract::<String>()?).map_err(|e| self.value_error("attenuation", e));
        }
        let [constant, linear, quadratic] = self.numbers::<3>("attenuation", value)?;
        Ok(Attenuation::Polynomial { constant, linear, quadratic })
    }
}

impl Reader<'_> {
    /// A value of the option table's `kind`: True or False, a number, a whole number, a tuple of
    /// numbers, a word of the set, a string or path, lights, an attenuation.
    pub(super) fn value(&self, key: &str, kind: &Kind, value: &Bound<'_, PyAny>) -> PyResult<Value> {
        Ok(match kind {
            Kind::Flag => Value::Flag(self.flag(key, value)?),
            Kind::Number => Value::Number(self.number(key, value)?),
            Kind::Whole { .. } => Value::Whole(self.count(key, value)?),
            Kind::Numbers(2) => Value::Numbers(self.numbers::<2>(key, value)?.to_vec()),
            // Every other count the tables use is three (a vector).
            Kind::Numbers(_) => Value::Numbers(self.numbers::<3>(key, value)?.to_vec()),
            Kind::Word(choices) => {
                let word: String =
                    value.cast::<PyString>().map_err(|_| self.type_error(key, "a string", value))?.extract()?;
                if !choices.iter().any(|c| c.name == word || c.aliases.contains(&word.as_str())) {
                    let names: Vec<&str> = choices.iter().map(|c| c.name).collect();
                    return Err(PyValueError::new_err(format!(
                        "{}(): invalid value '{word}' for {key}; possible values: {}",
                        self.function,
                        names.join(", ")
                    )));
                }
                Value::Word(word)
            }
            Kind::Text => Value::Text(self.text(key, value)?),
            Kind::Path => Value::Path(self.path(key, value)?),
            Kind::Lights => Value::Lights(self.lights(value)?),
            Kind::Attenuation => Value::Attenuation(self.attenuation(value)?),
            Kind::List(choices) => {
                let words = self.words(key, value)?;
                if let Some(choices) = choices
                    && let Some(w) = words.iter().find(|w| !choices.iter().any(|c| c.name == *w))
                {
                    let names: Vec<&str> = choices.iter().map(|c| c.name).collect();
                    return Err(PyValueError::new_err(format!(
                        "{}(): invalid value '{w}' for {key}; possible values: {}",
                        self.function,
                        names.join(", ")
                    )));
                }
                Value::Words(words)
            }
        })
    }

    /// Words: one string (comma-separated, as the command line takes them) or a list of them.
    pub(super) fn words(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
        if let Ok(s) = value.cast::<PyString>() {
            return Ok(s.extract::<String>()?.split(',').map(|w| w.trim().to_string()).collect());
        }
        let items = value.try_iter().map_err(|_| self.type_error(key, "a string or a list of strings", value))?;
        let mut out = Vec::new();
        for item in items {
            if out.len() == MAX_VALUES {
                return Err(self.value_error(key, format!("takes at most {MAX_VALUES} values")));
            }
            let item = item?;
            let word = item.cast::<PyString>().map_err(|_| self.type_error(key, "strings", &item))?;
            out.push(word.extract()?);
        }
        Ok(out)
    }
}

/// The keywords given, each with its value, but those given as None (a default asked for).
fn given<'py>(kwargs: Option<&Bound<'py, PyDict>>) -> PyResult<Vec<(String, Bound<'py, PyAny>)>> {
    let Some(kwargs) = kwargs else { return Ok(Vec::new()) };
    let mut out = Vec::new();
    for (key, value) in kwargs.iter() {
        let key: String = key.extract().map_err(|_| PyTypeError::new_err("option names must be strings"))?;
        if !value.is_none() {
            out.push((key, value));
        }
    }
    Ok(out)
}

/// A keyword `function` does not take, and the ones it does.
fn unexpected(function: &str, key: &str, taken: &[&str]) -> PyErr {
    let mut names = taken.to_vec();
    names.sort();
    PyTypeError::new_err(format!(
        "{function}() got an unexpected keyword argument '{key}' (it takes: {})",
        names.join(", ")
    ))
}
