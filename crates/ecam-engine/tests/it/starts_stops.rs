//! Start and stop behaviour beyond single document examples: edges, the
//! ramp-in, reversal, faults and events.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, AxisState, CamAxis, Coupling, RampIn, SlaveAlign, StartMode, StopKind, TickInput,
};

fn line() -> PointTable {
    PointTable::from_pairs(&[(0, 0), (1000, 3000)]).unwrap()
}

fn repeat(start: StartMode) -> AxisConfig {
    AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        start,
        ..AxisConfig::default()
    }
}

#[test]
fn a_start_input_already_high_at_arm_is_not_an_edge() {
    let mut a = CamAxis::new(line(), repeat(StartMode::OnRisingEdge)).unwrap();
    let high = |m| TickInput {
        start_input: true,
        ..TickInput::at(m, 1000)
    };
    let _ = a.tick(&high(0));
    a.arm().unwrap();
    assert_eq!(a.tick(&high(10)).state, AxisState::Armed);
    let _ = a.tick(&TickInput::at(20, 1000));
    assert!(a.tick(&high(30)).events.engaged);
}

#[test]
fn reversal_retraces_the_table_and_counts_down() {
    let table = PointTable::from_pairs(&[(0, 0), (300, 900), (600, -200), (1000, 400)]).unwrap();
    let mut a = CamAxis::new(table, repeat(StartMode::Immediate)).unwrap();
    a.arm().unwrap();
    let masters: Vec<i64> = (0..=5000).step_by(13).collect();
    let forward: Vec<i64> = masters
        .iter()
        .copied()
        .map(|m| a.tick(&TickInput::at(m, 1_000_000)).slave)
        .collect();
    let backward: Vec<i64> = masters
        .iter()
        .rev()
        .copied()
        .map(|m| a.tick(&TickInput::at(m, 1_000_000)).slave)
        .collect();
    let mut retraced = backward.clone();
    retraced.reverse();
    assert_eq!(forward, retraced);
    assert_eq!(a.status().emitted, 0);
}

#[test]
fn ramp_in_engages_a_moving_master_without_a_velocity_jump() {
    let config = AxisConfig {
        ramp_in: Some(RampIn {
            distance: NonZeroU64::new(2000).unwrap(),
        }),
        ..repeat(StartMode::Immediate)
    };
    let mut a = CamAxis::new(line(), config).unwrap();
    a.set_slave_position(-500).unwrap();
    a.arm().unwrap();
    // Master at 10 counts per tick; the cam moves 30 pulses per tick.
    let mut previous = -500;
    let mut previous_step = 0;
    let mut in_sync_at = None;
    for i in 0..400 {
        let m = 5000 + 10 * i;
        let out = a.tick(&TickInput::at(m, 100));
        let step = out.slave - previous;
        // Velocity changes gradually: from rest onto the cam's 30 pulses
        // per tick over 200 ticks, closing the start rule's 500-pulse gap
        // on the way (the quintic's peak second derivative is
        // 10/sqrt(3) / distance^2), a fraction of a pulse per tick per
        // tick, plus rounding.
        assert!(
            (step - previous_step).abs() <= 4,
            "tick {i}: {previous_step} -> {step}"
        );
        if i < 3 {
            assert!(step.abs() <= 1, "starts from rest: tick {i} moved {step}");
        }
        if out.following && in_sync_at.is_none() {
            in_sync_at = Some(i);
        }
        previous = out.slave;
        previous_step = step;
    }
    assert_eq!(in_sync_at, Some(200));
    assert_eq!(previous_step, 30);
    // The start rule: the cycle it engaged in (from 5000) is the first,
    // and the slave at -500 takes the table value 0 ahead of it.
    assert_eq!(previous, 3 * (10 * 399));
}

#[test]
fn relative_start_with_ramp_is_bumpless_and_smooth() {
    let config = AxisConfig {
        slave_align: SlaveAlign::Relative,
        ramp_in: Some(RampIn {
            distance: NonZeroU64::new(100).unwrap(),
        }),
        ..repeat(StartMode::Immediate)
    };
    let mut a = CamAxis::new(line(), config).unwrap();
    a.set_slave_position(777).unwrap();
    a.arm().unwrap();
    let out = a.tick(&TickInput::at(250, 100));
    assert_eq!(out.slave, 777);
    assert!(!out.following);
    assert_eq!(a.tick(&TickInput::at(251, 100)).slave, 777);
}

#[test]
fn immediate_stop_cancels_an_armed_start_and_reports_it() {
    let mut a = CamAxis::new(line(), repeat(StartMode::OnRisingEdge)).unwrap();
    a.arm().unwrap();
    let _ = a.tick(&TickInput::at(0, 100));
    a.stop(StopKind::EndOfCycle);
    let out = a.tick(&TickInput::at(0, 100));
    assert_eq!(out.state, AxisState::Idle);
    assert!(out.events.stopped);
    assert!(!a.tick(&TickInput::at(0, 100)).events.stopped);
    // Disengaging an idle axis changes nothing.
    a.disengage();
    assert!(!a.tick(&TickInput::at(0, 100)).events.stopped);
}

#[test]
fn overflow_is_a_fault_not_a_panic() {
    let table = PointTable::from_pairs(&[(0, 0), (1, i64::MAX / 2)]).unwrap();
    let mut a = CamAxis::new(table, repeat(StartMode::Immediate)).unwrap();
    a.arm().unwrap();
    let _ = a.tick(&TickInput::at(0, 100));
    let out = a.tick(&TickInput::at(1_000_000, 100));
    assert_eq!(out.fault, Some(ecam_engine::EngineError::SlaveOverflow));
    assert_eq!(out.state, AxisState::Idle);
    assert!(out.events.stopped);
    assert_eq!(out.slave, 0);
}

#[test]
fn a_bad_single_turn_table_is_refused() {
    let config = AxisConfig {
        single_turn: NonZeroU64::new(500),
        ..AxisConfig::default()
    };
    assert_eq!(
        CamAxis::new(line(), config).err(),
        Some(ecam_engine::EngineError::TableOutsideTurn)
    );
}
