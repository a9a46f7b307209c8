//! Stopping a computation that is no longer wanted: the server's request past its time budget,
//! a client gone, a server shutting down. A [`Cancel`] is a shared flag; whoever runs a
//! computation on a thread puts the flag in force there with [`Cancel::run`], and the long loops
//! (the Monte Carlo's samples, the interpreter's blocks, the mill's levels, the thread-mill's
//! turns) call [`check`] and stop with [`Error::Cancelled`] once it is raised. Without a flag in
//! force (the CLI, Python) [`check`] costs one thread-local read and never stops anything.
//!
//! A loop that runs on rayon's threads takes the flag with [`current`] before it starts and
//! checks it there, since the thread-local is the calling thread's.

use crate::Error;
use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A flag that stops the computations it is in force for.
///
/// ```
/// use threadcheck::Cancel;
/// let stop = Cancel::new();
/// let r = stop.run(|| {
///     stop.raise();
///     threadcheck::check_cancelled()
/// });
/// assert!(r.is_err());
/// assert!(threadcheck::check_cancelled().is_ok()); // no flag in force here
/// ```
#[derive(Clone, Debug, Default)]
pub struct Cancel(Arc<AtomicBool>);

thread_local! {
    static CURRENT: RefCell<Option<Cancel>> = const { RefCell::new(None) };
}

impl Cancel {
    /// A flag not raised.
    pub fn new() -> Cancel {
        Cancel::default()
    }

    /// Raises the flag: every computation it is in force for stops at its next check.
    pub fn raise(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether the flag is raised.
    pub fn is_raised(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// Runs `f` on this thread with this flag in force, then restores the one before.
    pub fn run<R>(&self, f: impl FnOnce() -> R) -> R {
        let before = CURRENT.with(|c| c.replace(Some(self.clone())));
        let r = f();
        CURRENT.with(|c| *c.borrow_mut() = before);
        r
    }

    /// `Err(Error::Cancelled)` once the flag is raised.
    pub fn check(&self) -> Result<(), Error> {
        if self.is_raised() {
            Err(Error::Cancelled)
        } else {
            Ok(())
        }
    }
}

/// The flag in force on this thread, for a loop that hands its work to other threads.
pub fn current() -> Option<Cancel> {
    CURRENT.with(|c| c.borrow().clone())
}

/// `Err(Error::Cancelled)` when the flag in force on this thread is raised.
pub fn check() -> Result<(), Error> {
    CURRENT.with(|c| c.borrow().as_ref().map_or(Ok(()), Cancel::check))
}
