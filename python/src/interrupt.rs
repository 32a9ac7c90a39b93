//! Long work off the interpreter: run on its own thread with the GIL released, while the calling
//! thread wakes every 50 ms to let Python handle signals, so Ctrl-C raises `KeyboardInterrupt`
//! at once instead of when the work ends.
//!
//! An interrupted call returns at once. Work that tells its progress stops at its next step: the
//! function it tells its steps to unwinds it from there ([`Stopped`], caught nowhere but the
//! worker thread's end), so a render or a bake given up on frees its cores within one step.
//! Other work runs on to its end and its result is dropped. Work that writes files claims the right to put them in
//! place ([`Cancel::begin_commit`]) after staging them: an interrupted call has given that right
//! up, so it writes nothing, and its staged files are removed when the work ends — or, when the
//! interpreter exits first, by the exit hook the module registers (`abandon_all`, which first
//! gives up on all running work and waits a while for it to end). A Ctrl-C
//! that arrives while files are being renamed into place (a few milliseconds) waits for the
//! renames and is raised as the call returns: the call happened whole, then the interrupt.
//!
//! What the work says besides its result reaches Python here too: its warnings as
//! `bumpmap.BumpmapWarning` through `warnings` (a filter that makes them errors raises), its notes
//! through the `bumpmap` logger at INFO, and its progress as calls of a `progress=` function, made
//! on the calling thread between waits (at most every 50 ms) and once at the end with done =
//! total; an exception the function raises ends the call as Ctrl-C does and is raised.

use std::path::PathBuf;
use std::sync::atomic::{AtomicU8, AtomicU64, Ordering};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::sync::{Arc, Condvar, Mutex, OnceLock, PoisonError};
use std::thread::ThreadId;
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;

use bumpmap_io::atomic::FileSet;
use bumpmap_words::Error;
use bumpmap_words::as_keywords;
use bumpmap_words::report::{Diagnostic, ReportFn};
use pyo3::prelude::*;

/// Whether the caller gave up on the work (Ctrl-C), and whether the work already began to put
/// its files in place: one of the two wins, never both.
#[derive(Clone, Default)]
pub struct Cancel(Arc<AtomicU8>);

const RUNNING: u8 = 0;
const CANCELLED: u8 = 1;
const COMMITTING: u8 = 2;

impl Cancel {
    /// Claims the right to put staged files in place: false when the caller gave up (write
    /// nothing); once claimed, the caller's Ctrl-C waits for the work to end.
    pub fn begin_commit(&self) -> bool {
        self.0.compare_exchange(RUNNING, COMMITTING, Ordering::SeqCst, Ordering::SeqCst).is_ok()
    }

    /// Puts `set`'s staged files in place, unless the caller gave up (Ctrl-C): then nothing goes
    /// in place and the staged files go with the set.
    pub fn commit(&self, set: FileSet) -> Result<Vec<PathBuf>, Error> {
        if !self.begin_commit() {
            return Err(Error::Interrupted);
        }
        Ok(set.commit()?)
    }

    /// Whether the caller gave up on the work.
    fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::SeqCst) == CANCELLED
    }

    /// Gives up on the work unless it is already putting files in place; whether it gave up.
    fn give_up(&self) -> bool {
        matches!(
            self.0.compare_exchange(RUNNING, CANCELLED, Ordering::SeqCst, Ordering::SeqCst),
            Ok(_) | Err(CANCELLED)
        )
    }
}

/// The error of a pool that could not be started.
fn no_threads(why: String) -> PyErr {
    PyRuntimeError::new_err(format!("cannot start bumpmap's worker threads: {why}"))
}

/// The worker's stack: as large as a main thread's, for the deep recursion some inputs bring.
const STACK_BYTES: usize = 64 << 20;

/// Runs `work` on its own thread with the GIL released and returns its result; a signal handler
/// that raises (Ctrl-C's `KeyboardInterrupt`) ends the wait at once, with the work's [`Cancel`]
/// set. A panic in the work is a `RuntimeError` naming it a bug. Its warnings and notes are
/// said in Python when it ends.
pub fn run<T: Send + 'static>(py: Python<'_>, work: impl FnOnce(&Cancel) -> T + Send + 'static) -> PyResult<T> {
    run_reporting(py, move |cancel, _| work(cancel), None)
}

/// What unwinds work whose caller gave up, from the function it tells its progress to.
struct Stopped;

/// [`run`] for work that tells its progress to the function it is given: `progress` (a
/// `progress=` function) is told the steps, and a caller that gives up (Ctrl-C, or `progress`
/// raising) stops the work at its next step.
pub fn run_reporting<T: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce(&Cancel, Option<ReportFn>) -> T + Send + 'static,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<T> {
    let counter = Arc::new(Counter::default());
    let cancel = Cancel::default();
    let shown = Some(counter.report_fn(cancel.clone()));
    let (value, said) = wait(
        py,
        cancel,
        move |cancel, pool| pool.install(|| bumpmap_words::report::collect(|| work(cancel, shown))),
        progress.map(|f| (&counter, f)),
    )?;
    say(py, said)?;
    Ok(value)
}

/// Steps done and in all, counted by the work's threads, read by the calling thread.
#[derive(Default)]
struct Counter {
    done: AtomicU64,
    total: AtomicU64,
}

impl Counter {
    /// The function the work tells its steps to; once `cancel` is given up, it unwinds the work
    /// instead (`resume_unwind`: no panic message, and the staged files' guards drop).
    fn report_fn(self: &Arc<Self>, cancel: Cancel) -> ReportFn {
        let counter = self.clone();
        Arc::new(move |done, total| {
            if cancel.is_cancelled() {
                std::panic::resume_unwind(Box::new(Stopped));
            }
            counter.total.store(total, Ordering::Relaxed);
            counter.done.fetch_max(done, Ordering::Relaxed);
        })
    }

    fn read(&self) -> (u64, u64) {
        (self.done.load(Ordering::Relaxed), self.total.load(Ordering::Relaxed))
    }
}

/// Says in Python what the work said: warnings through `warnings`, notes through `logging`.
fn say(py: Python<'_>, said: Vec<Diagnostic>) -> PyResult<()> {
    for d in said {
        match d {
            Diagnostic::Warning(w) => {
                let category = py.get_type::<crate::errors::BumpmapWarning>();
                let text = std::ffi::CString::new(as_keywords(&w).replace('\0', " ")).expect("no NUL left");
                // Level 2: the line that called the package's function, not the function itself.
                PyErr::warn(py, category.as_any(), &text, 2)?;
            }
            Diagnostic::Note(n) => {
                py.import("logging")?
                    .call_method1("getLogger", ("bumpmap",))?
                    .call_method1("info", (as_keywords(&n),))?;
            }
        }
    }
    Ok(())
}

/// [`run`], but `work` runs on the worker thread itself, beside this process's pool, and enters
/// it (`pool.install`) where it chooses: for work that must take a lock first. A pool thread
/// waiting on a lock can be the one another job's parallel loop needs (a thread idle in a
/// `join` runs whatever job is queued, the one that waits included): locks are taken outside.
///
/// What the work says goes to stderr: it is drawing, which says nothing.
pub fn run_beside_pool<T: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce(&Cancel, &rayon::ThreadPool) -> T + Send + 'static,
) -> PyResult<T> {
    wait(py, Cancel::default(), work, None)
}

/// Runs `work` on its own thread beside the pool and waits for it, handling signals and
/// telling `progress` between waits.
fn wait<T: Send + 'static>(
    py: Python<'_>,
    cancel: Cancel,
    work: impl FnOnce(&Cancel, &rayon::ThreadPool) -> T + Send + 'static,
    progress: Option<(&Arc<Counter>, &Bound<'_, PyAny>)>,
) -> PyResult<T> {
    let mut told = (0, 0);
    let tell = |told: &mut (u64, u64), now: (u64, u64)| -> PyResult<()> {
        if let Some((_, f)) = progress
            && now != *told
        {
            *told = now;
            f.call1(now)?;
        }
        Ok(())
    };
    let (tx, rx) = channel();
    // Waited on with the GIL released, from whichever thread the closure runs on.
    let rx = Mutex::new(rx);
    let worker_cancel = cancel.clone();
    // A daemon thread calling in once the interpreter's exit has begun: the call never starts,
    // and the thread waits, without the GIL, for the process to end.
    if exiting_elsewhere() {
        py.detach(|| park_for_ever());
    }
    let in_flight = InFlight::enter(&cancel);
    let handle = std::thread::Builder::new()
        .name("bumpmap".into())
        .stack_size(STACK_BYTES)
        .spawn(move || {
            // Counted until the work and everything it holds are gone, whatever way it ends.
            let _in_flight = in_flight;
            match crate::pool::current(STACK_BYTES) {
                // On this process's own pool, so the parallel loops inside survive a fork.
                Ok(pool) => {
                    let _ = tx.send(Ok(work(&worker_cancel, &pool)));
                }
                Err(e) => {
                    let _ = tx.send(Err(e.to_string()));
                }
            }
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a worker thread: {e}")))?;
    loop {
        match py.detach(|| unless_exiting(rx.lock().expect("one waiter").recv_timeout(Duration::from_millis(50)))) {
            Ok(value) => {
                let _ = handle.join();
                let value = value.map_err(no_threads)?;
                if let Some((counter, _)) = progress {
                    // Once more at the end, all steps done (1 of 1 for work that counted none).
                    let total = counter.read().1.max(1);
                    tell(&mut told, (total, total))?;
                }
                return Ok(value);
            }
            Err(RecvTimeoutError::Timeout) => {
                let reported = match progress {
                    Some((counter, _)) => match counter.read() {
                        (_, 0) => Ok(()),
                        now => tell(&mut told, now),
                    },
                    None => Ok(()),
                };
                if let Err(e) = reported.and_then(|()| py.check_signals()) {
                    if cancel.give_up() {
                        return Err(e);
                    }
                    // The files are going into place: the call ends as it was going to, and the
                    // interrupt comes right after it.
                    let value = py.detach(|| unless_exiting(rx.lock().expect("one waiter").recv()));
                    let _ = handle.join();
                    interrupt_again();
                    drop(e);
                    return value
                        .map_err(|_| {
                            PyRuntimeError::new_err(
                                "internal error in bumpmap (a bug; please report it): the worker ended",
                            )
                        })?
                        .map_err(no_threads);
                }
            }
            Err(RecvTimeoutError::Disconnected) => {
                let why = match handle.join() {
                    Err(payload) => payload
                        .downcast_ref::<&str>()
                        .map(|s| s.to_string())
                        .or_else(|| payload.downcast_ref::<String>().cloned())
                        .unwrap_or_else(|| "unknown panic".into()),
                    Ok(()) => "the worker ended without a result".into(),
                };
                return Err(PyRuntimeError::new_err(format!(
                    "internal error in bumpmap (a bug; please report it): {why}"
                )));
            }
        }
    }
}

/// Raises SIGINT's `KeyboardInterrupt` again at the interpreter's next chance: for a Ctrl-C that
/// came while the call was finishing, so it is not lost.
fn interrupt_again() {
    // SAFETY: `PyErr_SetInterrupt` only marks SIGINT as pending for the interpreter (it is
    // documented as callable from any thread, with or without the GIL).
    unsafe { pyo3::ffi::PyErr_SetInterrupt() };
}

/// The work running on worker threads, so the interpreter's exit can give up on it and wait for
/// it; and the thread that exit runs on, once it has begun.
static IN_FLIGHT: Mutex<Vec<Cancel>> = Mutex::new(Vec::new());
static IN_FLIGHT_ENDED: Condvar = Condvar::new();
static EXIT_THREAD: OnceLock<ThreadId> = OnceLock::new();

/// How long the interpreter's exit waits for running work: a step of a render or a bake, or a
/// whole map that tells no steps.
const EXIT_WAIT: Duration = Duration::from_secs(10);

/// One piece of work counted in [`IN_FLIGHT`] while it lives.
struct InFlight(Cancel);

impl InFlight {
    /// Counts the work of `cancel`; given up at once where the exit already began elsewhere.
    fn enter(cancel: &Cancel) -> InFlight {
        let mut list = IN_FLIGHT.lock().unwrap_or_else(PoisonError::into_inner);
        if exiting_elsewhere() {
            cancel.give_up();
        }
        list.push(cancel.clone());
        InFlight(cancel.clone())
    }
}

impl Drop for InFlight {
    fn drop(&mut self) {
        let mut list = IN_FLIGHT.lock().unwrap_or_else(PoisonError::into_inner);
        list.retain(|c| !Arc::ptr_eq(&c.0, &self.0.0));
        IN_FLIGHT_ENDED.notify_all();
    }
}

/// Whether the interpreter's exit has begun on another thread than this one. By then every
/// thread but the exiting one and daemon threads has been joined, so this thread is a daemon
/// thread; the exiting thread itself (an `atexit` function that runs after the module's) calls
/// in as before.
fn exiting_elsewhere() -> bool {
    EXIT_THREAD.get().is_some_and(|t| *t != std::thread::current().id())
}

/// Never returns: for a daemon thread during the interpreter's exit, which ends with the process.
fn park_for_ever() -> ! {
    loop {
        std::thread::park();
    }
}

/// `value`, on a thread that may take the GIL back; a daemon thread that waited through the
/// start of the interpreter's exit never returns instead. Taking the GIL back during the exit
/// ends the thread by a forced unwind through this crate's frames, which aborts the process
/// ("exception not rethrown"); Python 3.14 parks such threads itself.
fn unless_exiting<T>(value: T) -> T {
    if exiting_elsewhere() {
        park_for_ever();
    }
    value
}

/// Registered with `atexit`: gives up on every piece of work still running (a daemon thread's
/// call, or one whose caller was interrupted), waits up to [`EXIT_WAIT`] with the GIL released
/// for their threads to end (daemon threads' calls made after it never start), and removes
/// every staged file and folder not yet in place
/// ([`bumpmap_io::atomic::abandon_all`]). Without the wait, the process's exit tears down the
/// libraries a worker is inside — the Vulkan driver under a GPU render — and it crashes.
#[pyfunction]
pub fn abandon_all(py: Python<'_>) {
    let _ = EXIT_THREAD.set(std::thread::current().id());
    py.detach(|| {
        let deadline = std::time::Instant::now() + EXIT_WAIT;
        let mut list = IN_FLIGHT.lock().unwrap_or_else(PoisonError::into_inner);
        for work in list.iter() {
            work.give_up();
        }
        while !list.is_empty() {
            let left = deadline.saturating_duration_since(std::time::Instant::now());
            if left.is_zero() {
                break;
            }
            list = IN_FLIGHT_ENDED.wait_timeout(list, left).unwrap_or_else(PoisonError::into_inner).0;
        }
    });
    bumpmap_io::atomic::abandon_all();
}
