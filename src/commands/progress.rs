//! A run of many programs' progress on standard error: drawn by `indicatif` once the run has
//! taken a second, on the command line only and only when standard error is a terminal (the
//! caller says so with [`Request::progress`](super::Request)); nothing anywhere else.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// How long a run goes before its bar appears: a quick run prints nothing. The environment's
/// `THREADCHECK_PROGRESS_AFTER` (seconds, `0` at once) sets another wait.
const QUIET_FOR: Duration = Duration::from_secs(1);

/// The wait before the bar: `THREADCHECK_PROGRESS_AFTER`'s seconds where it holds a number of
/// them, else a second.
fn quiet_for() -> Duration {
    std::env::var("THREADCHECK_PROGRESS_AFTER")
        .ok()
        .and_then(|s| s.trim().parse::<f64>().ok())
        .and_then(|s| Duration::try_from_secs_f64(s).ok())
        .unwrap_or(QUIET_FOR)
}

/// The bar of one run, safe to advance from the threads that verify its programs.
pub(crate) struct Progress {
    bar: Option<ProgressBar>,
    start: Instant,
    quiet_for: Duration,
    shown: AtomicBool,
}

impl Progress {
    /// A bar over `total` programs, drawn only when `wanted` (the command line's standard error
    /// is a terminal).
    pub(crate) fn new(wanted: bool, total: usize) -> Progress {
        let bar = wanted.then(|| {
            let bar = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::hidden());
            if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} programs, {elapsed} {msg}")
            {
                bar.set_style(style);
            }
            bar
        });
        Progress { bar, start: Instant::now(), quiet_for: quiet_for(), shown: AtomicBool::new(false) }
    }

    /// One more program done.
    pub(crate) fn inc(&self) {
        let Some(bar) = &self.bar else { return };
        if self.start.elapsed() >= self.quiet_for && !self.shown.swap(true, Ordering::Relaxed) {
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        bar.inc(1);
    }

    /// The run is over: the bar leaves the terminal's line clear for the summary.
    pub(crate) fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
