//! A progress bar for long simulations, shown only to a person watching.
//!
//! Scripts and tests read stdout and stderr; a bar there would be noise, so
//! it appears only when stderr is a terminal and the run is long.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressStyle};

/// Runs shorter than this many ticks finish before a bar would be useful.
const MIN_TICKS: u64 = 200_000;

/// Advances a bar, if one is shown, in coarse steps (drawing is not free).
pub struct Progress {
    bar: Option<ProgressBar>,
    step: u64,
}

impl Progress {
    /// A bar over `total` ticks when stderr is a terminal and the run is long.
    pub fn new(total: u64) -> Self {
        let bar = (total >= MIN_TICKS && std::io::stderr().is_terminal()).then(|| {
            let bar = ProgressBar::new(total);
            if let Ok(style) = ProgressStyle::with_template(
                "{spinner} simulating [{bar:40}] {percent}% {pos}/{len} ticks, eta {eta}",
            ) {
                bar.set_style(style.progress_chars("=> "));
            }
            bar
        });
        Self {
            bar,
            step: (total / 1000).max(1),
        }
    }

    /// Reports that tick `done` has run.
    pub fn tick(&self, done: u64) {
        if let Some(bar) = &self.bar {
            if done.is_multiple_of(self.step) {
                bar.set_position(done);
            }
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
