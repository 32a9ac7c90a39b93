//! The command line's options are the library's option tables (`bumpmap::option_table`,
//! `bumpmap_compare::option_table`), which the Python package's keywords, signatures,
//! docstrings and stubs are made from too: for every command Python exposes, `--help` lists
//! each row of its table by the same name, with the same default and the same choices. (Python's
//! tests hold the stubs and `inspect.signature` to the same tables.)

use bumpmap::option_table::{self, Kind, Opt};
use clap::CommandFactory;

/// `(name, default as the command line writes it, choices, is a flag)` of each row.
fn rows<R: Default>(table: &[Opt<R>]) -> Vec<(String, Option<String>, Vec<String>, bool)> {
    table
        .iter()
        .map(|o| {
            let kind = o.kind();
            let choices = match &kind {
                Kind::Word(w) | Kind::List(Some(w)) => w.iter().map(|c| c.name.to_string()).collect(),
                _ => Vec::new(),
            };
            (o.name.to_string(), o.default_text(), choices, kind == Kind::Flag)
        })
        .collect()
}

/// The same of the argument `--name` of `command`.
fn listed(command: &clap::Command, name: &str) -> (String, Option<String>, Vec<String>, bool) {
    let arg = command
        .get_arguments()
        .find(|a| a.get_long() == Some(name))
        .unwrap_or_else(|| panic!("{} has no --{name}", command.get_name()));
    let flag = matches!(arg.get_action(), clap::ArgAction::SetTrue);
    let defaults: Vec<String> = arg.get_default_values().iter().map(|v| v.to_string_lossy().into_owned()).collect();
    let default = if flag || defaults.is_empty() { None } else { Some(defaults.join(",")) };
    let choices =
        if flag { Vec::new() } else { arg.get_possible_values().iter().map(|v| v.get_name().to_string()).collect() };
    (name.to_string(), default, choices, flag)
}

#[test]
fn every_command_python_exposes_lists_its_tables_options() {
    let cli = bumpmap_cli::args::Cli::command();
    let sub = |path: &[&str]| {
        let mut c = &cli;
        for p in path {
            c = c.find_subcommand(p).unwrap_or_else(|| panic!("no subcommand {p}"));
        }
        c.clone()
    };
    let cases = [
        (vec!["render"], [rows(option_table::SCENE), rows(option_table::FRAME)].concat()),
        (vec!["bench", "render"], rows(option_table::SCENE)),
        (vec!["compare"], rows(bumpmap_compare::option_table::COMPARE)),
        (vec!["tangents"], rows(option_table::TANGENTS)),
        (vec!["height"], rows(option_table::HEIGHTS)),
        (vec!["bake"], rows(option_table::BAKE)),
        (vec!["blend"], rows(option_table::BLEND)),
        (
            vec!["normalmap"],
            [rows(option_table::MAPS), rows(option_table::CHANNEL), rows(option_table::FORMAT)].concat(),
        ),
    ];
    let mut checked = 0;
    for (path, table) in cases {
        let command = sub(&path);
        for row in table {
            assert_eq!(listed(&command, &row.0), row, "bumpmap {} --{}", path.join(" "), row.0);
            checked += 1;
        }
    }
    assert!(checked > 80, "{checked} options checked");
    // view takes every scene option too; its backend defaults to auto (a window wants the GPU).
    let view = sub(&["view"]);
    for row in rows(option_table::SCENE) {
        let mut shown = listed(&view, &row.0);
        if row.0 == "backend" {
            assert_eq!(shown.1.as_deref(), Some("auto"));
            shown.1 = row.1.clone();
        }
        assert_eq!(shown, row, "bumpmap view --{}", row.0);
    }
}

#[test]
fn a_technique_lists_what_it_needs() {
    let cli = bumpmap_cli::args::Cli::command();
    let render = cli.find_subcommand("render").expect("render");
    let technique = render.get_arguments().find(|a| a.get_long() == Some("technique")).expect("--technique");
    let pom = technique.get_possible_values().into_iter().find(|v| v.get_name() == "pom").expect("pom");
    assert!(pom.get_help().is_some_and(|h| h.to_string().contains("[needs heights]")), "{:?}", pom.get_help());
}
