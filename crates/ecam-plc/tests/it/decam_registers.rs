//! Every register offset of the DECAM block, driven through the library API.
#![allow(clippy::unwrap_used)]

use crate::decam_support::{Rig, START};
use ecam_plc::Device;
use ecam_plc::decam::MasterOperand;

const TRIANGLE: &[(i32, i32)] = &[(0, 0), (500, 100), (1000, 0)];
const LINE: &[(i32, i32)] = &[(0, 0), (1000, 100)];
const ONE_TO_ONE: &[(i32, i32)] = &[(0, 0), (1000, 1000)];

#[test]
fn offset_0_version_and_39_table_offset() {
    let mut r = Rig::new(TRIANGLE);
    r.scan();
    assert_eq!(r.reg(0), 5200);
    assert_eq!(r.reg(39), 40);
}

#[test]
fn cyclic_start_sets_flags_and_follows_the_table() {
    let mut r = Rig::new(TRIANGLE);
    r.start(1);
    assert!(r.flag(0), "bit 0 init done");
    assert!(r.flag(6), "bit 6 cyclic");
    assert!(!r.flag(7));
    r.run_to(250, 10);
    assert_eq!(r.pulses(), 50);
    assert_eq!(r.reg_d(19), 50);
    assert_eq!(r.reg_d(21), 50);
    assert_eq!(r.reg_d(25), 250);
    assert_eq!(r.reg_d(27), 250);
    assert!(r.y(4), "direction output on while moving forward");
    r.run_to(750, 10);
    assert_eq!(r.pulses(), 50);
    assert!(!r.y(4), "direction output off while moving backward");
}

#[test]
fn bit_1_cycle_complete_is_latched_until_the_program_resets_it() {
    let mut r = Rig::new(TRIANGLE);
    r.start(1);
    r.run_to(990, 10);
    assert!(!r.flag(1));
    r.run_to(1010, 10);
    assert!(r.flag(1));
    let cleared = r.flags() & !2;
    r.set(1, cleared as i16);
    r.run_to(1500, 10);
    assert!(!r.flag(1), "stays reset until the next cycle completes");
    r.run_to(2010, 10);
    assert!(r.flag(1));
    assert!(r.flag(0), "bit 0 stays on in cyclic mode");
}

#[test]
fn offset_5_zero_and_other_values_stop_immediately() {
    for stop in [0, 3, -1] {
        let mut r = Rig::new(ONE_TO_ONE);
        r.start(1);
        r.run_to(300, 10);
        r.set(5, stop);
        r.tick(10);
        let held = r.pulses();
        r.run_to(600, 10);
        assert_eq!(r.pulses(), held, "start register {stop} stops the slave");
        assert!(!r.flag(6) && !r.flag(0));
        assert!(!r.cam.is_running());
    }
}

#[test]
fn restart_needs_the_start_register_off_for_100_us() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.tick_us = 50;
    r.start(1);
    r.run_to(100, 10);
    r.set(5, 0);
    r.tick(0);
    r.set(5, 1);
    r.tick(0); // off for only 50 µs: refused
    r.run_to(200, 10);
    assert!(!r.cam.is_running());
    assert_eq!(r.pulses(), 100);
    r.set(5, 0);
    for _ in 0..2 {
        r.tick(0); // off for 100 µs
    }
    r.set(5, 1);
    r.tick(0);
    assert!(r.cam.is_running());
    assert!(r.flag(6));
}

#[test]
fn switching_cyclic_to_noncyclic_without_stop_is_refused() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.start(1);
    r.run_to(100, 10);
    r.set(5, 2);
    r.run(20, 10);
    assert!(!r.cam.is_running());
    assert!(!r.flag(6) && !r.flag(7));
    r.set(5, 0);
    r.run(2, 0);
    r.set(5, 2);
    r.run(1, 0);
    assert!(r.cam.is_running());
    assert!(r.flag(7));
}

#[test]
fn offsets_6_7_limit_the_output_frequency() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.set_d(6, 1000);
    r.start(1);
    r.tick(500); // the slave should be at 500 at once
    assert!(r.pulses() <= 1);
    assert!(r.flag(2), "bit 2: pulse output delayed");
    r.run(4900, 0); // 0.49 s at 1 kHz
    assert!((489..=491).contains(&r.pulses()), "{}", r.pulses());
    r.run(200, 0);
    assert_eq!(r.pulses(), 500);
    assert!(!r.flag(2));
}

#[test]
fn offsets_6_7_above_200k_mean_200k() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.set_d(6, 300_000);
    r.start(1);
    r.tick(900);
    assert!(r.pulses() <= 20, "at most 200 kHz x 100 us: {}", r.pulses());
    r.run(50, 0);
    assert_eq!(r.pulses(), 900);
}

#[test]
fn offsets_8_to_12_sync_output_is_on_exactly_inside_the_window() {
    let mut r = Rig::new(&[(0, 0), (50000, 5000)]);
    r.set(8, 7);
    r.set_d(9, 200);
    r.set_d(11, 300);
    r.set(4, 1);
    r.start(1);
    r.run_to(150, 10);
    for _ in 150..350 {
        r.tick(1);
        let inside = (200..=300).contains(&r.master);
        assert_eq!(r.y(7), inside, "Y7 at master {}", r.master);
        assert_eq!(r.flag(10), inside, "bit 10 at master {}", r.master);
    }
}

#[test]
fn sync_output_disabled_leaves_the_y_alone_but_bit_10_shows_the_window() {
    let mut r = Rig::new(&[(0, 0), (50000, 5000)]);
    r.set(8, 7);
    r.set_d(9, 200);
    r.set_d(11, 300);
    r.start(1);
    r.run_to(250, 10);
    assert!(!r.y(7));
    assert!(r.flag(10));
    // Enabled while running (offset 4 may change during execution).
    r.set(4, 1);
    r.tick(0);
    assert!(r.y(7));
    // Moving the sync output turns the old one off.
    r.set(8, 6);
    r.scan();
    r.tick(0);
    assert!(!r.y(7) && r.y(6));
    // Stopping releases it.
    r.set(5, 0);
    r.tick(0);
    assert!(!r.y(6));
}

#[test]
fn sync_window_compares_the_zoomed_master() {
    let mut r = Rig::new(&[(0, 0), (50000, 5000)]);
    r.set(3, 0b100); // master zoom
    r.set(30, 2);
    r.set(29, 1);
    r.set(8, 7);
    r.set_d(9, 400);
    r.set_d(11, 600);
    r.set(4, 1);
    r.start(1);
    r.run_to(199, 1);
    assert!(!r.y(7));
    r.tick(1);
    assert!(r.y(7));
    assert_eq!(r.reg_d(25), 400);
    assert_eq!(r.reg_d(27), 200);
    r.run_to(300, 1);
    assert!(r.y(7));
    r.tick(1);
    assert!(!r.y(7));
}

#[test]
fn offsets_23_24_29_30_zoom_master_and_slave() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.set(3, 0b1100);
    r.set(29, 1); // master den
    r.set(30, 2); // master num
    r.set(23, 1); // slave den
    r.set(24, 3); // slave num
    r.start(1);
    r.run_to(400, 2);
    assert_eq!(r.reg_d(27), 400, "master before zoom");
    assert_eq!(r.reg_d(25), 800, "master after zoom");
    assert_eq!(r.reg_d(21), 800, "slave before zoom");
    assert_eq!(r.reg_d(19), 2400, "slave after zoom");
    assert_eq!(r.pulses(), 2400);
}

#[test]
fn zoom_registers_are_ignored_without_their_function_bits() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.set(30, 2);
    r.set(24, 3);
    r.start(1);
    r.run_to(400, 10);
    assert_eq!(r.pulses(), 400);
}

#[test]
fn offset_14_repeat_count_runs_n_plus_1_cycles() {
    let mut r = Rig::new(LINE);
    r.set(14, 2);
    r.start(2);
    assert!(r.flag(7), "bit 7 noncyclic");
    r.run_to(2950, 10);
    assert!(r.cam.is_running());
    assert_eq!(r.pulses(), 295);
    r.run_to(5000, 10);
    assert_eq!(r.pulses(), 300, "three cycles of 100 pulses, then it holds");
    assert!(!r.cam.is_running());
    assert!(r.flag(9), "bit 9: stopped at the end of its cycles");
    assert!(!r.flag(0), "bit 0 cleared when the noncyclic cam ends");
    assert!(r.flag(1));
}

#[test]
fn offset_14_ffff_runs_forever() {
    let mut r = Rig::new(LINE);
    r.set(14, -1);
    r.start(2);
    r.run_to(10_000, 10);
    assert!(r.cam.is_running());
    assert_eq!(r.pulses(), 1000);
}

#[test]
fn offsets_13_15_16_delay_start_counts_master_pulses() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.set(3, 0b1);
    r.set_d(15, 300);
    r.start(2);
    r.run_to(100, 10);
    assert_eq!(r.pulses(), 0);
    assert_eq!(r.reg(13), 200, "offset 13: delay pulses remaining");
    r.run_to(500, 10);
    assert_eq!(
        r.pulses(),
        200,
        "engaged exactly 300 counts after the start"
    );
    assert_eq!(r.reg(13), 0);
}

#[test]
fn delay_is_ignored_by_the_cyclic_cam() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.set(3, 0b1);
    r.set_d(15, 300);
    r.start(1);
    r.run_to(100, 10);
    assert_eq!(r.pulses(), 100);
}

#[test]
fn offsets_17_18_start_at_a_master_position() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.set(3, 0b10);
    r.set_d(17, 400);
    r.start(2);
    r.run_to(300, 10);
    assert_eq!(r.pulses(), 0);
    assert_eq!(r.reg(13), 100, "offset 13: counts to the start position");
    r.run_to(700, 10);
    assert_eq!(r.pulses(), 300);
}

#[test]
fn function_bit_6_starts_from_registers_27_28_and_19_20() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.master = 5000;
    r.set(3, 0b100_0000);
    r.set_d(27, 250);
    r.set_d(19, 1000);
    r.start(1);
    r.run(10, 10);
    assert_eq!(r.reg_d(27), 350);
    assert_eq!(r.reg_d(19), 1100);
    assert_eq!(r.pulses(), 100, "no jump at the start, then 100 pulses");
}

#[test]
fn function_bit_5_waits_for_a_rising_edge_of_s3() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.set(3, 0b10_0000);
    r.start(1);
    assert!(r.flag(0), "initialised, waiting for the start signal");
    r.run_to(200, 10);
    assert_eq!(r.pulses(), 0);
    r.set_bit(START, true);
    r.run_to(400, 10);
    assert!(r.cam.is_running());
    assert_eq!(
        r.pulses(),
        400,
        "cyclic: the slave takes the table value of the master"
    );
}

#[test]
fn noncyclic_external_start_rearms_after_5_ms() {
    let mut r = Rig::new(LINE);
    r.set(3, 0b10_0000);
    r.start(2);
    r.set_bit(START, true);
    r.run_to(1000, 10);
    r.tick(10);
    assert!(!r.cam.is_running());
    assert_eq!(r.pulses(), 100);
    assert!(!r.flag(0), "bit 0 cleared at the end of the run");
    // A start 2 ms after the end is too soon: ignored.
    r.set_bit(START, false);
    r.run(10, 0);
    r.set_bit(START, true);
    r.run(10, 10);
    assert!(!r.cam.is_running());
    assert_eq!(r.pulses(), 100);
    // After 5 ms the cam is ready again (bit 0) and the next edge runs it.
    r.run(40, 0);
    assert!(r.flag(0));
    r.set_bit(START, false);
    r.tick(0);
    r.set_bit(START, true);
    r.tick(0);
    r.run(50, 10);
    assert!(r.cam.is_running());
    assert_eq!(
        r.pulses(),
        150,
        "second run: relative to where the slave stood"
    );
}

#[test]
fn offset_4_bit_1_stops_at_the_end_of_the_cycle() {
    let mut r = Rig::new(LINE);
    r.start(1);
    r.run_to(300, 10);
    r.set(4, 0b10);
    r.run_to(1500, 10);
    assert_eq!(r.pulses(), 100, "held at the cycle end");
    assert!(!r.cam.is_running());
    assert!(r.flag(9));
    // Restart needs the start register through 0.
    r.set(4, 0);
    r.run(5, 10);
    assert!(!r.cam.is_running());
    r.set(5, 0);
    r.run(2, 0);
    r.set(5, 1);
    r.run(1, 0);
    assert!(r.cam.is_running());
    assert!(!r.flag(9));
}

#[test]
fn offset_4_bit_1_set_before_the_start_runs_one_cycle() {
    // Noncyclic, engaging on the table start: the stop is not "on the table
    // end" there; the cam runs its cycle and stops at its end.
    let mut r = Rig::new(LINE);
    r.set(4, 0b10);
    r.start(2);
    r.run(5, 0);
    assert!(r.cam.is_running(), "still waiting to run its cycle");
    r.run_to(1500, 10);
    assert_eq!(r.pulses(), 100, "one whole cycle, held at its end");
    assert!(!r.cam.is_running());
    assert!(r.flag(9));
}

#[test]
fn m8145_stops_the_output_immediately() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.start(1);
    r.run_to(300, 10);
    r.set_bit(Device::M(8145), true);
    r.tick(10);
    let held = r.pulses();
    assert!(held <= 310);
    r.run_to(600, 10);
    assert_eq!(r.pulses(), held);
    assert!(!r.cam.is_running());
    r.set_bit(Device::M(8145), false);
    r.run(5, 10);
    assert!(
        !r.cam.is_running(),
        "a stopped cam restarts only through the start register"
    );
}

#[test]
fn busy_flag_m8147_while_the_cam_runs() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.start(1);
    r.tick(0);
    assert!(r.dev.m(8147).unwrap());
    r.set(5, 0);
    r.tick(0);
    r.tick(0);
    assert!(!r.dev.m(8147).unwrap());
}

#[test]
fn time_base_master_sets_bit_11() {
    let mut r = Rig::with_master(LINE, MasterOperand::TimeBase(1));
    r.start(1);
    assert!(r.flag(11));
    // The time base read 0 on the start tick: 500 ticks of 100 µs later, 500.
    r.run(500, 0);
    assert_eq!(r.reg_d(27), 500);
    assert_eq!(r.pulses(), 50);
}

#[test]
fn counter_master() {
    let mut r = Rig::with_master(ONE_TO_ONE, MasterOperand::Counter(235));
    r.start(1);
    for c in (0..=300).step_by(10) {
        r.dev.set_counter(235, c).unwrap();
        r.tick(0);
    }
    assert_eq!(r.pulses(), 300);
}

#[test]
fn disabling_the_instruction_stops_the_cam() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.start(1);
    r.run_to(200, 10);
    r.enabled = false;
    r.run(20, 10);
    assert_eq!(r.pulses(), 200);
    assert!(!r.flag(6) && !r.flag(0));
    // Enabled again with the start register still 1: it starts again.
    r.enabled = true;
    r.run(2, 0);
    assert!(r.cam.is_running());
}

#[test]
fn pulse_counter_equals_slave_position() {
    use proptest::prelude::*;
    let config = ProptestConfig::with_cases(crate::cases(24));
    proptest!(config, |(steps in proptest::collection::vec(-40i64..40, 1..300))| {
        let mut r = Rig::new(&[(0, 0), (300, 250), (600, -100), (1000, 0)]);
        r.start(1);
        for s in steps {
            r.tick(s);
            if !r.flag(2) {
                prop_assert_eq!(r.pulses(), r.reg_d(19));
            }
        }
    });
}

#[test]
fn offsets_32_to_37_are_reserved_and_left_alone() {
    let mut r = Rig::new(ONE_TO_ONE);
    for offset in 32..=37 {
        r.set(offset, 1000 + offset as i16);
    }
    r.set(39, 7); // the table offset is always 40: the instruction rewrites it
    r.start(1);
    r.run_to(500, 10);
    for offset in 32..=37 {
        assert_eq!(r.reg(offset), 1000 + offset as i16);
    }
    assert_eq!(r.reg(39), 40);
    assert_eq!(r.pulses(), 500);
}

#[test]
fn offset_31_is_the_table_end_action() {
    // 1: the table runs one pass (midCAMend) and the cam stops at its end,
    // even as a cyclic cam.
    let mut r = Rig::new(ONE_TO_ONE);
    r.set(31, 1);
    r.start(1);
    r.run_to(1500, 10);
    r.run(5, 0);
    assert_eq!(r.pulses(), 1000, "stopped at the table end");
    assert!(!r.cam.is_running());
    assert!(r.flag(9), "current cycle complete");
    // Anything but 0 or 1 is a parameter error naming the offset.
    let mut r = Rig::new(ONE_TO_ONE);
    r.set(31, 2);
    r.start(1);
    assert_eq!(r.errors.last().map(|e| e.code), Some(6781));
    assert!(!r.cam.is_running());
}

#[test]
fn offset_2_and_error_flags_stay_clear_on_a_good_block() {
    let mut r = Rig::new(ONE_TO_ONE);
    r.set(2, 1234);
    r.start(1);
    assert_eq!(r.reg(2), 0);
    assert_eq!(r.flags() & 0b11_1000, 0);
    assert!(r.errors.is_empty());
}

#[test]
fn a_run_that_ends_under_the_frequency_limit_sends_every_pulse_it_owes() {
    // Noncyclic once, 5000 pulses over 1000 counts, at most 10 kHz (one
    // pulse per 100 µs tick): the master finishes the table long before
    // the pulses do. The run ends only once the last one has gone out.
    let mut r = Rig::new(&[(0, 0), (1000, 5000)]);
    r.set_d(6, 10_000);
    r.start(2);
    r.run_to(1200, 100);
    assert!(r.cam.is_running(), "still sending what it owes");
    assert!(r.flag(2), "pulse output delayed");
    assert!(!r.flag(9));
    r.run(6000, 0);
    assert_eq!(r.pulses(), 5000, "no pulse lost");
    assert!(!r.cam.is_running());
    assert!(r.flag(9) && !r.flag(2));
}
