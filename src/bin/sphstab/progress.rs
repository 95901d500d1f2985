//! Progress bar on stderr for long runs (hidden when stderr is not a terminal or with --json).

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A bar over [0, 1] that draws only on an interactive stderr and only after a second.
pub fn bar(enabled: bool) -> ProgressBar {
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
    pb
}

/// Whether to show a bar: interactive stderr and no JSON on stdout.
pub fn wanted(json: bool) -> bool {
    !json && std::io::IsTerminal::is_terminal(&std::io::stderr())
}

/// Sets the fraction done, drawing only once a second has passed.
pub fn set(pb: &ProgressBar, fraction: f64) {
    if pb.elapsed().as_secs_f64() >= 1.0 {
        pb.set_position((fraction.clamp(0.0, 1.0) * 1000.0) as u64);
    }
}
