//! What work tells the person waiting for it besides its result: warnings, notes and progress.
//! On the command line warnings and notes go to stderr and progress is a bar there; a caller that
//! wants them itself (the Python package: `warnings`, `logging` and a `progress=` function)
//! collects the warnings and notes of the work it runs with [`collect`] and hands
//! [`Progress::Report`] a function.
//!
//! What this module does not do: decide what deserves a warning (the commands do), or collect
//! what the threads of a parallel loop say (none of them warns: warnings come from the thread
//! that runs the command).

use std::cell::RefCell;
use std::sync::Arc;

use indicatif::{ProgressBar, ProgressStyle};

/// One thing work said.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Diagnostic {
    /// Something the caller may want to change: an input used in a way it may not expect.
    Warning(String),
    /// What the work did or chose, for the record.
    Note(String),
}

thread_local! {
    /// Where this thread's diagnostics go while [`collect`] runs; stderr otherwise.
    static COLLECTED: RefCell<Option<Vec<Diagnostic>>> = const { RefCell::new(None) };
}

/// Says `message` as a warning: to the collector this thread runs under, else to stderr as
/// `warning: MESSAGE`.
pub fn warn(message: impl Into<String>) {
    say(Diagnostic::Warning(message.into()));
}

/// Says `message` as a note: to the collector this thread runs under, else to stderr.
pub fn note(message: impl Into<String>) {
    say(Diagnostic::Note(message.into()));
}

/// A line of a scene's setup notes, which mark their warnings `warning: `: said as what it is.
pub fn setup_line(line: &str) {
    match line.strip_prefix("warning: ") {
        Some(w) => warn(w),
        None => note(line),
    }
}

fn say(d: Diagnostic) {
    let unsaid = COLLECTED.with(|c| match c.borrow_mut().as_mut() {
        Some(list) => {
            list.push(d);
            None
        }
        None => Some(d),
    });
    match unsaid {
        Some(Diagnostic::Warning(w)) => eprintln!("warning: {w}"),
        Some(Diagnostic::Note(n)) => eprintln!("{n}"),
        None => {}
    }
}

/// Runs `work` with the warnings and notes it says on this thread collected instead of printed,
/// and returns them beside its result, in the order said.
pub fn collect<R>(work: impl FnOnce() -> R) -> (R, Vec<Diagnostic>) {
    /// Puts the outer collector back however `work` ends, a panic included, so a panic caught
    /// further out does not leave this thread collecting into a list nobody reads.
    struct Restore(Option<Option<Vec<Diagnostic>>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            if let Some(outer) = self.0.take() {
                COLLECTED.with(|c| *c.borrow_mut() = outer);
            }
        }
    }
    let mut restore = Restore(Some(COLLECTED.with(|c| c.replace(Some(Vec::new())))));
    let result = work();
    let outer = restore.0.take().expect("restored only here or on unwinding");
    let said = COLLECTED.with(|c| c.replace(outer)).unwrap_or_default();
    (result, said)
}

/// A function told `(done, total)` steps as work advances, from any thread.
pub type ReportFn = Arc<dyn Fn(u64, u64) + Send + Sync>;

/// How long work shows its progress.
#[derive(Clone, Default)]
pub enum Progress {
    /// Not at all.
    #[default]
    Hidden,
    /// A bar on stderr (where stderr is a terminal).
    Bar,
    /// Told to a function.
    Report(ReportFn),
}

impl Progress {
    /// The function to tell, for [`Progress::Report`].
    pub fn report_fn(&self) -> Option<&ReportFn> {
        match self {
            Progress::Report(f) => Some(f),
            _ => None,
        }
    }
}

/// Counted steps of long work: a bar on stderr for [`Progress::Bar`], the function of
/// [`Progress::Report`] told after each step, or nothing.
pub struct Steps {
    bar: ProgressBar,
    report: Option<ReportFn>,
}

impl Steps {
    /// `total` steps, shown as `progress` says, the bar in `template` (indicatif's).
    pub fn new(progress: &Progress, total: u64, template: &str) -> Self {
        let bar = match progress {
            Progress::Bar => ProgressBar::new(total),
            _ => ProgressBar::hidden(),
        };
        let bar = bar.with_style(ProgressStyle::with_template(template).expect("a valid template"));
        bar.set_length(total);
        Self { bar, report: progress.report_fn().cloned() }
    }

    /// One more step done.
    pub fn inc(&self) {
        self.bar.inc(1);
        if let Some(f) = &self.report {
            f(self.bar.position(), self.bar.length().unwrap_or(0));
        }
    }

    /// What is being done now, beside the bar.
    pub fn set_message(&self, message: impl Into<String>) {
        self.bar.set_message(message.into());
    }

    /// Runs `f` with the bar hidden, for a line on stderr.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.bar.suspend(f)
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_tell_the_function_each_step() {
        let seen = Arc::new(std::sync::Mutex::new(Vec::new()));
        let s = seen.clone();
        let steps = Steps::new(&Progress::Report(Arc::new(move |d, t| s.lock().unwrap().push((d, t)))), 3, "{pos}");
        for _ in 0..3 {
            steps.inc();
        }
        assert_eq!(*seen.lock().unwrap(), vec![(1, 3), (2, 3), (3, 3)]);
    }

    #[test]
    fn a_panic_inside_collect_leaves_the_thread_printing_again() {
        let caught = std::panic::catch_unwind(|| {
            collect(|| {
                warn("lost with the panic");
                panic!("the work failed");
            })
        });
        assert!(caught.is_err());
        assert!(COLLECTED.with(|c| c.borrow().is_none()), "the collector outlived its collect");
        let ((), said) = collect(|| note("after"));
        assert_eq!(said, vec![Diagnostic::Note("after".into())]);
    }

    #[test]
    fn collected_diagnostics_come_back_in_order_and_nest() {
        let ((inner, ()), outer) = collect(|| {
            warn("a");
            let r = collect(|| note("b"));
            setup_line("warning: c");
            setup_line("d");
            (r, ())
        });
        assert_eq!(inner.1, vec![Diagnostic::Note("b".into())]);
        assert_eq!(
            outer,
            vec![Diagnostic::Warning("a".into()), Diagnostic::Warning("c".into()), Diagnostic::Note("d".into())]
        );
    }
}
