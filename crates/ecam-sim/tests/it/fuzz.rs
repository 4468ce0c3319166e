//! The fuzz harnesses of `ecam_sim::fuzz` on stable Rust: each target's
//! seed corpus (`fuzz/corpus/NAME/`), arbitrary bytes, and near-valid
//! inputs (seeds with a few edits). `PROPTEST_CASES` sets the case count;
//! `cargo fuzz run NAME` in `fuzz/` runs the same harness for longer.

use proptest::prelude::*;

#[path = "../../../../fuzz/seeds.rs"]
mod seeds;

/// Tokens of the scenario language for near-valid inputs.
const SCENARIO_TOKENS: &[&str] = &[
    "tick_us = ",
    "duration = ",
    "[table]",
    "[cam]",
    "[start]",
    "[master]",
    "[stop]",
    "points = ",
    "kind = ",
    "\"repeat\"",
    "\"one-shot\"",
    "moves = ",
    "single_turn = ",
    "update_us = ",
    "trace_every = ",
    "generator = ",
    "\"rotary-cut\"",
    "expr = ",
    "file = ",
    "[modulo]",
    "\"endless-positive\"",
    "[direction_guard]",
    "[registration]",
    "[cam_switches]",
    "[[cam_switches.switch]]",
    "[[plcopen]]",
    "MC_CamIn = {}",
    "MC_GearIn = { ratio = [1, 2] }",
    "MC_Phasing = ",
    "MC_MoveSuperimposed = ",
    "at_s = ",
];

#[test]
fn scenario_seeds() {
    for seed in seeds::corpus("scenario") {
        ecam_sim::fuzz::scenario(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn scenario_bytes(data in seeds::bytes()) {
        ecam_sim::fuzz::scenario(&data);
    }

    #[test]
    fn scenario_near_valid(data in seeds::near_valid("scenario", SCENARIO_TOKENS)) {
        ecam_sim::fuzz::scenario(&data);
    }
}
