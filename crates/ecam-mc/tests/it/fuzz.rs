//! The fuzz harnesses of `ecam_mc::fuzz` on stable Rust: each target's
//! seed corpus (`fuzz/corpus/NAME/`), arbitrary bytes, and near-valid
//! inputs (seeds with a few edits). `PROPTEST_CASES` sets the case count;
//! `cargo fuzz run NAME` in `fuzz/` runs the same harness for longer.

use proptest::prelude::*;

#[path = "../../../../fuzz/seeds.rs"]
mod seeds;

/// Tokens of the mc script language for near-valid inputs.
const MC_SCRIPT_TOKENS: &[&str] = &[
    "Axes ",
    "ECAMTable ",
    "StartECAM ",
    "StopECAM ",
    "SetSingleTurn ",
    "SetUserUnit ",
    "SetCommandPosition ",
    "MoveTo ",
    "Tick ",
    "Repeat",
    "Periodic",
    "GetCommandPosition ",
    "Trace ",
    "/dev/null",
];

#[test]
fn mc_script_seeds() {
    for seed in seeds::corpus("mc_script") {
        ecam_mc::fuzz::mc_script(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn mc_script_bytes(data in seeds::bytes()) {
        ecam_mc::fuzz::mc_script(&data);
    }

    #[test]
    fn mc_script_near_valid(data in seeds::near_valid("mc_script", MC_SCRIPT_TOKENS)) {
        ecam_mc::fuzz::mc_script(&data);
    }
}
