//! `bumpmap compare`: the flags made into `bumpmap_compare`'s options, its steps shown as a bar,
//! its refusals in the command line's words (`bumpmap_words::compare`). The measuring, the studies and the report are
//! `bumpmap_compare`'s.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use bumpmap_compare::{CompareNote, CompareOptions, Results};

use crate::args::CompareArgs;
use crate::error::CliError;
use crate::report::{Progress, Steps};
use bumpmap_words::compare::compare_err;

/// Runs `bumpmap compare`.
pub fn run(args: &CompareArgs) -> Result<(), CliError> {
    let out = &args.output;
    check_output(out)?;
    let (results, inputs) = measure(args, &Progress::Bar)?;
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    let written = write(out, &results, &inputs, &|| false)?;
    let shown = results.outcomes.iter().filter(|o| o.result.is_ok()).count();
    eprintln!(
        "wrote {} files into {} ({shown} techniques against the reference; open {})",
        written.len(),
        out.display(),
        out.join("report.html").display()
    );
    Ok(())
}

/// Refuses an output that is a file: compare writes a folder.
pub fn check_output(out: &Path) -> Result<(), CliError> {
    bumpmap_compare::check_output(out).map_err(|e| compare_err(e, None, None))
}

/// Everything `compare` measures, and the files it read; its steps shown as `progress` says,
/// the techniques it skips noted.
pub fn measure(args: &CompareArgs, progress: &Progress) -> Result<(Results, Vec<PathBuf>), CliError> {
    measure_options(&compare_options(args)?, Some(&args.output), progress)
}

/// [`measure`] of typed options; `output`, the folder the results will go to, for messages.
pub fn measure_options(
    options: &CompareOptions,
    output: Option<&Path>,
    progress: &Progress,
) -> Result<(Results, Vec<PathBuf>), CliError> {
    let shown = Shown::new(progress);
    let bumps = options.height_field.to_string();
    bumpmap_compare::measure(options, &shown).map_err(|e| compare_err(e, Some(&bumps), output))
}

/// Writes the folder, all files or none.
pub fn write(
    out: &Path,
    results: &Results,
    inputs: &[&Path],
    cancelled: &dyn Fn() -> bool,
) -> Result<Vec<PathBuf>, CliError> {
    bumpmap_compare::write(out, results, inputs, cancelled).map_err(|e| compare_err(e, None, None))
}

/// The library's options as the flags give them (the library's table read them).
pub fn compare_options(args: &CompareArgs) -> Result<CompareOptions, CliError> {
    Ok(args.options.0.clone())
}

/// A library's steps (`compare`'s, the demo's) on a bar or hidden, its notes on stderr.
pub struct Shown<'a> {
    progress: &'a Progress,
    steps: RefCell<Option<Steps>>,
}

impl<'a> Shown<'a> {
    /// Steps shown as `progress` says.
    pub fn new(progress: &'a Progress) -> Self {
        Self { progress, steps: RefCell::new(None) }
    }
}

impl bumpmap_compare::Progress for Shown<'_> {
    fn start(&self, steps: u64) {
        *self.steps.borrow_mut() = Some(Steps::new(self.progress, steps, "{bar:40} {pos}/{len} {elapsed} {wide_msg}"));
    }

    fn step(&self, what: &str) {
        if let Some(s) = self.steps.borrow().as_ref() {
            s.set_message(what);
        }
    }

    fn advance(&self, _done: u64) {
        if let Some(s) = self.steps.borrow().as_ref() {
            s.inc();
        }
    }

    fn note(&self, note: &CompareNote) {
        let line = bumpmap_words::compare::note_line(note);
        match self.steps.borrow().as_ref() {
            Some(s) => s.suspend(|| crate::report::note(line)),
            None => crate::report::note(line),
        }
    }

    fn finish(&self) {
        if let Some(s) = self.steps.borrow().as_ref() {
            s.finish();
        }
    }
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;
    use crate::args::{Cli, Command};

    #[test]
    fn the_flags_defaults_are_the_librarys() {
        let Command::Compare(args) = Cli::try_parse_from(["bumpmap", "compare"]).expect("parses").command else {
            unreachable!("compare parses as compare")
        };
        let from_flags = compare_options(&args).expect("the defaults are valid");
        assert_eq!(format!("{from_flags:?}"), format!("{:?}", CompareOptions::default()));
    }
}
