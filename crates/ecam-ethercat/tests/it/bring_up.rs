//! Bring-up: INIT → PRE-OP → SAFE-OP → OP with DC, CSP mapping checked.

use ecam_ethercat::cia402::DriveState;
use ecam_ethercat::emulation::{DriveBehaviour, EMULATED_NAME};

use crate::emulated;

#[test]
fn two_drives_reach_op_with_sync0_at_the_cycle_time() {
    let (mut segment, emulation) = emulated(2, DriveBehaviour::default());
    assert_eq!(segment.len(), 2);
    assert_eq!(segment.drive_name(0).as_deref(), Some(EMULATED_NAME));
    {
        let emulation = emulation.lock().unwrap();
        for esc in emulation.escs() {
            assert_eq!(esc.al_state(), 8, "OP");
            assert!(esc.sync0_active());
            assert_eq!(esc.sync0_cycle_ns(), 1_000_000);
        }
    }
    let report = segment.exchange().unwrap();
    assert_eq!(report.working_counter, 6);
    assert!(!report.working_counter_error());
    for drive in segment.drives() {
        assert_eq!(drive.state(), DriveState::SwitchOnDisabled);
    }
}
