//! Progress of the long phases of reading and encoding, for a caller that shows it (the
//! `lrmesh` command draws a bar with a percentage and the time left). The library draws
//! nothing: a caller runs work under [`report_to`], and each long phase announces itself with
//! [`phase`] and its work done with [`advance`]. Without a reporter both cost a thread-local
//! read. Only the calling thread reports; helper threads of a parallel phase do not.

use std::cell::RefCell;
use std::rc::Rc;

/// What a caller does with the progress of the work it runs under [`report_to`].
pub trait Progress {
    /// A phase starts: `name` says what it does, `total` how many units of work it has.
    fn phase(&self, name: &str, total: u64);
    /// `done` units of the current phase are finished (from 0 to its `total`).
    fn advance(&self, done: u64);
}

thread_local! {
    static REPORTER: RefCell<Option<Rc<dyn Progress>>> = const { RefCell::new(None) };
}

/// Runs `work` with `reporter` told of the phases it goes through on this thread (the
/// reporter in place before comes back afterwards, also when `work` panics).
pub fn report_to<T>(reporter: Rc<dyn Progress>, work: impl FnOnce() -> T) -> T {
    struct Restore(Option<Rc<dyn Progress>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take();
            REPORTER.with(|r| *r.borrow_mut() = previous);
        }
    }
    let _restore = Restore(REPORTER.with(|r| r.borrow_mut().replace(reporter)));
    work()
}

/// This thread's reporter, if any.
fn reporter() -> Option<Rc<dyn Progress>> {
    REPORTER.with(|r| r.borrow().clone())
}

/// Announces a phase of `total` units of work to this thread's reporter, if any.
pub fn phase(name: &str, total: u64) {
    if let Some(reporter) = reporter() {
        reporter.phase(name, total);
    }
}

/// Tells this thread's reporter that `done` units of the current phase are finished.
pub fn advance(done: u64) {
    if let Some(reporter) = reporter() {
        reporter.advance(done);
    }
}

/// Units of work between two reports in a loop: [`tick`] reports when `i` is a multiple.
pub const TICK: usize = 1 << 16;

/// Reports `i` units done when `i` is a multiple of [`TICK`]: cheap enough for every
/// iteration of a loop over triangles or vertices.
#[inline(always)]
pub fn tick(i: usize) {
    if i % TICK == 0 {
        advance(i as u64);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;

    #[derive(Default)]
    struct Log(RefCell<Vec<(String, u64)>>);

    impl Log {
        fn take(&self) -> Vec<(String, u64)> {
            self.0.take()
        }
    }

    impl Progress for Log {
        fn phase(&self, name: &str, total: u64) {
            self.0.borrow_mut().push((name.to_string(), total));
        }
        fn advance(&self, done: u64) {
            self.0.borrow_mut().push(("advance".to_string(), done));
        }
    }

    #[test]
    fn reports_reach_the_reporter_only_while_it_runs() {
        let log = Rc::new(Log::default());
        phase("before", 1);
        let out = report_to(log.clone(), || {
            phase("work", 3 * TICK as u64);
            for i in 0..3 * TICK {
                tick(i);
            }
            7
        });
        phase("after", 1);
        assert_eq!(out, 7);
        let seen = log.take();
        let expected = [
            ("work", 3 * TICK),
            ("advance", 0),
            ("advance", TICK),
            ("advance", 2 * TICK),
        ];
        let expected: Vec<_> = expected
            .iter()
            .map(|&(n, d)| (n.to_string(), d as u64))
            .collect();
        assert_eq!(seen, expected);
    }
}
