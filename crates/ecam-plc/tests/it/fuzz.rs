//! The fuzz harnesses of `ecam_plc::fuzz` on stable Rust: each target's
//! seed corpus (`fuzz/corpus/NAME/`), arbitrary bytes, and near-valid
//! inputs (seeds with a few edits). `PROPTEST_CASES` sets the case count;
//! `cargo fuzz run NAME` in `fuzz/` runs the same harness for longer.

use proptest::prelude::*;

#[path = "../../../../fuzz/seeds.rs"]
mod seeds;

/// Tokens of the il program language for near-valid inputs.
const IL_PROGRAM_TOKENS: &[&str] = &[
    "LD ",
    "OUT ",
    "DMOVP ",
    "DECAM ",
    "ECAMTBX ",
    "DPLSY ",
    "END",
    "X0",
    "Y0",
    "M8000",
    "D8511",
    "D65536",
    "K-99999999999",
    "HFFFFFFFFF",
    "E1e39",
    "C235",
    "Z0",
    "V7",
    "D8511Z0",
    "K4M8500Z1",
    "X377V0",
    "K8Y0",
    "BMOV ",
    "DFMOV ",
    "ZCP ",
    "K512",
];

#[test]
fn il_program_seeds() {
    for seed in seeds::corpus("il_program") {
        ecam_plc::fuzz::il_program(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn il_program_bytes(data in seeds::bytes()) {
        ecam_plc::fuzz::il_program(&data);
    }

    #[test]
    fn il_program_near_valid(data in seeds::near_valid("il_program", IL_PROGRAM_TOKENS)) {
        ecam_plc::fuzz::il_program(&data);
    }
}
