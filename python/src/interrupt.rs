//! Long work off the interpreter: run on its own thread with the GIL released, while the calling
//! thread wakes every 50 ms to let Python handle signals, so Ctrl-C raises `KeyboardInterrupt`
//! at once instead of when the work ends.
//!
//! What it does not do: stop the work. An interrupted call returns at once; its thread runs on
//! to its end and its result is dropped. Work that writes files asks [`Cancel::is_set`] before
//! putting them in place, so an interrupted call leaves no file behind.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// Set when the caller gave up on the work (Ctrl-C).
#[derive(Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// Whether the caller gave up.
    pub fn is_set(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}

/// The worker's stack: as large as a main thread's, for the deep recursion some inputs bring.
const STACK_BYTES: usize = 64 << 20;

/// Runs `work` on its own thread with the GIL released and returns its result; a signal handler
/// that raises (Ctrl-C's `KeyboardInterrupt`) ends the wait at once, with the work's [`Cancel`]
/// set. A panic in the work is a `RuntimeError` naming it a bug.
pub fn run<T: Send + 'static>(py: Python<'_>, work: impl FnOnce(&Cancel) -> T + Send + 'static) -> PyResult<T> {
    let cancel = Cancel::default();
    let (tx, rx) = channel();
    // Waited on with the GIL released, from whichever thread the closure runs on.
    let rx = Mutex::new(rx);
    let worker_cancel = cancel.clone();
    let handle = std::thread::Builder::new()
        .name("bumpmap".into())
        .stack_size(STACK_BYTES)
        .spawn(move || {
            let _ = tx.send(work(&worker_cancel));
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a worker thread: {e}")))?;
    loop {
        match py.detach(|| rx.lock().expect("one waiter").recv_timeout(Duration::from_millis(50))) {
            Ok(value) => {
                let _ = handle.join();
                return Ok(value);
            }
            Err(RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals() {
                    cancel.0.store(true, Ordering::SeqCst);
                    return Err(e);
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
