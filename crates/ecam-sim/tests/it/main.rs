//! Integration tests of `ecam-sim`, one binary (one link) for the crate:
//! each module is one area, named after what it checks.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

mod couplings;
mod fuzz;

/// Property-test case count: `PROPTEST_CASES` when set (a long pass, e.g.
/// `PROPTEST_CASES=10000 cargo test`), else the module's own `default`.
fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}
