//! The fuzz harnesses of `ecam_serve::fuzz` on stable Rust: each target's
//! seed corpus (`fuzz/corpus/NAME/`), arbitrary bytes, and near-valid
//! inputs (seeds with a few edits). `PROPTEST_CASES` sets the case count;
//! `cargo fuzz run NAME` in `fuzz/` runs the same harness for longer.

use proptest::prelude::*;

#[path = "../../../../fuzz/seeds.rs"]
mod seeds;

/// Tokens of the modbus request language for near-valid inputs.
const MODBUS_REQUEST_TOKENS: &[&str] = &[
    "\0\0\0\x06\x01",
    "\x03\0\0\0\x7d",
    "\x10",
    "\x0f",
    "\x17",
    "\x7f\x7f",
];

#[test]
fn modbus_request_seeds() {
    for seed in seeds::corpus("modbus_request") {
        ecam_serve::fuzz::modbus_request(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn modbus_request_bytes(data in seeds::bytes()) {
        ecam_serve::fuzz::modbus_request(&data);
    }

    #[test]
    fn modbus_request_near_valid(data in seeds::near_valid("modbus_request", MODBUS_REQUEST_TOKENS)) {
        ecam_serve::fuzz::modbus_request(&data);
    }
}

/// Tokens of the device json language for near-valid inputs.
const DEVICE_JSON_TOKENS: &[&str] = &[
    "\"D", "\"M", "\"X", "\"Y", "\"C", "8000", "200", "235", "\":", ":4", "true", "false", "70000",
    "-32768",
];

#[test]
fn device_json_seeds() {
    for seed in seeds::corpus("device_json") {
        ecam_serve::fuzz::device_json(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn device_json_bytes(data in seeds::bytes()) {
        ecam_serve::fuzz::device_json(&data);
    }

    #[test]
    fn device_json_near_valid(data in seeds::near_valid("device_json", DEVICE_JSON_TOKENS)) {
        ecam_serve::fuzz::device_json(&data);
    }
}

/// Tokens of the journal line language for near-valid inputs.
const JOURNAL_LINE_TOKENS: &[&str] = &[
    "D", "M", "X", "C", "Y", "D8000 ", "C199 ", "C235 ", "M500 ", "D512 ",
];

#[test]
fn journal_line_seeds() {
    for seed in seeds::corpus("journal_line") {
        ecam_serve::fuzz::journal_line(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn journal_line_bytes(data in seeds::bytes()) {
        ecam_serve::fuzz::journal_line(&data);
    }

    #[test]
    fn journal_line_near_valid(data in seeds::near_valid("journal_line", JOURNAL_LINE_TOKENS)) {
        ecam_serve::fuzz::journal_line(&data);
    }
}

/// Tokens of the journal open language for near-valid inputs.
const JOURNAL_OPEN_TOKENS: &[&str] = &["D", "M", "X", "C", "D200 ", "M500 ", "C100 ", "\0"];

#[test]
fn journal_open_seeds() {
    for seed in seeds::corpus("journal_open") {
        ecam_serve::fuzz::journal_open(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(60)))]

    #[test]
    fn journal_open_bytes(data in seeds::bytes()) {
        ecam_serve::fuzz::journal_open(&data);
    }

    #[test]
    fn journal_open_near_valid(data in seeds::near_valid("journal_open", JOURNAL_OPEN_TOKENS)) {
        ecam_serve::fuzz::journal_open(&data);
    }
}
