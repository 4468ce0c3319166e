//! The fuzz harnesses of `ecam_core::fuzz` on stable Rust: each target's
//! seed corpus (`fuzz/corpus/NAME/`), arbitrary bytes, and near-valid
//! inputs (seeds with a few edits). `PROPTEST_CASES` sets the case count;
//! `cargo fuzz run NAME` in `fuzz/` runs the same harness for longer.

use proptest::prelude::*;

#[path = "../../../../fuzz/seeds.rs"]
mod seeds;

/// Tokens of the table csv language for near-valid inputs.
const TABLE_CSV_TOKENS: &[&str] = &[
    "master,slave",
    ",velocity,acceleration,jerk",
    "master",
    "slave",
    "\n0,0",
    "1.5",
];

#[test]
fn table_csv_seeds() {
    for seed in seeds::corpus("table_csv") {
        ecam_core::fuzz::table_csv(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn table_csv_bytes(data in seeds::bytes()) {
        ecam_core::fuzz::table_csv(&data);
    }

    #[test]
    fn table_csv_near_valid(data in seeds::near_valid("table_csv", TABLE_CSV_TOKENS)) {
        ecam_core::fuzz::table_csv(&data);
    }
}

/// Tokens of the table json language for near-valid inputs.
const TABLE_JSON_TOKENS: &[&str] = &[
    "\"kind\":",
    "\"points\"",
    "\"uniform\"",
    "\"profile\"",
    "\"master\":",
    "\"slave\":",
    "\"sync\":",
    "\"low\":",
    "\"high\":",
    "\"law\":",
    "\"cycloid\"",
    "\"cam_counts\":",
    "\"values\":",
    "null",
];

#[test]
fn table_json_seeds() {
    for seed in seeds::corpus("table_json") {
        ecam_core::fuzz::table_json(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn table_json_bytes(data in seeds::bytes()) {
        ecam_core::fuzz::table_json(&data);
    }

    #[test]
    fn table_json_near_valid(data in seeds::near_valid("table_json", TABLE_JSON_TOKENS)) {
        ecam_core::fuzz::table_json(&data);
    }
}
