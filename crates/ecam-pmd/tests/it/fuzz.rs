//! The fuzz harnesses of `ecam_pmd::fuzz` on stable Rust: each target's
//! seed corpus (`fuzz/corpus/NAME/`), arbitrary bytes, and near-valid
//! inputs (seeds with a few edits). `PROPTEST_CASES` sets the case count;
//! `cargo fuzz run NAME` in `fuzz/` runs the same harness for longer.

use proptest::prelude::*;

#[path = "../../../../fuzz/seeds.rs"]
mod seeds;

/// Tokens of the pmd script language for near-valid inputs.
const PMD_SCRIPT_TOKENS: &[&str] = &[
    "Axis ",
    "Define ",
    "SetBufferLength ",
    "WriteBuffer ",
    "SetCam ",
    "SetProfileMode ",
    "Update",
    "MoveTo ",
    "Tick ",
    "SetBreakpointValue ",
    "SetEventAction ",
    "0x",
    "0xFFFFFFFF",
    "CamCounts",
    "StartCam",
];

#[test]
fn pmd_script_seeds() {
    for seed in seeds::corpus("pmd_script") {
        ecam_pmd::fuzz::pmd_script(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn pmd_script_bytes(data in seeds::bytes()) {
        ecam_pmd::fuzz::pmd_script(&data);
    }

    #[test]
    fn pmd_script_near_valid(data in seeds::near_valid("pmd_script", PMD_SCRIPT_TOKENS)) {
        ecam_pmd::fuzz::pmd_script(&data);
    }
}
