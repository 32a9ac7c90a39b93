//! Every function's option table — help texts, defaults, choices — which the docstrings,
//! signatures and stubs are made from, in Python's words (`bump_scale`, not `--bump-scale`). The
//! table is the command line's (`options.json`, compiled in; `bumpmap_cli::args::options_table`
//! makes it and a test of the command line keeps the file current), so each help text is
//! written once. The keywords themselves are read by `keywords`, into typed options.
//!
//! What it does not do: decide any default or range itself; those are the library's and the
//! command line's.

use std::sync::OnceLock;

use bumpmap_words::{as_keywords, keyword};
use serde_json::Value;

/// One option as the docstrings show it: `(keyword, default as the command line writes it,
/// help, choices, is a flag)`.
pub type OptionRow = (String, Option<String>, String, Vec<String>, bool);

/// A Python function and the command whose options it takes as keywords (those of its options
/// whose keyword `keywords::names` lists).
pub struct Function {
    /// The Python name.
    pub name: &'static str,
    /// The subcommand.
    command: &'static str,
}

/// Every function that takes options, by Python name, and its command.
pub const FUNCTIONS: [Function; 12] = [
    Function { name: "normal_map", command: "normalmap" },
    Function { name: "mip_chain", command: "normalmap" },
    Function { name: "height_mips", command: "normalmap" },
    Function { name: "horizon_maps", command: "normalmap" },
    Function { name: "roughness_map", command: "normalmap" },
    Function { name: "lean_moments", command: "normalmap" },
    Function { name: "read_height_field", command: "normalmap" },
    Function { name: "write_texture", command: "normalmap" },
    Function { name: "tangents", command: "tangents" },
    Function { name: "render", command: "render" },
    Function { name: "compare", command: "compare" },
    Function { name: "height_from_normals", command: "height" },
];

/// The commands' option table, parsed once.
fn table() -> &'static Value {
    static TABLE: OnceLock<Value> = OnceLock::new();
    TABLE.get_or_init(|| serde_json::from_str(include_str!("options.json")).expect("options.json is the CLI's JSON"))
}

/// A string field of a row ("" where absent).
fn text<'a>(row: &'a Value, key: &str) -> &'a str {
    row[key].as_str().unwrap_or_default()
}

impl Function {
    /// Each option the function takes, in the order `--help` lists them.
    pub fn describe(&self) -> Vec<OptionRow> {
        let taken = crate::keywords::names(self.name).expect("every function with options reads keywords");
        let rows = table()[self.command].as_array().expect("the function's command is in the table");
        rows.iter()
            .filter(|row| taken.contains(&keyword(text(row, "long")).as_str()))
            .map(|row| {
                let values = row["values"].as_array().map(Vec::as_slice).unwrap_or_default();
                let mut help = as_keywords(text(row, "help"));
                // Each value's meaning, where the set gives one, as `--help` lists it: one
                // "\n- name: meaning" line each.
                for value in values.iter().filter(|v| v["help"].is_string()) {
                    help.push_str(&format!("\n- {}: {}", text(value, "name"), as_keywords(text(value, "help"))));
                }
                let choices = values.iter().map(|v| text(v, "name").to_string()).collect();
                let default = row["default"].as_str().map(str::to_string);
                (keyword(text(row, "long")), default, help, choices, row["flag"] == true)
            })
            .collect()
    }
}
