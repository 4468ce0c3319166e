//! The fuzz harnesses of `ecam_design::fuzz` on stable Rust: each target's
//! seed corpus (`fuzz/corpus/NAME/`), arbitrary bytes, and near-valid
//! inputs (seeds with a few edits). `PROPTEST_CASES` sets the case count;
//! `cargo fuzz run NAME` in `fuzz/` runs the same harness for longer.

use proptest::prelude::*;

#[path = "../../../../fuzz/seeds.rs"]
mod seeds;

/// Tokens of the generator toml language for near-valid inputs.
const GENERATOR_TOML_TOKENS: &[&str] = &[
    "points = ",
    "expr = ",
    "from = ",
    "to = ",
    "master = ",
    "slave = ",
    "sync = ",
    "ratio = ",
    "\"5/3\"",
    "resolution = ",
    "pulses = ",
    "[[key]]",
    "[[segment]]",
    "[start]",
    "velocity = ",
    "\"poly-5\"",
    "continuous = ",
    "law = ",
    "true",
    "\"x\"",
];

#[test]
fn generator_toml_seeds() {
    for seed in seeds::corpus("generator_toml") {
        ecam_design::fuzz::generator_toml(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn generator_toml_bytes(data in seeds::bytes()) {
        ecam_design::fuzz::generator_toml(&data);
    }

    #[test]
    fn generator_toml_near_valid(data in seeds::near_valid("generator_toml", GENERATOR_TOML_TOKENS)) {
        ecam_design::fuzz::generator_toml(&data);
    }
}

/// Tokens of the generator json language for near-valid inputs.
const GENERATOR_JSON_TOKENS: &[&str] = &[
    "\"points\":",
    "\"expr\":",
    "\"master\":",
    "\"params\":",
    "\"generator\":",
    "\"keys\":",
    "\"ratio\":",
    "\"5/3\"",
    "null",
    "true",
];

#[test]
fn generator_json_seeds() {
    for seed in seeds::corpus("generator_json") {
        ecam_design::fuzz::generator_json(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn generator_json_bytes(data in seeds::bytes()) {
        ecam_design::fuzz::generator_json(&data);
    }

    #[test]
    fn generator_json_near_valid(data in seeds::near_valid("generator_json", GENERATOR_JSON_TOKENS)) {
        ecam_design::fuzz::generator_json(&data);
    }
}

/// Tokens of the expression language for near-valid inputs.
const EXPRESSION_TOKENS: &[&str] = &[
    "x", "pi", "tau", "e", "sin(", "cos(", "tan(", "exp(", "ln(", "sqrt(", "abs(", ")", "^", "/",
    "*", "-", "+", "1e", "E-", "(", "<", "==",
];

#[test]
fn expression_seeds() {
    for seed in seeds::corpus("expression") {
        ecam_design::fuzz::expression(&seed);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn expression_bytes(data in seeds::bytes()) {
        ecam_design::fuzz::expression(&data);
    }

    #[test]
    fn expression_near_valid(data in seeds::near_valid("expression", EXPRESSION_TOKENS)) {
        ecam_design::fuzz::expression(&data);
    }
}
