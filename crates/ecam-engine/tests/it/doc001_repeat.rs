//! Document 001 (Repeat-type cam, single-turn master): every worked example.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::{AxisConfig, AxisState, CamAxis, Coupling, SlaveAlign, TickInput};

fn table() -> PointTable {
    PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)]).unwrap()
}

fn axis(config: AxisConfig) -> CamAxis<PointTable> {
    let mut axis = CamAxis::new(table(), config).unwrap();
    axis.arm().unwrap();
    axis
}

fn slave_at(axis: &mut CamAxis<PointTable>, master: i64) -> i64 {
    axis.tick(&TickInput::at(master, 1_000_000)).slave
}

#[test]
fn repeat_joins_the_seam_and_periodic_jumps() {
    let repeat = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        ..AxisConfig::default()
    };
    let mut a = axis(repeat);
    assert_eq!(slave_at(&mut a, 0), 500);
    assert_eq!(slave_at(&mut a, 29999), 2000);
    assert_eq!(slave_at(&mut a, 30000), 2000);
    assert_eq!(slave_at(&mut a, 35000), 2500);
    assert_eq!(slave_at(&mut a, 60000), 3500);
    // Backwards through the seams, continuous both ways.
    assert_eq!(slave_at(&mut a, -1), 500);
    assert_eq!(slave_at(&mut a, -30000), -1000);

    let mut p = axis(AxisConfig::default());
    assert_eq!(slave_at(&mut p, 29999), 2000);
    assert_eq!(slave_at(&mut p, 30000), 500);
    assert_eq!(slave_at(&mut p, 35000), 1000);
}

#[test]
fn ends_closer_than_one_user_unit_are_not_joined() {
    // 1500 pulses of stroke, one user unit = 2000 pulses: behaves as Periodic.
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 2000 },
        ..AxisConfig::default()
    };
    let mut a = axis(config);
    assert_eq!(slave_at(&mut a, 0), 500);
    assert_eq!(slave_at(&mut a, 35000), 1000);
    // One user unit = 1500 pulses: exactly one unit apart, joined.
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1500 },
        ..AxisConfig::default()
    };
    let mut a = axis(config);
    assert_eq!(slave_at(&mut a, 0), 500);
    assert_eq!(slave_at(&mut a, 35000), 2500);
}

#[test]
fn equal_ends_make_repeat_and_periodic_identical() {
    let t = PointTable::from_pairs(&[(0, 0), (500, 300), (1000, 0)]).unwrap();
    let mut a = CamAxis::new(
        t.clone(),
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        },
    )
    .unwrap();
    let mut b = CamAxis::new(t, AxisConfig::default()).unwrap();
    a.arm().unwrap();
    b.arm().unwrap();
    for m in (-5000..5000).step_by(37) {
        let input = TickInput::at(m, 1_000_000);
        assert_eq!(a.tick(&input).slave, b.tick(&input).slave);
    }
}

fn single_turn(table: PointTable, align: SlaveAlign) -> CamAxis<PointTable> {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        single_turn: NonZeroU64::new(30000),
        slave_align: align,
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(table, config).unwrap();
    axis.arm().unwrap();
    axis
}

#[test]
fn single_turn_master_keeps_the_slave_across_wraps() {
    let mut a = single_turn(table(), SlaveAlign::Absolute);
    assert_eq!(slave_at(&mut a, 0), 500);
    // Two turns forward in steps of 7000 counts of the wrapping reading.
    let mut raw = 0i64;
    for _ in 0..(60000 / 7000) {
        raw = (raw + 7000) % 30000;
        slave_at(&mut a, raw);
    }
    // 56000 counts travelled: one wrap and 26000 into the second turn.
    assert_eq!(slave_at(&mut a, 26000), 1600 + 1500);
    assert_eq!(slave_at(&mut a, 0), 3500);
    // And back over the wrap.
    assert_eq!(slave_at(&mut a, 25000), 1500 + 1500);
    assert_eq!(a.status().cycle, 1);
}

#[test]
fn single_turn_start_takes_the_nearest_equivalent_slave() {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        single_turn: NonZeroU64::new(30000),
        slave_align: SlaveAlign::NearestEquivalent,
        ..AxisConfig::default()
    };
    let mut a = CamAxis::new(table(), config).unwrap();
    a.set_slave_position(-1500).unwrap();
    a.arm().unwrap();
    let out = a.tick(&TickInput::at(20000, 1_000_000));
    assert_eq!(out.state, AxisState::Running);
    assert_eq!(out.slave, -2000);
    // The curve continues from there: at the end of the turn 2000 - 3000.
    assert_eq!(slave_at(&mut a, 29999), -1000);
    assert_eq!(slave_at(&mut a, 5000), -1000 + 500);
}

#[test]
fn single_turn_table_not_covering_the_turn_is_extended() {
    let t = PointTable::from_pairs(&[(5000, 1000), (20000, 4000), (25000, 3000)]).unwrap();
    let mut a = single_turn(t, SlaveAlign::Absolute);
    assert_eq!(slave_at(&mut a, 0), 1000);
    assert_eq!(slave_at(&mut a, 4000), 1000);
    assert_eq!(slave_at(&mut a, 12500), 2500);
    assert_eq!(slave_at(&mut a, 27000), 3000);
    assert_eq!(slave_at(&mut a, 29999), 3000);
    // Next turn: the stroke 2000 is kept, continuous at the wrap.
    assert_eq!(slave_at(&mut a, 2000), 3000);
    assert_eq!(slave_at(&mut a, 12500), 4500);
}

#[test]
fn normal_type_holds_the_end_values() {
    let mut a = axis(AxisConfig {
        coupling: Coupling::Normal,
        ..AxisConfig::default()
    });
    assert_eq!(slave_at(&mut a, -5000), 500);
    assert_eq!(slave_at(&mut a, 15000), 1250);
    assert_eq!(slave_at(&mut a, 45000), 2000);
    assert_eq!(a.status().cycle, 0);
}
