//! Every function's option table — help texts, defaults, choices, read from the command's own
//! definition — which the docstrings, signatures and stubs are made from, and messages in
//! Python's words (`bump_scale`, not `--bump-scale`). The keywords themselves are read by
//! `keywords`, into typed options.
//!
//! What it does not do: decide any default or range itself; those live in `bumpmap_cli::args`.

use bumpmap_cli::args::Cli;
use clap::{Arg, ArgAction, CommandFactory};

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

/// A keyword's name for an option's long name: `bump-scale` → `bump_scale`.
fn keyword(long: &str) -> String {
    long.replace('-', "_")
}

impl Function {
    /// The command's arguments this function takes, in the order `--help` lists them.
    fn arguments(&self) -> Vec<Arg> {
        let taken = crate::keywords::names(self.name).expect("every function with options reads keywords");
        let command = Cli::command();
        let sub = command.find_subcommand(self.command).expect("the function's command exists").clone();
        sub.get_arguments()
            .filter(|a| {
                let Some(long) = a.get_long() else { return false };
                if matches!(long, "help" | "version") {
                    return false;
                }
                taken.contains(&keyword(long).as_str())
            })
            .cloned()
            .collect()
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
                // A flag's "values" are clap's true and false: not choices to document.
                let values = if flag { Vec::new() } else { a.get_possible_values() };
                let choices = values.iter().map(|p| p.get_name().to_string()).collect();
                let mut help = python_words(&a.get_help().map(|h| h.to_string()).unwrap_or_default());
                // Each value's meaning, where the set gives one, as `--help` lists it: one
                // "\n- name: meaning" line each.
                for value in values.iter().filter(|v| v.get_help().is_some()) {
                    let meaning = python_words(&value.get_help().map(|h| h.to_string()).unwrap_or_default());
                    help.push_str(&format!("\n- {}: {meaning}", value.get_name()));
                }
                (keyword(a.get_long().expect("taken arguments are long")), default, help, choices, flag)
            })
            .collect()
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
