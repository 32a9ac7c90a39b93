//! The Python package compiles the commands' option table in (`python/src/options.json`: its
//! docstrings, signatures and stubs come from it); this keeps the file equal to the table the
//! command line's own definition gives, so no help text or default is written twice.
//! `BUMPMAP_BLESS=1 cargo test -p bumpmap-cli --test python_options` rewrites it.

use std::path::PathBuf;

#[test]
fn pythons_option_table_is_the_command_lines() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../python/src/options.json");
    let table = bumpmap_cli::args::options_table_text();
    if std::env::var_os("BUMPMAP_BLESS").is_some() {
        std::fs::write(&path, &table).expect("writes the table");
    }
    let held = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        held == table,
        "{} is not the command line's option table: run `BUMPMAP_BLESS=1 cargo test -p bumpmap-cli --test python_options` and commit it",
        path.display()
    );
}

#[test]
fn the_table_lists_what_the_docstrings_need() {
    let table = bumpmap_cli::args::options_table();
    let render = table["render"].as_array().expect("render's options");
    let technique = render.iter().find(|o| o["long"] == "technique").expect("render takes --technique");
    let default = bumpmap::options::SceneOptions::default().technique.technique;
    assert_eq!(technique["default"], bumpmap::Named::name(default), "the library's default, as the flag writes it");
    let values = technique["values"].as_array().expect("its values");
    assert!(values.iter().any(|v| v["name"] == "pom" && v["help"].as_str().is_some_and(|h| !h.is_empty())));
    let flag = render.iter().find(|o| o["long"] == "no-self-shadow").expect("a flag");
    assert_eq!(flag["flag"], true);
    assert!(flag["values"].as_array().is_some_and(Vec::is_empty), "a flag's true/false are no choices");
    assert!(!render.iter().any(|o| o["long"] == "help"));
}
