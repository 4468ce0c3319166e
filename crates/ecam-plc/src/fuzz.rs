//! Fuzzing harnesses: one function per reader a user can feed, shared by
//! the cargo-fuzz targets in `fuzz/` and by the stable property tests in
//! `tests/it/fuzz.rs`, so both exercise the same code.
//!
//! Each takes arbitrary bytes and must return without panicking, whatever
//! the bytes; a panic is a bug in the reader.

use crate::Plc;

/// Scans a fuzzed program gets: enough to run each instruction, its edges
/// and a hardware tick, while keeping each input quick.
const SCANS: usize = 3;

/// Feeds `data` to the instruction-list parser ([`crate::Program::parse`]); a
/// program it accepts is loaded and scanned a few times.
pub fn il_program(data: &[u8]) {
    let Ok(text) = core::str::from_utf8(data) else {
        return;
    };
    let Ok(program) = crate::Program::parse(text, "fuzz.il") else {
        return;
    };
    let Ok(mut plc) = Plc::new(program) else {
        return;
    };
    for _ in 0..SCANS {
        let _ = plc.scan();
        plc.hardware_tick(100);
    }
}
