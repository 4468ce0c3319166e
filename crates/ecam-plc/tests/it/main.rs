//! Integration tests of `ecam-plc`, one binary (one link) for the crate:
//! each module is one area, named after what it checks.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

mod decam_support;

mod arithmetic;
mod block_and_zone;
mod compare_contacts;
mod counters;
mod decam_errors;
mod decam_hostile;
mod decam_registers;
mod decam_starts;
mod ecamtbx_generators;
mod fuzz;
mod il_parser;
mod index_registers;
mod instructions;
mod parser_never_panics;
mod program_flow;
mod pulse_output_owner;
mod timers;
mod word_bits;
mod word_groups;

/// Property-test case count: `PROPTEST_CASES` when set (a long pass, e.g.
/// `PROPTEST_CASES=10000 cargo test`), else the module's own `default`.
fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}
