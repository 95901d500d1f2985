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

/// Set by [`interrupt`]: the analysis and the solver stop at their next wave vector, time step
/// or cell with [`Error::Cancelled`](crate::error::Error) while an [`Interruptible`] lives.
static INTERRUPTED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
/// Live [`Interruptible`] guards.
static ACTIVE: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// Asks every computation of this process to stop (an embedding interpreter's Ctrl-C: the
/// signal is process-wide, so is this). The CLI never calls it: Ctrl-C ends its process.
pub fn interrupt() {
    INTERRUPTED.store(true, std::sync::atomic::Ordering::SeqCst);
}

/// Err([`Error::Cancelled`](crate::error::Error)) once [`interrupt`] was called: checked per
/// wave vector by the analysis (an atomic load, nothing next to an eigenvalue problem).
pub fn interrupted() -> crate::error::Result<()> {
    match INTERRUPTED.load(std::sync::atomic::Ordering::Relaxed) {
        true => Err(crate::error::Error::Cancelled),
        false => Ok(()),
    }
}

/// A computation that [`interrupt`] may stop: while one lives, the interruption stands; when
/// the last one is dropped it is cleared, so the next computation starts afresh.
#[must_use]
pub struct Interruptible(());

impl Interruptible {
    /// Registers a computation.
    pub fn new() -> Self {
        ACTIVE.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        Self(())
    }
}

impl Default for Interruptible {
    fn default() -> Self {
        Self::new()
    }
}

impl Drop for Interruptible {
    fn drop(&mut self) {
        if ACTIVE.fetch_sub(1, std::sync::atomic::Ordering::SeqCst) == 1 {
            INTERRUPTED.store(false, std::sync::atomic::Ordering::SeqCst);
        }
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
