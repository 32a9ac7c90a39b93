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
pub const FUNCTIONS: [&str; 15] = [
    "normal_map",
    "mip_chain",
    "height_mips",
    "write_heights",
    "horizon_maps",
    "roughness_map",
    "lean_moments",
    "read_height_field",
    "write_texture",
    "tangents",
    "render",
    "compare",
    "height_from_normals",
    "bake",
    "blend_normals",
];

/// Each option `function` takes, in the order its table lists them; `None` for a function that
/// takes none.
pub fn describe(function: &str) -> Option<Vec<OptionRow>> {
    Some(rows(function)?.into_iter().map(|(row, _)| row).collect())
}

/// Each option `function` takes with its kind as the stub generator reads it
/// (`scripts/python_stub_literals.py`): `flag`, `number`, `whole`, `numbers:N`, `word`, `text`,
/// `path`, `lights`, `attenuation` or `list`.
pub fn kinds(function: &str) -> Option<Vec<(String, String)>> {
    Some(rows(function)?.into_iter().map(|(row, kind)| (row.0, kind_name(&kind))).collect())
}

/// [`describe`]'s rows with each option's kind.
fn rows(function: &str) -> Option<Vec<(OptionRow, Kind)>> {
    fn of<R: Default>(table: &[Opt<R>]) -> Vec<(OptionRow, Kind)> {
        table.iter().map(|o| (row_of(o), o.kind())).collect()
    }
    let taken = crate::keywords::names(function)?;
    let all = match function {
        "render" => option_table::render().map(|o| (row_of(o), o.kind())).collect(),
        "compare" => of(bumpmap_compare::option_table::COMPARE),
        "tangents" => of(option_table::TANGENTS),
        "bake" => of(option_table::BAKE),
        "blend_normals" => of(option_table::BLEND),
        "height_from_normals" => of(option_table::HEIGHTS),
        "read_height_field" => of(option_table::CHANNEL),
        "write_texture" => of(option_table::FORMAT),
        _ => of(option_table::MAPS),
    };
    Some(all.into_iter().filter(|(row, _)| taken.contains(&row.0)).collect())
}

/// A kind as one word for the stub generator.
fn kind_name(kind: &Kind) -> String {
    match kind {
        Kind::Flag => "flag".into(),
        Kind::Number => "number".into(),
        Kind::Whole { .. } => "whole".into(),
        Kind::Numbers(n) => format!("numbers:{n}"),
        Kind::Word(_) => "word".into(),
        Kind::Text => "text".into(),
        Kind::Path => "path".into(),
        Kind::Lights => "lights".into(),
        Kind::Attenuation => "attenuation".into(),
        Kind::List(_) => "list".into(),
    }
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
