//! The text a run shows: status lines and the one JSON summary line of
//! `ecam ethercat run` and `ecam serve --ethercat` (keys may be added,
//! none removed or renamed: docs/ethercat.md).

use std::time::Duration;

use serde_json::{Value, json};

use crate::cia402::error_code_text;
use crate::dc::{ERROR_BUCKETS_US, Sync0Lock};
use crate::driver::Summary;
use crate::monitor::LineSnapshot;
use crate::rt::{BUCKETS_US, LatenessHistogram};

/// The lateness part of a summary: mean, worst, overruns and the
/// histogram as `[upper bound µs (null: open), count]` pairs.
pub fn lateness_json(lateness: &LatenessHistogram) -> Value {
    let histogram: Vec<Value> = lateness
        .counts
        .iter()
        .enumerate()
        .map(|(i, n)| json!([BUCKETS_US.get(i), n]))
        .collect();
    json!({
        "mean_us": lateness.mean().as_secs_f64() * 1e6,
        "max_us": lateness.max.as_secs_f64() * 1e6,
        "overruns": lateness.overruns,
        "histogram_us": histogram,
    })
}

/// The SYNC0 part: the configured shift, the frames' lead before the
/// SYNC0 edge (mean, least, most) and |lead − shift| per bucket.
pub fn sync0_json(lock: &Sync0Lock) -> Value {
    let us = |ns: i64| ns as f64 / 1000.0;
    let histogram: Vec<Value> = lock
        .error_counts
        .iter()
        .enumerate()
        .map(|(i, n)| json!([ERROR_BUCKETS_US.get(i), n]))
        .collect();
    json!({
        "shift_us": us(lock.shift_ns()),
        "frames": lock.frames,
        "lead_mean_us": us(lock.lead_mean_ns()),
        "lead_min_us": if lock.frames > 0 { Some(us(lock.lead_min_ns)) } else { None },
        "lead_max_us": if lock.frames > 0 { Some(us(lock.lead_max_ns)) } else { None },
        "error_histogram_us": histogram,
    })
}

/// The summary line's object.
pub fn summary_json(summary: &Summary, drives: usize, cycle_us: u32) -> Value {
    let c = &summary.counters;
    json!({
        "drives": drives,
        "cycles": c.cycles,
        "cycle_us": cycle_us,
        "virtual_master": c.virtual_master,
        "state": summary.state.map_or("stopped", |s| s.name()),
        "faults": summary.faults.iter().map(|(_, f)| f.to_string()).collect::<Vec<_>>(),
        "working_counter_errors": c.working_counter_errors,
        "exchange_errors": c.exchange_errors,
        "lost_cycles": c.lost_cycles,
        "lost_in_a_row_max": c.lost_in_a_row_max,
        "late_replies": summary.link.late_discarded,
        "send_errors": summary.link.send_errors,
        "recoveries": summary.recoveries,
        "stop_cycles": summary.stop_cycles,
        "actual": summary.actual,
        "scheduling": summary.setup.to_string(),
        "lateness": lateness_json(&summary.lateness),
        "sync0": summary.sync0.as_ref().map(sync0_json),
    })
}

/// One status line: time, master, line state, each drive (CiA 402 and
/// EtherCAT state, positions, following error, fault in words), lost
/// cycles.
pub fn status_line(s: &LineSnapshot, t: Duration) -> String {
    let mut line = format!(
        "t={:.3}s master={} {}",
        t.as_secs_f64(),
        s.counters.virtual_master,
        s.state.map_or("starting", |st| st.name())
    );
    if s.counters.lost_cycles > 0 {
        line.push_str(&format!(" lost={}", s.counters.lost_cycles));
    }
    for (i, d) in s.drives.iter().enumerate() {
        line.push_str(&format!(
            " | d{i} {} {} actual={} ferr={}",
            d.al_state.name(),
            d.state,
            d.actual,
            d.following_error
        ));
        if !d.reachable {
            line.push_str(&format!(" (no answer for {} cycles)", d.missed));
        } else if d.error_code != 0 {
            line.push_str(&format!(
                " (error {:#06x}: {})",
                d.error_code,
                error_code_text(d.error_code)
            ));
        }
    }
    line
}
