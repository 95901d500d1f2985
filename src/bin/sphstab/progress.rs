//! Progress bar on stderr for long runs (hidden when stderr is not a terminal or with --json):
//! the library's [`Progress`] drawn with indicatif.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use sphstab::progress::Progress;

/// A bar over [0, 1] that draws only on an interactive stderr and only after a second (a
/// clone draws the same bar).
#[derive(Clone)]
pub struct Bar(ProgressBar);

impl Bar {
    /// A bar, drawn when `enabled` (see [`wanted`]).
    pub fn new(enabled: bool) -> Self {
        let pb = ProgressBar::with_draw_target(
            Some(1000),
            if enabled {
                ProgressDrawTarget::stderr()
            } else {
                ProgressDrawTarget::hidden()
            },
        );
        if let Ok(style) =
            ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {percent}% (eta {eta})")
        {
            pb.set_style(style.progress_chars("=> "));
        }
        Self(pb)
    }

    /// Removes the bar from the terminal.
    pub fn finish(&self) {
        self.0.finish_and_clear();
    }
}

impl Progress for Bar {
    /// Sets the fraction done, drawing only once a second has passed.
    fn advance(&self, fraction: f64) {
        if self.0.elapsed().as_secs_f64() >= 1.0 {
            self.0
                .set_position((fraction.clamp(0.0, 1.0) * 1000.0) as u64);
        }
    }
}

/// Whether to show a bar: interactive stderr and no JSON on stdout.
pub fn wanted(json: bool) -> bool {
    !json && std::io::IsTerminal::is_terminal(&std::io::stderr())
}
