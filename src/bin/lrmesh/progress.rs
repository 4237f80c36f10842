//! Progress of the steps of a command that take a while on a large mesh (reading, encoding,
//! decoding): a spinner with the elapsed time, which becomes a bar with a percentage and the
//! time left while the library reports a phase ([`lrmesh::progress`]). They draw on stderr
//! only when it is a terminal and `--quiet` is not given, so piped output and the tests stay
//! clean.

use std::rc::Rc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Set by `--quiet`: no progress at all.
static QUIET: AtomicBool = AtomicBool::new(false);

/// Silences every progress display of this run.
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

/// A spinner with `message` while `work` runs, a bar for each phase the library reports,
/// cleared afterwards.
pub fn step<T>(message: &str, work: impl FnOnce() -> T) -> T {
    let bar = spinner(message);
    if bar.is_hidden() {
        return work();
    }
    let reporter = Rc::new(Bar {
        bar: bar.clone(),
        step: message.to_string(),
    });
    let out = lrmesh::progress::report_to(reporter, work);
    bar.finish_and_clear();
    out
}

/// A spinner with `message` that ticks until finished; hidden when stderr is not a terminal
/// or with `--quiet`.
pub fn spinner(message: &str) -> ProgressBar {
    let target = match QUIET.load(Ordering::Relaxed) {
        true => ProgressDrawTarget::hidden(),
        false => ProgressDrawTarget::stderr(),
    };
    let bar = ProgressBar::with_draw_target(None, target);
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

/// The library's phases drawn on a step's bar: its name, a percentage and the time left.
struct Bar {
    bar: ProgressBar,
    step: String,
}

impl lrmesh::progress::Progress for Bar {
    fn phase(&self, name: &str, total: u64) {
        // Position and length first: the bar may be drawn between two of these calls, and
        // must not show the new phase with the last one's position.
        self.bar.set_position(0);
        self.bar.set_length(total.max(1));
        self.bar.reset_eta();
        let template = "{spinner} {msg} [{bar:24}] {percent:>3}% {elapsed} (about {eta} left)";
        if let Ok(style) = ProgressStyle::with_template(template) {
            self.bar.set_style(style.progress_chars("=> "));
        }
        self.bar.set_message(format!("{}: {name}", self.step));
    }

    fn advance(&self, done: u64) {
        self.bar.set_position(done);
    }
}
