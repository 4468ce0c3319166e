//! A progress bar for runs that take a while, shown only to a person
//! watching: it appears on stderr once a run has taken more than
//! [`SHOW_AFTER`] and only when stderr is a terminal (scripts and tests,
//! reading pipes and files, never see it).

use std::cell::{Cell, OnceCell};
use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

/// Runs shorter than this finish before a bar would help.
const SHOW_AFTER: Duration = Duration::from_secs(1);
/// Calls between two looks at the clock (reading it is not free).
const CHECK_EVERY: u32 = 1024;

/// A bar over `total` steps of some run, drawn once the run is slow.
pub struct Progress {
    what: &'static str,
    total: u64,
    watched: bool,
    started: Instant,
    calls: Cell<u32>,
    bar: OnceCell<ProgressBar>,
}

impl Progress {
    /// A bar named `what` (`simulating`) over `total` steps.
    pub fn new(what: &'static str, total: u64) -> Self {
        Self {
            what,
            total,
            watched: std::io::stderr().is_terminal(),
            started: Instant::now(),
            calls: Cell::new(0),
            bar: OnceCell::new(),
        }
    }

    /// Reports that `done` steps have run.
    pub fn at(&self, done: u64) {
        if !self.watched {
            return;
        }
        let calls = self.calls.get().wrapping_add(1);
        self.calls.set(calls);
        if !calls.is_multiple_of(CHECK_EVERY) {
            return;
        }
        if self.bar.get().is_none() && self.started.elapsed() >= SHOW_AFTER {
            let bar = ProgressBar::new(self.total);
            if let Ok(style) = ProgressStyle::with_template(&format!(
                "{{spinner}} {} [{{bar:40}}] {{percent}}%, eta {{eta}}",
                self.what
            )) {
                bar.set_style(style.progress_chars("=> "));
            }
            let _ = self.bar.set(bar);
        }
        if let Some(bar) = self.bar.get() {
            bar.set_position(done);
        }
    }

    /// Removes the bar, if one was drawn.
    pub fn finish(&self) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
    }
}
