//! The PLCopen-shaped face: MC_CamTableSelect / MC_CamIn / MC_CamOut.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::Zoom;
use ecam_engine::plcopen::{CamIn, CamInStartMode, CamOut, CamTableSelect, McCamAxis};

fn table() -> PointTable {
    PointTable::from_pairs(&[(0, 0), (400, 100), (1000, 600)]).unwrap()
}

#[test]
fn relative_master_starts_the_table_at_its_beginning() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.select(CamTableSelect {
        periodic: true,
        master_absolute: false,
        slave_absolute: false,
    })
    .unwrap();
    axis.set_slave_position(50).unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    let s = axis.tick(12_345, 1000);
    assert!(s.active && s.in_sync && s.busy);
    assert_eq!(s.output.slave, 50);
    assert_eq!(axis.tick(12_745, 1000).output.slave, 150);
    // Periodic with a stroke: one full table later the slave has moved 600.
    let s = axis.tick(13_345, 1000);
    assert!(s.end_of_profile);
    assert_eq!(s.output.slave, 650);
}

#[test]
fn absolute_offsets_and_scaling() {
    let mut axis = McCamAxis::new(table()).unwrap();
    let params = CamIn {
        master_offset: 400,
        slave_offset: 7,
        master_scaling: Zoom::new(1, 2).unwrap(),
        slave_scaling: Zoom::new(2, 1).unwrap(),
        start_mode: CamInStartMode::Absolute,
    };
    axis.cam_in(&params).unwrap();
    // master 1200 → table input 600 + 400 = 1000 → table 600 → ×2 + 7.
    assert_eq!(axis.tick(1200, 1_000_000).output.slave, 1207);
}

#[test]
fn non_periodic_table_ends_the_coupling() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.select(CamTableSelect {
        periodic: false,
        master_absolute: false,
        slave_absolute: true,
    })
    .unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    assert!(axis.tick(0, 1_000_000).active);
    let s = axis.tick(1000, 1_000_000);
    assert!(s.end_of_profile);
    assert!(!s.active && !s.busy);
    assert_eq!(s.output.slave, 600);
    assert_eq!(axis.tick(3000, 1_000_000).output.slave, 600);
}

#[test]
fn ramp_in_reports_in_sync_when_done_and_cam_out_holds() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.cam_in(&CamIn {
        start_mode: CamInStartMode::RampIn {
            distance: NonZeroU64::new(100).unwrap(),
        },
        ..CamIn::default()
    })
    .unwrap();
    assert!(!axis.tick(500, 1_000_000).in_sync);
    assert!(!axis.tick(550, 1_000_000).in_sync);
    let s = axis.tick(600, 1_000_000);
    assert!(s.in_sync);
    assert!(axis.cam_in(&CamIn::default()).is_err());
    axis.cam_out(CamOut);
    let held = axis.tick(700, 1_000_000);
    assert!(!held.active && !held.in_sync);
    assert_eq!(held.output.slave, s.output.slave);
}
