//! Progress spinners for the steps of a command that take a while on a large mesh (import,
//! construction, encoding). They draw on stderr only when it is a terminal, so piped output
//! and the tests stay clean. The library reports no progress itself: the steps are timed here.

use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A spinner with `message` and the elapsed time while `work` runs, cleared afterwards.
pub fn step<T>(message: &str, work: impl FnOnce() -> T) -> T {
    let bar = spinner(message);
    let out = work();
    bar.finish_and_clear();
    out
}

/// A spinner with `message` that ticks until finished; hidden when stderr is not a terminal.
pub fn spinner(message: &str) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    if bar.is_hidden() {
        return bar;
    }
    if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} {elapsed}") {
        bar.set_style(style);
    }
    bar.set_message(message.to_string());
    bar.enable_steady_tick(Duration::from_millis(100));
    bar
}
