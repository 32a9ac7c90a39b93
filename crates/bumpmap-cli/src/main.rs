//! `bumpmap`: normal maps, cube maps, tangent frames and bump-mapped renders from the command
//! line. This file only parses and dispatches (see the library, `lib.rs`), turns errors into
//! one line on stderr and exit status 1 — 2 for a malformed command line, as clap's own errors —
//! and on Ctrl-C or SIGTERM removes the files not yet in place before it exits (130).

use clap::Parser;

fn main() {
    let cli = bumpmap_cli::args::Cli::parse();
    // A set of output files is all or nothing, also when the command is stopped: what was
    // staged is removed (a set being renamed into place is let finish first).
    let _ = ctrlc::set_handler(|| {
        bumpmap_io::atomic::abandon_all();
        eprintln!("interrupted: no file was left half-written (a folder run keeps the images it had finished)");
        std::process::exit(130);
    });
    if let Err(e) = bumpmap_cli::run(cli) {
        eprintln!("error: {e}");
        std::process::exit(e.exit_code());
    }
}
