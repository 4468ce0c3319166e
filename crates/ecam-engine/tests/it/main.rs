//! Integration tests of `ecam-engine`, one binary (one link) for the crate:
//! each module is one area, named after what it checks.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

mod cam_out;
mod couplings;
mod couplings_safe_motion;
mod doc001_repeat;
mod doc002_profile;
mod doc003_decam;
mod master_sources;
mod missed_activation;
mod offsets_on_the_fly;
mod plcopen;
mod plcopen_peer;
mod plcopen_peer_couplings;
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

/// Ticks of `tick_us` a pulse output at `hz` needs to send `backlog`
/// pulses, and a margin: a drain loop's bound that any backlog fits.
fn ticks_to_drain(backlog: i64, hz: i64, tick_us: u32) -> u64 {
    let per_second = u128::from(hz.unsigned_abs().max(1));
    let ticks =
        u128::from(backlog.unsigned_abs()) * 1_000_000 / (per_second * u128::from(tick_us.max(1)));
    u64::try_from(ticks).unwrap_or(u64::MAX).saturating_add(100)
}
