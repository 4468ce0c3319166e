//! Bad tables and bad parameters: 6781/6782/6783 in the error register and
//! the flags, the running cam left unchanged, everything cleared once fixed.
#![allow(clippy::unwrap_used)]

use crate::decam_support::Rig;

const GOOD: &[(i32, i32)] = &[(0, 0), (500, 500), (1000, 1000)];

fn last_code(r: &Rig) -> Option<u16> {
    r.errors.last().map(|e| e.code)
}

#[test]
fn master_not_increasing_is_6782_with_the_section_number() {
    let mut r = Rig::new(&[(0, 0), (500, 10), (400, 20), (1000, 0)]);
    r.start(1);
    assert_eq!(last_code(&r), Some(6782));
    assert_eq!(r.reg(2), 2, "error register: the bad section");
    assert!(r.flag(3) && r.flag(5) && !r.flag(4));
    assert!(!r.cam.is_running(), "a bad table does not start");
    assert!(
        r.errors[0].message.contains("D2048"),
        "{}",
        r.errors[0].message
    );
}

#[test]
fn equal_masters_are_a_table_error_too() {
    let mut r = Rig::new(&[(0, 0), (0, 10)]);
    r.scan();
    assert_eq!(last_code(&r), Some(6782));
    assert_eq!(r.reg(2), 1);
}

#[test]
fn section_count_out_of_range_is_6783() {
    for count in [0i16, 1, 513, -4] {
        let mut r = Rig::new(GOOD);
        r.set(38, count);
        r.scan();
        assert_eq!(last_code(&r), Some(6783), "{count} sections");
        assert_eq!(r.reg(2), 6783);
        assert!(r.flag(3) && r.flag(5));
    }
}

#[test]
fn unwritten_points_after_the_table_are_a_table_error() {
    let mut r = Rig::new(GOOD);
    r.set(38, 5);
    r.scan();
    // Points 3 and 4 are zeros: master not increasing at point 3.
    assert_eq!(last_code(&r), Some(6782));
    assert_eq!(r.reg(2), 3);
}

#[test]
fn a_table_that_does_not_fit_below_d8512_is_6783() {
    use ecam_plc::decam::{Decam, DecamOperands, MasterOperand};
    use ecam_plc::{Device, Devices};
    let ops = DecamOperands::new(
        MasterOperand::Register(10),
        8400,
        Device::M(0),
        0,
        Device::Y(4),
    )
    .unwrap();
    let mut cam = Decam::new(ops);
    let mut dev = Devices::new();
    dev.set_word(8438, 30).unwrap(); // 8440 + 120 > 8512
    let err = cam.execute(true, &mut dev, 0).unwrap_err();
    assert_eq!(err.code, 6783);
    assert_eq!(dev.word(8402).unwrap(), 6783);
}

#[test]
fn zero_zoom_is_6781() {
    let mut r = Rig::new(GOOD);
    r.set(3, 0b100);
    r.set(30, 2);
    r.set(29, 0);
    r.start(1);
    assert_eq!(last_code(&r), Some(6781));
    assert_eq!(r.reg(2), 6781);
    assert!(r.flag(3) && r.flag(4) && !r.flag(5));
    assert!(!r.cam.is_running());
    r.set(3, 0b1000);
    r.set(24, 0);
    r.set(23, 1);
    r.scan();
    assert_eq!(r.reg(2), 6781);
}

#[test]
fn delay_and_start_position_together_is_6781() {
    let mut r = Rig::new(GOOD);
    r.set(3, 0b11);
    r.scan();
    assert_eq!(last_code(&r), Some(6781));
}

#[test]
fn sync_parameters_are_checked_when_sync_is_enabled() {
    let mut r = Rig::new(GOOD);
    r.set(8, 300);
    r.scan();
    assert!(r.errors.is_empty(), "not checked while sync is off");
    r.set(4, 1);
    r.scan();
    assert_eq!(last_code(&r), Some(6781));
    r.set(8, 7);
    r.set_d(9, 500);
    r.set_d(11, 400);
    r.scan();
    assert_eq!(r.errors.len(), 2);
    assert_eq!(last_code(&r), Some(6781));
    r.set_d(11, 500);
    r.scan();
    assert_eq!(r.errors.len(), 2);
    assert_eq!(r.reg(2), 0);
}

#[test]
fn the_running_cam_is_left_unchanged_and_errors_clear_when_corrected() {
    let mut r = Rig::new(GOOD);
    r.start(1);
    r.run_to(300, 10);
    assert_eq!(r.pulses(), 300);
    // Corrupt the table while running: point 2's master below point 1's.
    r.set_d(48, 100);
    r.run_to(600, 10);
    assert_eq!(last_code(&r), Some(6782));
    assert_eq!(r.reg(2), 2);
    // Flags say what happens: the cam runs on with its last good table
    // (bit 8), so bits 3-5 ("E-cam stop running") stay off.
    assert!(r.flag(8), "flags {:#b}", r.flags());
    assert!(!r.flag(3) && !r.flag(4) && !r.flag(5));
    assert!(r.cam.is_running());
    assert_eq!(r.pulses(), 600, "still following the table it started with");
    // Corrected: error register and flags clear; the cam never stopped.
    r.set_d(48, 1000);
    let before = r.errors.len();
    r.run_to(800, 10);
    assert_eq!(r.errors.len(), before);
    assert_eq!(r.reg(2), 0);
    assert!(!r.flag(3) && !r.flag(5) && !r.flag(8));
    assert_eq!(r.pulses(), 800);
}

#[test]
fn a_cam_stopped_with_a_bad_block_shows_the_error_flags() {
    let mut r = Rig::new(GOOD);
    r.start(1);
    r.run_to(300, 10);
    r.set_d(48, 100);
    r.run_to(400, 10);
    assert!(r.flag(8) && !r.flag(3));
    r.set(5, 0);
    r.run(2, 0);
    assert!(!r.cam.is_running());
    assert!(
        r.flag(3) && r.flag(5) && !r.flag(8),
        "flags {:#b}",
        r.flags()
    );
}

#[test]
fn a_start_waits_for_the_block_to_be_corrected() {
    let mut r = Rig::new(&[(0, 0), (0, 10)]);
    r.start(1);
    r.run(10, 0);
    assert!(!r.cam.is_running());
    r.set_table(GOOD);
    r.run(11, 0);
    assert!(r.cam.is_running());
    assert!(r.flag(0) && r.flag(6));
    assert_eq!(r.reg(2), 0);
}

#[test]
fn a_table_changed_while_running_takes_over_at_the_next_seam() {
    let mut r = Rig::new(GOOD);
    r.start(1);
    r.run_to(100, 10);
    r.set_table(&[(0, 0), (1000, 2000)]);
    r.run_to(990, 10);
    assert_eq!(
        r.pulses(),
        990,
        "the running cam keeps its table to the seam"
    );
    r.run_to(1000, 10);
    assert_eq!(r.pulses(), 1000, "no step at the seam");
    r.run_to(1100, 10);
    assert_eq!(r.pulses(), 1200, "the new table from the seam on");
    r.set(5, 0);
    r.run(2, 0);
    r.set(5, 1);
    // 1000 pulses owed at 20 per tick (200 kHz).
    r.run(60, 0);
    assert_eq!(
        r.pulses(),
        2200,
        "restarted with the new table (absolute): its value at master 100 is 200"
    );
}

#[test]
fn a_start_edge_while_the_block_is_bad_is_ignored() {
    use crate::decam_support::START;
    let mut r = Rig::new(GOOD);
    r.set(3, 0b10_0000); // external start
    r.start(1);
    r.set(38, 0);
    r.scan();
    r.set_bit(START, true);
    r.run(10, 10);
    assert!(!r.cam.is_running());
    r.set(38, 3);
    r.run(10, 10);
    assert!(!r.cam.is_running(), "the edge was not remembered");
    r.set_bit(START, false);
    r.tick(0);
    r.set_bit(START, true);
    r.tick(0);
    assert!(r.cam.is_running());
}

#[test]
fn sync_terminal_on_the_cams_own_outputs_is_6781_and_leaves_them_alone() {
    // The rig's cam drives Y0 (pulses) and Y4 (direction). A sync terminal
    // on either would overwrite that output's level with the sync signal.
    for own in [0i16, 4] {
        let mut r = Rig::new(GOOD);
        r.start(1);
        r.run_to(300, 10);
        r.set(8, own);
        r.set_d(9, 0);
        r.set_d(11, 1_000_000);
        r.set(4, 1);
        r.scan();
        assert_eq!(last_code(&r), Some(6781), "sync on Y{own}");
        assert_eq!(r.reg(2), 6781);
        assert!(r.cam.is_running(), "the running cam is left unchanged");
        r.run_to(400, 10);
        assert_eq!(r.pulses(), 400);
        // Corrected to Y7: accepted, and Y7 shows the window.
        r.set(8, 7);
        r.scan();
        assert_eq!(r.reg(2), 0);
        r.run_to(500, 10);
        assert!(r.y(7));
    }
}

#[test]
fn a_cam_the_engine_must_stop_shows_an_error_not_a_completed_cycle() {
    // Noncyclic forever (offset 14 = 0xFFFF), slave zoom 65535:1, a steep
    // 1-count table: the commanded slave position leaves the 64-bit range
    // after about 65000 master counts, and the engine stops the cam.
    let mut r = Rig::new(&[(0, 0), (1, i32::MAX)]);
    r.set(3, 1 << 3); // slave zoom
    r.set(23, 1); // denominator
    r.set(24, -1); // numerator 65535
    r.set(14, -1); // 0xFFFF: forever
    r.start(2);
    assert!(r.cam.is_running());
    r.run(200, 1000);
    assert!(!r.cam.is_running(), "the engine stopped the cam");
    assert!(r.flag(3), "bit 3: something is error, E-cam stopped");
    assert!(!r.flag(9), "not a completed cycle");
    assert!(!r.flag(0), "not re-armed");
    assert!(
        r.errors
            .iter()
            .any(|e| e.code == 6781 && e.message.contains("overflow")),
        "{:?}",
        r.errors
    );
    // The fault is reported once, not every scan after.
    let reported = r.errors.len();
    r.run(50, 0);
    assert_eq!(r.errors.len(), reported);
    // A new start clears it.
    r.set(5, 0);
    r.run(10, 0);
    r.set_table(GOOD);
    r.set(3, 0);
    r.start(2);
    assert!(!r.flag(3));
}
