//! The thread pool the package's work runs on: one per process.
//!
//! rayon's global pool does not survive `fork`: the child inherits its registry but none of its
//! threads, so the child's first parallel loop waits for ever (a `ProcessPoolExecutor` with the
//! default start method on Linux, after the parent has called bumpmap once). The package keeps
//! a pool of its own instead, built on first use in each process (a child sees a new process
//! id and builds a fresh one), and runs every call inside it ([`crate::interrupt::run`]).
//!
//! What it does not do: make a `fork` taken while another thread of the parent is inside a
//! bumpmap call safe (no library's locks are; Python warns about forking with threads), or
//! carry the GPU adapter across a fork (a child opens its own).

use std::sync::{Arc, Mutex, PoisonError};

use rayon::{ThreadPool, ThreadPoolBuilder};

/// This process's pool, with the process it was built in.
static POOL: Mutex<Option<(u32, Arc<ThreadPool>)>> = Mutex::new(None);

/// The pool of this process, built on first use here; its threads have `stack_bytes` of stack.
pub fn current(stack_bytes: usize) -> Result<Arc<ThreadPool>, rayon::ThreadPoolBuildError> {
    let pid = std::process::id();
    let mut slot = POOL.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some((owner, pool)) = &*slot
        && *owner == pid
    {
        return Ok(pool.clone());
    }
    let pool =
        Arc::new(ThreadPoolBuilder::new().thread_name(|i| format!("bumpmap-{i}")).stack_size(stack_bytes).build()?);
    if let Some((_, inherited)) = slot.replace((pid, pool.clone())) {
        // The parent's pool, inherited by a fork: its threads do not exist in this process, so
        // nothing may wait on them; it is left as it is.
        std::mem::forget(inherited);
    }
    Ok(pool)
}
