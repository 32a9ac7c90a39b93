//! Every function's option table — help texts, defaults, choices — which the docstrings,
//! signatures and stubs are made from, in Python's words (`bump_scale`, not `--bump-scale`).
//! The tables are the library's (`bumpmap::option_table`, `bumpmap_compare::option_table`),
//! which the command line's arguments are made from too, so each help text, default and
//! choice is written once. The keywords themselves are read by `keywords`, into typed options.
//!
//! What it does not do: decide any default or range itself; those are the library's.

use bumpmap::option_table::{self, Kind, Opt};
use bumpmap_words::as_keywords;

/// One option as the docstrings show it: `(keyword, default as the command line writes it,
/// help, choices, is a flag)`.
pub type OptionRow = (String, Option<String>, String, Vec<String>, bool);

/// Every function that takes options, by Python name.
pub const FUNCTIONS: [&str; 12] = [
    "normal_map",
    "mip_chain",
    "height_mips",
    "horizon_maps",
    "roughness_map",
    "lean_moments",
    "read_height_field",
    "write_texture",
    "tangents",
    "render",
    "compare",
    "height_from_normals",
];

/// Each option `function` takes, in the order its table lists them; `None` for a function that
/// takes none.
pub fn describe(function: &str) -> Option<Vec<OptionRow>> {
    fn rows<R: Default>(table: &[Opt<R>]) -> Vec<OptionRow> {
        table.iter().map(row_of).collect()
    }
    let taken = crate::keywords::names(function)?;
    let all = match function {
        "render" => option_table::render().map(row_of).collect(),
        "compare" => rows(bumpmap_compare::option_table::COMPARE),
        "tangents" => rows(option_table::TANGENTS),
        "height_from_normals" => rows(option_table::HEIGHTS),
        "read_height_field" => rows(option_table::CHANNEL),
        "write_texture" => rows(option_table::FORMAT),
        _ => rows(option_table::MAPS),
    };
    Some(all.into_iter().filter(|row| taken.contains(&row.0)).collect())
}

/// A row of the library's option table as the docstrings show it: the help in keywords, each
/// value of a closed set with its meaning on a line of its own.
fn row_of<R: Default>(option: &Opt<R>) -> OptionRow {
    let kind = option.kind();
    let mut help = as_keywords(option.help);
    let mut choices = Vec::new();
    if let Kind::Word(words) | Kind::List(Some(words)) = &kind {
        for word in words {
            help.push_str(&format!("\n- {}: {}", word.name, as_keywords(&word.help)));
            choices.push(word.name.to_string());
        }
    }
    (option.keyword(), option.default_text(), help, choices, kind == Kind::Flag)
}
