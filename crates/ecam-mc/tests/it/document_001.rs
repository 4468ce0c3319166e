//! Document 001's examples: Repeat and Periodic types, single-turn masters,
//! the initial slave position, incomplete tables, the user-unit rule.
#![allow(clippy::unwrap_used, missing_docs)]

use ecam_core::PointTable;
use ecam_mc::{CamType, ECamData, McError, MotionController, SingleTurn, UserUnit};

const MASTER: usize = 0;
const SLAVE: usize = 1;

fn doc_table() -> PointTable {
    PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)]).unwrap()
}

fn start(mc: &mut MotionController, cam_type: CamType, table: PointTable) {
    mc.start_ecam(ECamData {
        master_axis: MASTER,
        slave_axis: SLAVE,
        cam_type,
        table,
    })
    .unwrap();
}

/// Drives the master from its position to `to` in steps of 100 counts
/// (unwrapped; a single-turn axis wraps on its own) and gives the slave
/// positions at every multiple of `every`, keyed by the unwrapped master.
fn sweep(mc: &mut MotionController, from: i64, to: i64, every: i64) -> Vec<(i64, i64)> {
    let step = if to >= from { 100 } else { -100 };
    let mut seen = Vec::new();
    let mut m = from;
    loop {
        let slave = mc.drive(MASTER, m, SLAVE).unwrap();
        if m % every == 0 {
            seen.push((m, slave));
        }
        if m == to {
            return seen;
        }
        m += step;
    }
}

#[test]
fn repeat_type_is_continuous_at_every_seam() {
    let mut mc = MotionController::new(2);
    start(&mut mc, CamType::Repeat, doc_table());
    let seen = sweep(&mut mc, 0, 90000, 5000);
    let expected = [
        500, 1000, 1500, 1250, 1000, 1500, // first cycle 0..25000
        2000, 2500, 3000, 2750, 2500, 3000, // second: +1500
        3500, 4000, 4500, 4250, 4000, 4500, // third: +3000
        5000,
    ];
    assert_eq!(seen.iter().map(|s| s.1).collect::<Vec<_>>(), expected);
    // Back down: the offset is taken away again.
    let back = sweep(&mut mc, 90000, -10000, 10000);
    assert_eq!(
        back.iter().map(|s| s.1).collect::<Vec<_>>(),
        [
            5000, 4000, 4500, 3500, 2500, 3000, 2000, 1000, 1500, 500, -500
        ]
    );
}

#[test]
fn periodic_type_jumps_back_at_the_seam() {
    let mut mc = MotionController::new(2);
    start(&mut mc, CamType::Periodic, doc_table());
    let seen = sweep(&mut mc, 0, 60000, 5000);
    // Each cycle repeats 500..2000; just past the seam the slave is back near 500.
    for (m, s) in &seen {
        let in_cycle = m % 30000;
        if in_cycle == 0 {
            assert!(*s == 500 || *s == 2000, "master {m}: {s}");
            continue;
        }
        let expected = [500, 1000, 1500, 1250, 1000, 1500][(in_cycle / 5000) as usize];
        assert_eq!(*s, expected, "master {m}");
    }
    assert_eq!(mc.drive(MASTER, 30100, SLAVE).unwrap(), 510);
}

#[test]
fn repeat_and_periodic_agree_when_the_ends_are_equal() {
    let table = PointTable::from_pairs(&[(0, 0), (5000, 800), (10000, 0)]).unwrap();
    let mut a = MotionController::new(2);
    let mut b = MotionController::new(2);
    start(&mut a, CamType::Repeat, table.clone());
    start(&mut b, CamType::Periodic, table);
    assert_eq!(sweep(&mut a, 0, 35000, 500), sweep(&mut b, 0, 35000, 500));
}

#[test]
fn normal_type_holds_the_end_values() {
    let mut mc = MotionController::new(2);
    start(&mut mc, CamType::Normal, doc_table());
    let seen = sweep(&mut mc, 0, 45000, 15000);
    assert_eq!(
        seen,
        [(0, 500), (15000, 1250), (30000, 2000), (45000, 2000)]
    );
    let back = sweep(&mut mc, 45000, -5000, 5000);
    assert_eq!(back.last(), Some(&(-5000, 500)));
}

#[test]
fn single_turn_master_repeat_preserves_the_slave_across_wraps() {
    let mut mc = MotionController::new(2);
    mc.set_single_turn(MASTER, Some(SingleTurn::new(30000).unwrap()))
        .unwrap();
    start(&mut mc, CamType::Repeat, doc_table());
    assert_eq!(mc.position(SLAVE).unwrap(), 500);
    let seen = sweep(&mut mc, 0, 75000, 5000);
    let slaves: Vec<i64> = seen.iter().map(|s| s.1).collect();
    assert_eq!(
        slaves,
        [
            500, 1000, 1500, 1250, 1000, 1500, 2000, 2500, 3000, 2750, 2500, 3000, 3500, 4000,
            4500, 4250
        ]
    );
    // The master's own position stayed within the turn.
    assert_eq!(mc.position(MASTER).unwrap(), 15000);
}

#[test]
fn single_turn_start_at_20000_with_slave_at_minus_1500_begins_at_minus_2000() {
    let mut mc = MotionController::new(2);
    mc.set_single_turn(MASTER, Some(SingleTurn::new(30000).unwrap()))
        .unwrap();
    mc.set_position(MASTER, 20000).unwrap();
    mc.set_position(SLAVE, -1500).unwrap();
    start(&mut mc, CamType::Repeat, doc_table());
    // Table value 1000 at 20000; equivalents 1000 - 1500k: -500, -2000, …;
    // the nearest to -1500 is -2000.
    assert_eq!(mc.position(SLAVE).unwrap(), -2000);
    let seen = sweep(&mut mc, 20000, 40000, 5000);
    assert_eq!(
        seen.iter().map(|s| s.1).collect::<Vec<_>>(),
        [-2000, -1500, -1000, -500, 0]
    );
}

#[test]
fn incomplete_table_is_extended_with_its_end_values() {
    let table = PointTable::from_pairs(&[(5000, 1000), (20000, 4000), (25000, 3000)]).unwrap();
    let mut mc = MotionController::new(2);
    mc.set_single_turn(MASTER, Some(SingleTurn::new(30000).unwrap()))
        .unwrap();
    mc.set_position(SLAVE, 1000).unwrap();
    start(&mut mc, CamType::Repeat, table);
    assert_eq!(mc.position(SLAVE).unwrap(), 1000);
    let seen = sweep(&mut mc, 0, 60000, 2500);
    let at = |m: i64| seen.iter().find(|s| s.0 == m).unwrap().1;
    // First turn: flat 1000 up to 5000, rise to 4000 at 20000, down to 3000
    // at 25000, flat 3000 to the end of the turn.
    assert_eq!(
        [
            at(0),
            at(2500),
            at(5000),
            at(12500),
            at(20000),
            at(25000),
            at(27500)
        ],
        [1000, 1000, 1000, 2500, 4000, 3000, 3000]
    );
    // Second turn: the same shape 2000 higher (stroke 3000 - 1000).
    assert_eq!(
        [at(30000), at(35000), at(50000), at(55000), at(60000)],
        [3000, 3000, 6000, 5000, 5000]
    );
}

#[test]
fn ends_less_than_one_user_unit_apart_are_not_joined() {
    // Stroke 400 pulses; with 1000 pulses per user unit the ends are less
    // than one unit apart, so the Repeat cam behaves as Periodic: at the
    // seam (master 10000) the next cycle begins at 0.
    let table = PointTable::from_pairs(&[(0, 0), (5000, 3000), (10000, 400)]).unwrap();
    let mut fine = MotionController::new(2);
    fine.set_user_unit(SLAVE, UserUnit::new(1000).unwrap())
        .unwrap();
    start(&mut fine, CamType::Repeat, table.clone());
    assert_eq!(
        sweep(&mut fine, 0, 15000, 5000),
        [(0, 0), (5000, 3000), (10000, 0), (15000, 3000)]
    );
    // With 100 pulses per unit the same ends are 4 units apart: joined.
    let mut coarse = MotionController::new(2);
    coarse
        .set_user_unit(SLAVE, UserUnit::new(100).unwrap())
        .unwrap();
    start(&mut coarse, CamType::Repeat, table);
    assert_eq!(
        sweep(&mut coarse, 0, 15000, 5000),
        [(0, 0), (5000, 3000), (10000, 400), (15000, 3400)]
    );
}

#[test]
fn refusals_change_nothing() {
    let mut mc = MotionController::new(2);
    start(&mut mc, CamType::Repeat, doc_table());
    assert_eq!(
        mc.set_position(SLAVE, 7),
        Err(McError::SlaveBusy { axis: SLAVE })
    );
    assert_eq!(
        mc.set_single_turn(MASTER, Some(SingleTurn::new(30000).unwrap())),
        Err(McError::AxisInUse { axis: MASTER })
    );
    let again = ECamData {
        master_axis: MASTER,
        slave_axis: SLAVE,
        cam_type: CamType::Normal,
        table: doc_table(),
    };
    assert_eq!(
        mc.start_ecam(again),
        Err(McError::SlaveBusy { axis: SLAVE })
    );
    assert!(matches!(
        mc.set_position(5, 0),
        Err(McError::NoSuchAxis { axis: 5, count: 2 })
    ));
    assert_eq!(mc.position(SLAVE).unwrap(), 500);
    assert_eq!(mc.single_turn(MASTER).unwrap(), None);
    assert!(mc.stop_ecam(SLAVE));
    mc.set_position(SLAVE, 7).unwrap();
    assert_eq!(mc.position(SLAVE).unwrap(), 7);
}

#[test]
fn table_outside_the_turn_is_refused() {
    let mut mc = MotionController::new(2);
    mc.set_single_turn(MASTER, Some(SingleTurn::new(20000).unwrap()))
        .unwrap();
    let data = ECamData {
        master_axis: MASTER,
        slave_axis: SLAVE,
        cam_type: CamType::Repeat,
        table: doc_table(),
    };
    let err = mc.start_ecam(data).unwrap_err();
    assert!(matches!(err, McError::Engine(_)), "{err}");
    assert!(!mc.ecam_running(SLAVE));
}

#[test]
fn repeat_started_mid_way_counts_cycles_from_the_cycle_it_starts_in() {
    // Not single-turn: the master at 45000 is in the second cycle, but the
    // start rule counts from there: the table value (1250) less one
    // stroke (1500) is nearer the slave at 0 (the table turns back, so
    // either way), where the old count from the table's start gave 2750.
    let mut mc = MotionController::new(2);
    mc.set_position(MASTER, 45000).unwrap();
    start(&mut mc, CamType::Repeat, doc_table());
    assert_eq!(mc.position(SLAVE).unwrap(), -250);
    assert_eq!(mc.drive(MASTER, 60000, SLAVE).unwrap(), 500);
}

#[test]
fn a_rising_repeat_table_started_mid_way_moves_less_than_a_stroke_forwards() {
    // A knife-like table (never turns back, stroke 3000) started at master
    // 45000: the table value there is 1500, which counted from the table's
    // start would be 4500. The slave lands on the first equivalent at or
    // ahead of it: from 0 on 1500, from 1600 on 4500.
    let rising = PointTable::from_pairs(&[(0, 0), (30000, 3000)]).unwrap();
    for (master, slave, expected) in [(45000, 0, 1500), (45000, 1600, 4500), (0, 0, 0)] {
        let mut mc = MotionController::new(2);
        mc.set_position(MASTER, master).unwrap();
        mc.set_position(SLAVE, slave).unwrap();
        start(&mut mc, CamType::Repeat, rising.clone());
        assert_eq!(mc.position(SLAVE).unwrap(), expected, "{master}, {slave}");
    }
    // The start rule's cases (docs/mc.md): a table in its third cycle, and
    // one started before its origin, which used to move 100 backwards.
    for (pairs, master, expected) in [
        ([(0, 0), (1000, 100)], 2500, 50),
        ([(1000, 0), (2000, 100)], 0, 0),
    ] {
        let mut mc = MotionController::new(2);
        mc.set_position(MASTER, master).unwrap();
        start(
            &mut mc,
            CamType::Repeat,
            PointTable::from_pairs(&pairs).unwrap(),
        );
        assert_eq!(
            mc.position(SLAVE).unwrap(),
            expected,
            "{pairs:?} at {master}"
        );
        assert_eq!(
            mc.drive(MASTER, master + 500, SLAVE).unwrap(),
            expected + 50
        );
    }
}

#[test]
fn normal_type_on_a_single_turn_master_follows_every_turn() {
    // Document 001: with a table covering the turn, Normal and Periodic
    // behave the same; Normal must not freeze at the end after a wrap.
    let mut mc = MotionController::new(2);
    mc.set_single_turn(MASTER, Some(SingleTurn::new(30000).unwrap()))
        .unwrap();
    start(&mut mc, CamType::Normal, doc_table());
    let normal = sweep(&mut mc, 0, 75000, 5000);
    let mut mc = MotionController::new(2);
    mc.set_single_turn(MASTER, Some(SingleTurn::new(30000).unwrap()))
        .unwrap();
    start(&mut mc, CamType::Periodic, doc_table());
    let periodic = sweep(&mut mc, 0, 75000, 5000);
    assert_eq!(normal, periodic);
    // 75000 is 15000 into the third turn: halfway from 1500 to 1000.
    assert_eq!(normal.last(), Some(&(75000, 1250)));
}

#[test]
fn a_master_step_above_the_limit_faults_instead_of_reversing() {
    let mut mc = MotionController::new(2);
    mc.set_single_turn(MASTER, Some(SingleTurn::new(30000).unwrap()))
        .unwrap();
    mc.set_max_master_step(MASTER, core::num::NonZeroU64::new(9000))
        .unwrap();
    start(&mut mc, CamType::Repeat, doc_table());
    mc.drive(MASTER, 5000, SLAVE).unwrap();
    // 20000 further on reads as 10000 back the short way round.
    mc.drive(MASTER, 25000, SLAVE).unwrap();
    assert!(!mc.ecam_running(SLAVE));
    assert_eq!(
        mc.fault(SLAVE).unwrap(),
        Some(ecam_engine::EngineError::MasterStep)
    );
}
