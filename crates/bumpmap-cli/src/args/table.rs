//! Every command's options as data — long name, default, help, each value's name and meaning,
//! whether it is a flag — for a skin that is not a command line. The Python package makes its
//! docstrings, signatures and stubs from this table, which it compiles in as
//! `python/src/options.json`; a test here (`tests/python_options.rs`) keeps that file equal to
//! [`options_table`], so the help is written once, here, as doc comments.
//!
//! What this module does not do: decide which options a Python function takes (it reads the
//! keywords it lists), or word anything in Python's terms (the package does, with
//! `bumpmap_words::as_keywords`).

use clap::{ArgAction, CommandFactory};
use serde_json::{Value, json};

use super::Cli;

/// `{command: [{long, default, help, values: [{name, help}], flag}]}` for every subcommand, its
/// options in the order `--help` lists them (`help` and `version` left out). `default` is as
/// the command line writes it (several joined by commas), `null` for none and for flags; a
/// flag's values (clap's true and false) are not listed.
pub fn options_table() -> Value {
    let command = Cli::command();
    let mut table = serde_json::Map::new();
    for sub in command.get_subcommands() {
        let rows: Vec<Value> = sub
            .get_arguments()
            .filter_map(|a| {
                let long = a.get_long().filter(|l| !matches!(*l, "help" | "version"))?;
                let flag = matches!(a.get_action(), ArgAction::SetTrue);
                let defaults: Vec<String> =
                    a.get_default_values().iter().map(|v| v.to_string_lossy().into_owned()).collect();
                let default = if flag || defaults.is_empty() { None } else { Some(defaults.join(",")) };
                let values: Vec<Value> = if flag {
                    Vec::new()
                } else {
                    a.get_possible_values()
                        .iter()
                        .map(|v| json!({"name": v.get_name(), "help": v.get_help().map(|h| h.to_string())}))
                        .collect()
                };
                let help = a.get_help().map(|h| h.to_string()).unwrap_or_default();
                Some(json!({"long": long, "default": default, "help": help, "values": values, "flag": flag}))
            })
            .collect();
        table.insert(sub.get_name().to_string(), Value::Array(rows));
    }
    Value::Object(table)
}

/// [`options_table`] as the file holds it: pretty-printed, one newline at the end.
pub fn options_table_text() -> String {
    let mut text = serde_json::to_string_pretty(&options_table()).expect("a table of strings serializes");
    text.push('\n');
    text
}
