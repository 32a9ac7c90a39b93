//! What work tells the person waiting for it besides its result: warnings and notes, and its
//! progress as `(done, total)` told to a function. Said on the thread that runs the work, they go
//! to stderr, unless a caller that wants them itself (the Python package: `warnings` and
//! `logging`) collects them with [`collect`].
//!
//! What this module does not do: decide what deserves a warning (the skins do, from the
//! library's typed notes), draw a progress bar (the command line's `report` does), or collect
//! what the threads of a parallel loop say (none of them warns: warnings come from the thread
//! that runs the command).

use std::cell::RefCell;
use std::sync::Arc;

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

#[cfg(test)]
mod tests {
    use super::*;

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
