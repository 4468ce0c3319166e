//! What the tick benchmark and the side-by-side example share: the
//! scenario (tables, axis settings, queries) and the minimal loop that is
//! the honest limit for one axis-tick on this machine.

// Each includer uses a different part of this module.
#![allow(dead_code)]

pub mod minimal;

use ecam_core::PointTable;
use ecam_engine::{AxisConfig, CamAxis, Coupling, SlaveAlign, SyncWindow, TickInput, Zoom};

/// Points of every benchmark table: 512 sections, like a full DECAM block.
pub const POINTS: usize = 513;
/// Master counts between two table points.
pub const STEP: i64 = 2000;
/// Master counts the benchmark master moves per tick (a 100 µs tick).
pub const MASTER_PER_TICK: i64 = 13;
/// Tick length in µs.
pub const DT_US: u32 = 100;

/// A repeat cam with a stroke: 10,000 pulses per cycle with a sine ripple.
pub fn stroke_table() -> Option<PointTable> {
    table(|u| 10_000.0 * u - 800.0 * (u * std::f64::consts::TAU).sin())
}

/// A periodic cam (slave back where it started): a cycloidal lift and return.
pub fn periodic_table() -> Option<PointTable> {
    table(|u| 5_000.0 * (1.0 - (u * std::f64::consts::TAU).cos()))
}

fn table(slave: impl Fn(f64) -> f64) -> Option<PointTable> {
    let last = (POINTS - 1) as f64;
    let pairs: Vec<(i64, i64)> = (0..POINTS)
        .map(|i| (i as i64 * STEP, slave(i as f64 / last).round() as i64))
        .collect();
    PointTable::from_pairs(&pairs).ok()
}

/// The settings of axis `i`: a repeat cam with both zooms and two sync
/// windows, so every step of the tick does real work.
pub fn config(i: usize) -> AxisConfig {
    AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        slave_align: SlaveAlign::Relative,
        master_zoom: Zoom::new(7, 3).unwrap_or_default(),
        slave_zoom: Zoom::new(5, 4).unwrap_or_default(),
        sync_windows: [
            SyncWindow::new(1000, 2000),
            SyncWindow::new(10_000 + i as i64, 20_000),
            SyncWindow::OFF,
            SyncWindow::OFF,
        ],
        ..AxisConfig::default()
    }
}

/// `n` engaged axes on `table`, each with [`config`].
pub fn axes(table: &PointTable, n: usize) -> Vec<CamAxis<PointTable>> {
    (0..n)
        .filter_map(|i| {
            let mut axis = CamAxis::new(table.clone(), config(i)).ok()?;
            axis.arm().ok()?;
            let _ = axis.tick(&TickInput::at(0, DT_US));
            Some(axis)
        })
        .collect()
}

/// `n` minimal-loop axes with the same settings, engaged at master 0.
pub fn minimal_axes(table: &PointTable, n: usize) -> Vec<minimal::MinimalAxis> {
    (0..n)
        .filter_map(|i| minimal::MinimalAxis::engage(table.clone(), &config(i), 0, 0))
        .collect()
}
