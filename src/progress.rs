//! Progress of long work (a study, a time integration): one small trait the caller implements —
//! the binary draws a progress bar with it — instead of a closure signature per function.
//!
//! Work reports the fraction done with [`Progress::advance`] (possibly from several threads:
//! the studies run their cells in parallel) and asks [`Progress::cancelled`] between steps or
//! cells; when that says stop, the work ends with [`Error::Cancelled`](crate::error::Error).
//! `()` ignores both; a closure `|fraction| …` reports and never cancels.

/// Where long work reports how far it got and learns whether to stop.
pub trait Progress: Sync {
    /// The fraction of the work done, in [0, 1].
    fn advance(&self, fraction: f64);

    /// Whether the work should stop now (checked between steps or cells). Default: never.
    fn cancelled(&self) -> bool {
        false
    }
}

/// No progress reporting.
impl Progress for () {
    fn advance(&self, _fraction: f64) {}
}

/// A closure told the fraction done.
impl<F: Fn(f64) + Sync> Progress for F {
    fn advance(&self, fraction: f64) {
        self(fraction)
    }
}

/// Counts finished items of `total` from several threads and reports the fraction to
/// `progress` every `every` items (and at the last one).
pub(crate) struct Counter<'a> {
    progress: &'a dyn Progress,
    done: std::sync::atomic::AtomicUsize,
    total: usize,
    every: usize,
}

impl<'a> Counter<'a> {
    /// A counter of `total` items reporting every `every` (≥ 1) items.
    pub(crate) fn new(progress: &'a dyn Progress, total: usize, every: usize) -> Self {
        Self {
            progress,
            done: std::sync::atomic::AtomicUsize::new(0),
            total,
            every: every.max(1),
        }
    }

    /// `n` more items are finished; Err([`crate::error::Error::Cancelled`]) if the work should
    /// stop.
    pub(crate) fn add(&self, n: usize) -> crate::error::Result<()> {
        let d = self.done.fetch_add(n, std::sync::atomic::Ordering::Relaxed) + n;
        if d / self.every != (d - n) / self.every || d == self.total {
            self.progress.advance(d as f64 / self.total.max(1) as f64);
        }
        if self.progress.cancelled() {
            return Err(crate::error::Error::Cancelled);
        }
        Ok(())
    }
}
