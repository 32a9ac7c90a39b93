//! The `bumpmap` command line as a library: `main.rs` parses and calls [`run`]; the fuzz
//! targets (`fuzz/`) reach the argument parser through [`args::Cli`]. Each subcommand lives in
//! its own module. The work is the libraries' (`bumpmap`, `bumpmap_compare`); what they refuse
//! and note is worded by `bumpmap_words`, which the Python package shares.
//!
//! - [`args`]: the command line (clap), a module per command; the options the library declares
//!   as tables (`bumpmap::option_table`) become arguments through [`args::table`];
//! - `setup`, `compare`: the flags made into the libraries' options (`bumpmap::options`,
//!   `bumpmap_compare`);
//! - `normalmap`, `cubemap`, `mesh` (tangents), `bake`, `render`, `bench`, `demo`, `view`, `inspect`
//!   (inspect and height): the subcommands, drawing through the `bumpmap` crate's renderer;
//! - [`error`]: every layer's errors as one type (`bumpmap_words::Error`), with exit statuses;
//! - `report`: progress as a bar on stderr (warnings and notes are `bumpmap_words::report`'s).

// The argument structs' doc comments are clap's help texts, written for a terminal: their
// `[dir:]X,Y,Z` and `[0,1]` are not intra-doc links.
#![allow(rustdoc::broken_intra_doc_links)]
#![warn(missing_docs)]

pub mod args;
mod bake;
mod bench;
mod blend;
mod compare;
mod cubemap;
mod demo;
pub mod error;
mod inspect;
mod mesh;
mod normalmap;
mod render;
mod report;
mod setup;
mod view;

use crate::args::{Cli, Command};

/// Runs the parsed command.
pub fn run(cli: Cli) -> Result<(), error::CliError> {
    match cli.command {
        Command::Normalmap(a) => normalmap::run(&a),
        Command::Cubemap(a) => cubemap::run(&a),
        Command::Bake(a) => bake::run(&a),
        Command::Blend(a) => blend::run(&a),
        Command::Bench(a) => bench::run(&a),
        Command::Render(a) => render::run(&a),
        Command::Tangents(a) => mesh::run(&a),
        Command::Demo(a) => demo::run(&a),
        Command::Compare(a) => compare::run(&a),
        Command::View(a) => view::run(&a),
        Command::Inspect(a) => inspect::run_inspect(&a),
        Command::Height(a) => inspect::run_height(&a),
    }
}
