//! `bumpmap`: normal maps, cube maps, tangent frames and bump-mapped renders from the command
//! line. This file only parses and dispatches (see the library, `lib.rs`), turns errors into
//! one line on stderr and exit status 1 — 2 for a malformed command line, as clap's own errors —
//! and on Ctrl-C or SIGTERM removes the files not yet in place before it exits (130).

use clap::Parser;

fn main() {
    // Elsewhere than Linux there is no prioritized constructor to run it earlier: first thing.
    #[cfg(not(target_os = "linux"))]
    ensure_cpu();
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

/// Stops with a message when this build needs an x86-64 level the processor lacks (the default
/// build is for x86-64-v3, `.cargo/config.toml`): otherwise the first AVX instruction anywhere
/// would kill it with SIGILL. Scalar code and a fixed message only, as the rest of the build may
/// use the instructions that are missing. Runs before `main` (see [`ENSURE_CPU`]).
extern "C" fn ensure_cpu() {
    use std::io::Write;
    if !bumpmap::cpu::has(bumpmap::cpu::built_for()) {
        let _ = std::io::stderr().write_all(
            b"error: this bumpmap was built for x86-64-v3 (AVX2, FMA, BMI2), which this processor lacks; \
              build one for any x86-64 with: RUSTFLAGS=\"-C target-cpu=x86-64\" cargo build --release\n",
        );
        std::process::exit(1);
    }
}

/// [`ensure_cpu`] as the program's first constructor. Libraries run constructors of their own
/// before `main` (the X11 loader behind the viewer's window does), built for x86-64-v3 like the
/// rest; a prioritized `.init_array.NNNNN` entry runs before every unprioritized one, and 101 is
/// the first priority left to programs.
#[cfg(target_os = "linux")]
#[used]
// SAFETY: the section holds pointers to `extern "C" fn()` that the C runtime calls once at start;
// this is one, and `ensure_cpu` needs nothing that is not set up by then (it writes to stderr
// and may exit).
#[unsafe(link_section = ".init_array.00101")]
static ENSURE_CPU: extern "C" fn() = ensure_cpu;
