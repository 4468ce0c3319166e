//! A cam the engine has to stop mid-run (overflow) must say so and free its
//! slave, not leave it frozen and "running".
#![allow(clippy::unwrap_used, missing_docs)]

use ecam_core::PointTable;
use ecam_mc::{CamType, ECamData, McError, MotionController};

#[test]
fn an_overflowing_repeat_cam_ends_with_a_fault_and_frees_its_slave() {
    // Stroke 2^32 - 1 per 30000 counts: a master near i64::MAX needs a slave
    // position far beyond i64.
    let table =
        PointTable::from_pairs(&[(0, i64::from(i32::MIN)), (30000, i64::from(i32::MAX))]).unwrap();
    let mut mc = MotionController::new(2);
    mc.start_ecam(ECamData {
        master_axis: 0,
        slave_axis: 1,
        cam_type: CamType::Repeat,
        table,
    })
    .unwrap();
    assert_eq!(mc.fault(1).unwrap(), None);
    let before = mc.drive(0, 15000, 1).unwrap();
    mc.drive(0, i64::MAX, 1).unwrap();
    assert!(mc.fault(1).unwrap().is_some(), "the overflow is reported");
    assert!(!mc.ecam_running(1), "the faulted cam no longer runs");
    // The slave kept a position (no wrap-around garbage) and is free again.
    let held = mc.position(1).unwrap();
    assert!(held >= before, "{held} < {before}");
    mc.set_position(1, 0).unwrap();
    assert_eq!(mc.position(1).unwrap(), 0);
    assert!(matches!(mc.fault(7), Err(McError::NoSuchAxis { .. })));
}
