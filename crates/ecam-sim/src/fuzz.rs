//! Fuzzing harnesses: one function per reader a user can feed, shared by
//! the cargo-fuzz targets in `fuzz/` and by the stable property tests in
//! `tests/it/fuzz.rs`, so both exercise the same code.
//!
//! Each takes arbitrary bytes and must return without panicking, whatever
//! the bytes; a panic is a bug in the reader.

use std::path::Path;

use crate::{Scenario, simulate};

/// Where a fuzzed scenario says it lives: a directory that does not
/// exist, so relative table files it names are refused rather than read.
pub const BASE: &str = "/nonexistent/ecam-fuzz";

/// Longest run (in ticks) a fuzzed scenario is simulated for; longer ones
/// are only parsed, the run being the engine's to fuzz.
pub const MAX_TICKS: u64 = 2_000;

/// Feeds `data` to the scenario reader ([`Scenario::parse`]); a short
/// scenario it accepts is also simulated ([`simulate`]).
pub fn scenario(data: &[u8]) {
    let Ok(text) = core::str::from_utf8(data) else {
        return;
    };
    let Ok(scenario) = Scenario::parse(text, Path::new(BASE)) else {
        return;
    };
    let ticks = scenario.ticks();
    for t_us in [0, 1, u64::from(scenario.tick_us), scenario.duration_us] {
        let master = scenario.master_read_at(t_us);
        let _ = (scenario.master_input(master), scenario.start_input_at(t_us));
    }
    if ticks <= MAX_TICKS {
        let _ = simulate(&scenario, |_, _, _| Ok::<(), core::convert::Infallible>(()));
    }
}
