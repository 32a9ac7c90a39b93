//! `bumpmap`: normal maps, cube maps, tangent frames and bump-mapped renders from the command
//! line. This file only parses and dispatches (see the library, `lib.rs`), and turns errors into
//! one line on stderr and exit status 1 — 2 for a malformed command line, as clap's own errors.

use clap::Parser;

fn main() {
    let cli = bumpmap_cli::args::Cli::parse();
    if let Err(e) = bumpmap_cli::run(cli) {
        eprintln!("error: {e}");
        std::process::exit(e.exit_code());
    }
}
