//! `bumpmap`: normal maps, cube maps, tangent frames and bump-mapped renders from the command
//! line. Each subcommand lives in its own module; this file only parses and dispatches, and
//! turns errors into one line on stderr and a non-zero exit code.

// The argument structs' doc comments are clap's help texts, written for a terminal: their
// `[dir:]X,Y,Z` and `[0,1]` are not intra-doc links.
#![allow(rustdoc::broken_intra_doc_links)]

mod args;
mod backend;
mod bench;
mod cubemap;
mod demo;
mod error;
mod mesh;
mod normalmap;
mod render;
mod render_args;

use clap::Parser;

use crate::args::{Cli, Command};

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Normalmap(a) => normalmap::run(&a),
        Command::Cubemap(a) => cubemap::run(&a),
        Command::Bench(a) => bench::run(&a),
        Command::Render(a) => render::run(&a),
        Command::Tangents(a) => mesh::run(&a),
        Command::Demo(a) => demo::run(&a),
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
