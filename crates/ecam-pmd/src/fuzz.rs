//! Fuzzing harnesses: one function per reader a user can feed, shared by
//! the cargo-fuzz targets in `fuzz/` and by the stable property tests in
//! `tests/it/fuzz.rs`, so both exercise the same code.
//!
//! Each takes arbitrary bytes and must return without panicking, whatever
//! the bytes; a panic is a bug in the reader.

use crate::ScriptRunner;
use crate::script::{Command, Parser};

/// Processor cycles one fuzzed script may run in all: `Tick N` accepts up
/// to [`ecam_core::limits::MAX_SIMULATED_TICKS`], far more than a fuzzer
/// can afford per input.
pub const TICK_BUDGET: u64 = 2_000;

/// Feeds `data` to the PMD script parser ([`Parser::parse_line`], line by
/// line) and runs it on a [`ScriptRunner`], `Tick`s cut down to
/// [`TICK_BUDGET`] cycles in all.
pub fn pmd_script(data: &[u8]) {
    let Ok(text) = core::str::from_utf8(data) else {
        return;
    };
    // A second parser sees the same lines (and `Define`s) as the runner's,
    // to find the `Tick`s before they run.
    let mut parser = Parser::new();
    let mut runner = ScriptRunner::new();
    let mut budget = TICK_BUDGET;
    for (index, line) in text.lines().enumerate() {
        let number = index.saturating_add(1);
        let report = match parser.parse_line(line) {
            Ok(Some(Command::Tick(n))) if n > budget => {
                let cut = format!("Tick {budget}");
                budget = 0;
                runner.run_line(number, &cut)
            }
            Ok(Some(Command::Tick(n))) => {
                budget -= n;
                runner.run_line(number, line)
            }
            _ => runner.run_line(number, line),
        };
        if let Some(report) = report {
            let _ = report.to_json();
        }
    }
}
