//! Every function's option table — help texts, defaults, choices, read from the command's own
//! definition — which the docstrings, signatures and stubs are made from; and, for
//! `height_from_normals` alone (every other function reads typed keywords: `keywords`), its
//! keyword arguments as the command line's options: `scale=8` becomes `--scale=8`, parsed by the
//! command's clap definition, its messages put in Python's words (`bump_scale`, not
//! `--bump-scale`).
//!
//! What it does not do: decide any default or range itself; those live in `bumpmap_cli::args`.

use bumpmap_cli::args::{Cli, Command};
use clap::error::ErrorKind;
use clap::{Arg, ArgAction, CommandFactory, Parser};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// One option as the docstrings show it: `(keyword, default as the command line writes it,
/// help, choices, is a flag)`.
pub type OptionRow = (String, Option<String>, String, Vec<String>, bool);

/// Which of a command's options a function takes.
enum Taken {
    /// These long names.
    Only(&'static [&'static str]),
    /// All but these long names.
    AllBut(&'static [&'static str]),
}

/// A Python function and the command whose options it takes.
pub struct Function {
    /// The Python name.
    pub name: &'static str,
    /// The subcommand.
    command: &'static str,
    /// Its options the function takes as keywords.
    taken: Taken,
}

const MAP_OPTIONS: &[&str] = &["scale", "kernel", "wrap", "encoding", "y-convention", "bits"];
/// How heights become normals, for what is always made from the 8-bit map.
const MAP_OPTIONS_8_BIT: &[&str] = &["scale", "kernel", "wrap", "encoding", "y-convention"];

/// `normal_map`: how heights become normals, level 0.
pub const NORMAL_MAP: Function = Function { name: "normal_map", command: "normalmap", taken: Taken::Only(MAP_OPTIONS) };
/// `mip_chain`: the same and the mip mode.
pub const MIP_CHAIN: Function = Function {
    name: "mip_chain",
    command: "normalmap",
    taken: Taken::Only(&["scale", "kernel", "wrap", "encoding", "y-convention", "bits", "mip-mode"]),
};
/// `height_mips`: the bits the heights are stored in.
pub const HEIGHT_MIPS: Function = Function { name: "height_mips", command: "normalmap", taken: Taken::Only(&["bits"]) };
/// `horizon_maps`: how heights become normals (the scale is also the depth the horizons are
/// taken at).
pub const HORIZON_MAPS: Function =
    Function { name: "horizon_maps", command: "normalmap", taken: Taken::Only(MAP_OPTIONS) };
/// `roughness_map`: how heights become normals, and the surface's roughness and its layout.
pub const ROUGHNESS_MAP: Function = Function {
    name: "roughness_map",
    command: "normalmap",
    taken: Taken::Only(&["scale", "kernel", "wrap", "encoding", "y-convention", "roughness", "roughness-layout"]),
};
/// `lean_moments`: how heights become normals (always the 8-bit map's, as `render` draws).
pub const LEAN_MOMENTS: Function =
    Function { name: "lean_moments", command: "normalmap", taken: Taken::Only(MAP_OPTIONS_8_BIT) };
/// `read_height_field`: the channel.
pub const READ_HEIGHT_FIELD: Function =
    Function { name: "read_height_field", command: "normalmap", taken: Taken::Only(&["channel"]) };
/// `write_texture`: the texel format.
pub const WRITE_TEXTURE: Function =
    Function { name: "write_texture", command: "normalmap", taken: Taken::Only(&["format"]) };
/// `tangents`: the algorithm and its split angle.
pub const TANGENTS: Function =
    Function { name: "tangents", command: "tangents", taken: Taken::Only(&["mode", "split-angle"]) };
/// `render`: every option of `bumpmap render` but the output files.
pub const RENDER: Function =
    Function { name: "render", command: "render", taken: Taken::AllBut(&["output", "passes"]) };
/// `compare`: every option of `bumpmap compare` but the output folder (its own argument).
pub const COMPARE: Function = Function { name: "compare", command: "compare", taken: Taken::AllBut(&["output"]) };

/// `height_from_normals`: how the slopes are integrated (the output is an array).
pub const HEIGHT_FROM_NORMALS: Function = Function {
    name: "height_from_normals",
    command: "height",
    taken: Taken::Only(&["method", "kernel", "scale", "y-convention", "raw"]),
};

/// Every function that takes options, by Python name.
pub const FUNCTIONS: [&Function; 12] = [
    &NORMAL_MAP,
    &MIP_CHAIN,
    &HEIGHT_MIPS,
    &HORIZON_MAPS,
    &ROUGHNESS_MAP,
    &LEAN_MOMENTS,
    &READ_HEIGHT_FIELD,
    &WRITE_TEXTURE,
    &TANGENTS,
    &RENDER,
    &COMPARE,
    &HEIGHT_FROM_NORMALS,
];

/// A keyword's name for an option's long name: `bump-scale` → `bump_scale`.
fn keyword(long: &str) -> String {
    long.replace('-', "_")
}

impl Function {
    /// The command's arguments this function takes, in the order `--help` lists them.
    fn arguments(&self) -> Vec<Arg> {
        let command = Cli::command();
        let sub = command.find_subcommand(self.command).expect("the function's command exists").clone();
        sub.get_arguments()
            .filter(|a| {
                let Some(long) = a.get_long() else { return false };
                if matches!(long, "help" | "version") {
                    return false;
                }
                match self.taken {
                    Taken::Only(names) => names.contains(&long),
                    Taken::AllBut(names) => !names.contains(&long),
                }
            })
            .cloned()
            .collect()
    }

    /// Parses `fixed` (the positional words and options the function supplies itself) and the
    /// keyword arguments `kwargs` as the command line would.
    pub fn parse(&self, fixed: &[String], kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Command> {
        let arguments = self.arguments();
        let mut argv: Vec<String> = vec!["bumpmap".into(), self.command.into()];
        argv.extend(fixed.iter().cloned());
        if let Some(kwargs) = kwargs {
            for (key, value) in kwargs.iter() {
                let key: String = key.extract().map_err(|_| PyTypeError::new_err("option names must be strings"))?;
                let Some(arg) = arguments.iter().find(|a| a.get_long().is_some_and(|l| keyword(l) == key)) else {
                    let mut names: Vec<String> = arguments.iter().filter_map(|a| a.get_long()).map(keyword).collect();
                    names.sort();
                    return Err(PyTypeError::new_err(format!(
                        "{}() got an unexpected keyword argument '{key}' (it takes: {})",
                        self.name,
                        names.join(", ")
                    )));
                };
                argv.extend(words(self.name, arg, &key, &value)?);
            }
        }
        Cli::try_parse_from(&argv).map(|cli| cli.command).map_err(|e| clap_error(self.name, e))
    }

    /// Each option the function takes.
    pub fn describe(&self) -> Vec<OptionRow> {
        self.arguments()
            .iter()
            .map(|a| {
                let defaults: Vec<String> =
                    a.get_default_values().iter().map(|v| v.to_string_lossy().into_owned()).collect();
                let flag = matches!(a.get_action(), ArgAction::SetTrue);
                let default = if flag || defaults.is_empty() { None } else { Some(defaults.join(",")) };
                let choices = a.get_possible_values().iter().map(|p| p.get_name().to_string()).collect();
                let help = python_words(&a.get_help().map(|h| h.to_string()).unwrap_or_default());
                (keyword(a.get_long().expect("taken arguments are long")), default, help, choices, flag)
            })
            .collect()
    }
}

/// The command-line words for one keyword argument.
fn words(function: &str, arg: &Arg, key: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    let long = arg.get_long().expect("taken arguments are long");
    if value.is_none() {
        return Ok(Vec::new());
    }
    if matches!(arg.get_action(), ArgAction::SetTrue) {
        return match value.cast::<PyBool>() {
            Ok(b) if b.is_true() => Ok(vec![format!("--{long}")]),
            Ok(_) => Ok(Vec::new()),
            Err(_) => Err(PyTypeError::new_err(format!(
                "{function}(): {key} is True or False, got {}",
                value.get_type().name()?
            ))),
        };
    }
    if value.is_instance_of::<PyBool>() {
        return Err(PyTypeError::new_err(format!("{function}(): {key} takes a value, not True or False")));
    }
    // A list for a repeatable option is one value per item; a sequence of numbers is one value.
    let repeatable = matches!(arg.get_action(), ArgAction::Append);
    if repeatable && !is_scalar(value) && !all_numbers(value)? {
        let mut out = Vec::new();
        for item in value.try_iter()? {
            // An iterator may never end: read no further than any option could use.
            if out.len() == MAX_VALUES {
                return Err(PyValueError::new_err(format!(
                    "{function}(): {key} takes at most {MAX_VALUES} values; this one gave more (an endless iterator?)"
                )));
            }
            out.push(format!("--{long}={}", text(function, key, &item?)?));
        }
        return Ok(out);
    }
    Ok(vec![format!("--{long}={}", text(function, key, value)?)])
}

/// The most values a repeatable option reads from one sequence or iterator: far past what any
/// takes (64 lights at most), and a bound on an iterator that never ends.
const MAX_VALUES: usize = 4096;

/// A str, number or path: not a sequence of values.
fn is_scalar(value: &Bound<'_, PyAny>) -> bool {
    value.is_instance_of::<PyString>()
        || value.is_instance_of::<PyInt>()
        || value.is_instance_of::<PyFloat>()
        || value.hasattr("__fspath__").unwrap_or(false)
        || value.hasattr("__float__").unwrap_or(false) && !value.hasattr("__len__").unwrap_or(false)
}

/// A list, tuple or array whose items are all numbers.
fn all_numbers(value: &Bound<'_, PyAny>) -> PyResult<bool> {
    if !(value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() || value.hasattr("__array__")?) {
        return Ok(false);
    }
    for item in value.try_iter()? {
        let item = item?;
        if item.is_instance_of::<PyString>() || !item.hasattr("__float__")? {
            return Ok(false);
        }
    }
    Ok(true)
}

/// One value as the command line writes it: a string or path as it is, a number as Python
/// prints it (the shortest form that reads back the same), a sequence joined by commas.
fn text(function: &str, key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(s) = value.cast::<PyString>() {
        return s.extract::<String>();
    }
    if value.hasattr("__fspath__")? {
        let path = value.py().import("os")?.call_method1("fspath", (value,))?;
        return text(function, key, &path);
    }
    if value.hasattr("__float__")? && !value.hasattr("__len__")? {
        return value.str()?.extract::<String>();
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() || value.hasattr("__array__")? {
        let parts: Vec<String> = value.try_iter()?.map(|item| text(function, key, &item?)).collect::<PyResult<_>>()?;
        return Ok(parts.join(","));
    }
    Err(PyTypeError::new_err(format!(
        "{function}(): {key} takes a string, a number or a sequence of numbers, got {}",
        value.get_type().name()?
    )))
}

/// A clap error in Python's words: a `ValueError` (a `TypeError` for a missing value).
fn clap_error(function: &str, e: clap::Error) -> PyErr {
    let rendered = e.render().to_string();
    let lines: Vec<&str> = rendered
        .lines()
        .map(str::trim_end)
        .filter(|l| !l.is_empty() && !l.starts_with("For more information") && !l.starts_with("Usage:"))
        .collect();
    let message = format!("{function}(): {}", python_words(lines.join(" ").trim_start_matches("error: ")));
    match e.kind() {
        ErrorKind::UnknownArgument | ErrorKind::NoEquals => PyTypeError::new_err(message),
        _ => PyValueError::new_err(message),
    }
}

/// A message in Python's words: each `--long-name` (and its `<VALUE>` placeholder) becomes the
/// keyword `long_name`.
pub fn python_words(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(i) = rest.find("--") {
        let (before, after) = rest.split_at(i);
        out.push_str(before);
        let name_len = after[2..]
            .find(|c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'))
            .unwrap_or(after.len() - 2);
        let starts_word = before.is_empty() || before.ends_with([' ', '\'', '(', '"', ',', '`', '[', '/']);
        if name_len == 0 || !starts_word || !after[2..].starts_with(|c: char| c.is_ascii_lowercase()) {
            out.push_str("--");
            rest = &after[2..];
            continue;
        }
        out.push_str(&keyword(&after[2..2 + name_len]));
        rest = &after[2 + name_len..];
        // `--scale <SCALE>`: the placeholder goes too.
        if let Some(p) = rest.strip_prefix(" <")
            && let Some(end) = p.find('>')
            && p[..end].chars().all(|c| c.is_ascii_uppercase() || c == '_' || c == '.')
        {
            rest = &p[end + 1..];
        }
    }
    out.push_str(rest);
    out
}
