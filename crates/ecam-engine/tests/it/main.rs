//! Integration tests of `ecam-engine`, one binary (one link) for the crate:
//! each module is one area, named after what it checks.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

mod cam_out;
mod doc001_repeat;
mod doc002_profile;
mod doc003_decam;
mod master_sources;
mod missed_activation;
mod offsets_on_the_fly;
mod plcopen;
mod plcopen_reference;
mod properties;
mod ramp_in_limits;
mod safe_motion;
mod scaling_on_the_fly;
mod signed_scaling;
mod starts_stops;
mod table_switch;

/// Property-test case count: `PROPTEST_CASES` when set (a long pass, e.g.
/// `PROPTEST_CASES=10000 cargo test`), else the module's own `default`.
fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}
