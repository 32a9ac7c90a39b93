//! `bumpmap demo`: the `bumpmap_demo` library's folder, its steps on a bar.

use crate::args::DemoArgs;
use crate::compare::Shown;
use crate::error::CliError;
use crate::report::Progress;

/// Runs `bumpmap demo`.
pub fn run(args: &DemoArgs) -> Result<(), CliError> {
    let out = bumpmap_demo::write(&args.output, args.gpu, &Shown::new(&Progress::Bar))?;
    eprintln!("wrote the demo into {} (see its README.md)", out.display());
    Ok(())
}
