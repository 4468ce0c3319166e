//! Fuzzing harnesses: one function per reader a user can feed, shared by
//! the cargo-fuzz targets in `fuzz/` and by the stable property tests in
//! `tests/it/fuzz.rs`, so both exercise the same code.
//!
//! Each takes arbitrary bytes and must return without panicking, whatever
//! the bytes; a panic is a bug in the reader.

use crate::script::Script;

/// Where a fuzzed script says it lives: a directory that does not exist,
/// so relative table paths it names are refused rather than read.
pub const SCRIPT_PATH: &str = "/nonexistent/ecam-fuzz/fuzz.mc";

/// Feeds `data` to the MC script parser ([`Script::parse`]). Scripts are
/// parsed, not run: a run may write trace files.
pub fn mc_script(data: &[u8]) {
    let Ok(text) = core::str::from_utf8(data) else {
        return;
    };
    match Script::parse(text, SCRIPT_PATH) {
        Ok(script) => {
            let _ = script.axis_count();
            for line in script.lines() {
                let _ = line.command.name();
            }
        }
        Err(error) => {
            let _ = error.to_string();
        }
    }
}
