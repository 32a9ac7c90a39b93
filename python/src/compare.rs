//! `compare()`: every technique measured against the reference by `bumpmap_compare`, as `bumpmap
//! compare` measures them, its steps told to a `progress=` function and its notes to the logger.
//!
//! What it does not do: measure or write anything itself (`bumpmap_compare::measure` and
//! `write` do).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use bumpmap_compare::CompareNote;
use bumpmap_words::Error;
use bumpmap_words::compare::{compare_err, note_line};
use bumpmap_words::report::ReportFn;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::to_py;
use crate::{interrupt, keywords, take_progress};

/// `compare`'s steps told to a `progress=` function (where there is one), its notes said as
/// notes.
struct Shown {
    report: Option<ReportFn>,
    total: AtomicU64,
}

impl bumpmap_compare::Progress for Shown {
    fn start(&self, steps: u64) {
        self.total.store(steps, Ordering::Relaxed);
    }

    fn advance(&self, done: u64) {
        if let Some(f) = &self.report {
            f(done, self.total.load(Ordering::Relaxed));
        }
    }

    fn note(&self, note: &CompareNote) {
        bumpmap_words::report::note(note_line(note));
    }
}

/// Every technique measured against the reference, as `bumpmap compare` does; returns
/// `results.json`'s content as a dict, and writes the report folder when `output` is given.
#[pyfunction]
#[pyo3(signature = (output = None, options = None))]
pub fn compare<'py>(
    py: Python<'py>,
    output: Option<PathBuf>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (options, progress) = take_progress("compare", options)?;
    let compare_options = keywords::compare_options("compare", options.as_ref())?;
    if let Some(out) = &output {
        // Before minutes of work: an output that cannot be a folder.
        bumpmap_compare::check_output(out).map_err(|e| to_py("compare", compare_err(e, None, None)))?;
    }
    // Measured and written on the worker, so Ctrl-C also stops the writing (nothing is put
    // in place once it came).
    let results = interrupt::run_reporting(
        py,
        move |cancel, report| {
            let named = output.as_deref().unwrap_or(Path::new("the results"));
            let bumps = compare_options.height_field.to_string();
            let shown = Shown { report, total: AtomicU64::new(0) };
            let (results, inputs) = bumpmap_compare::measure(&compare_options, &shown)
                .map_err(|e| compare_err(e, Some(&bumps), Some(named)))?;
            if let Some(out) = &output {
                let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
                bumpmap_compare::write(out, &results, &inputs, &|| !cancel.begin_commit())
                    .map_err(|e| compare_err(e, None, None))?;
            }
            Ok::<_, Error>(results)
        },
        progress.as_ref(),
    )?
    .map_err(|e| to_py("compare", e))?;
    let json = bumpmap_compare::json(&results);
    py.import("json")?.call_method1("loads", (json,))
}
