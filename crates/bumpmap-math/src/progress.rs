//! Progress told from a parallel loop, and a loop that stops when the telling panics.
//!
//! A caller that gives up on long work (Ctrl-C in Python, a progress function that raises) has
//! nothing but the progress function to reach the work by: it unwinds from there. In a rayon
//! loop that unwinding would stop one item and let every other run to its end (a `join` finishes
//! both halves before it goes on with a panic), so the loop asks [`Told::stopped`] before each
//! item, skips the rest once the function has panicked, and goes on with that panic when the loop
//! is over ([`Told::finish`]).
//!
//! ```
//! use bumpmap_math::progress::Told;
//! use rayon::prelude::*;
//!
//! let progress = |done: usize, _total: usize| if done == 3 { std::panic::resume_unwind(Box::new("stop")) };
//! let told = Told::new(&progress, 1000);
//! let worked = std::sync::atomic::AtomicUsize::new(0);
//! let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
//!     (0..1000).into_par_iter().for_each(|_| {
//!         if told.stopped() {
//!             return;
//!         }
//!         worked.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
//!         told.step();
//!     });
//!     told.finish();
//! }));
//! assert!(outcome.is_err(), "the function's panic goes on");
//! assert!(worked.into_inner() < 1000, "the items after it were skipped");
//! ```
//!
//! What this module does not do: decide what a step is (the loop's items), or stop anything
//! itself.

use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind, resume_unwind};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// A progress function `(done, total)` told from a parallel loop of `total` steps.
pub struct Told<'a> {
    progress: &'a (dyn Fn(usize, usize) + Sync),
    total: usize,
    done: AtomicUsize,
    stopped: AtomicBool,
    unwound: Mutex<Option<Box<dyn Any + Send>>>,
}

impl<'a> Told<'a> {
    /// Nothing done yet of `total` steps.
    pub fn new(progress: &'a (dyn Fn(usize, usize) + Sync), total: usize) -> Self {
        Self { progress, total, done: AtomicUsize::new(0), stopped: AtomicBool::new(false), unwound: Mutex::new(None) }
    }

    /// Whether the function panicked: the loop's remaining steps are to be skipped.
    pub fn stopped(&self) -> bool {
        self.stopped.load(Ordering::Relaxed)
    }

    /// One more step done, told; a panic of the function is kept for [`Told::finish`].
    pub fn step(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if let Err(payload) = catch_unwind(AssertUnwindSafe(|| (self.progress)(done, self.total))) {
            self.stopped.store(true, Ordering::Relaxed);
            self.unwound.lock().unwrap_or_else(|e| e.into_inner()).get_or_insert(payload);
        }
    }

    /// After the loop: goes on with the function's panic, if it panicked.
    pub fn finish(self) {
        if let Some(payload) = self.unwound.into_inner().unwrap_or_else(|e| e.into_inner()) {
            resume_unwind(payload);
        }
    }
}
