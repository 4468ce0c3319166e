//! Leaving the cam at velocity (PLCopen `MC_CamOut`) and the decelerating
//! stop: constant velocity, exact pulses, the frequency ceiling, no reversal.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::plcopen::{CamIn, CamOut, McCamAxis};
use ecam_engine::{
    AxisConfig, AxisState, CamAxis, Coupling, EngineError, StopKind, TickInput, TickOutput,
};
use proptest::prelude::*;

/// slave = 3 × master.
fn line() -> PointTable {
    PointTable::from_pairs(&[(0, 0), (1000, 3000)]).unwrap()
}

fn running(hz: i64) -> CamAxis<PointTable> {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        max_frequency_hz: hz,
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(line(), config).unwrap();
    axis.arm().unwrap();
    axis
}

#[test]
fn cam_out_continues_at_the_slave_velocity_exactly() {
    let mut axis = running(200_000);
    // Master 10 counts per 1 ms tick: 10 000 counts/s, slave 30 000 pulses/s.
    let mut m = 0;
    for _ in 0..100 {
        m += 10;
        let _ = axis.tick(&TickInput::at(m, 1000));
    }
    let at = axis.commanded();
    axis.cam_out_at_velocity().unwrap();
    assert_eq!(axis.coast_velocity(), Some(30_000.0));
    // The master stops: the slave does not care any more.
    for i in 1..=1000_i64 {
        let out = axis.tick(&TickInput::at(m, 1000));
        assert_eq!(out.state, AxisState::Velocity);
        assert!(out.busy && !out.following);
        assert_eq!(out.slave, at + 30 * i, "tick {i}");
        assert_eq!(out.pulses, 30);
    }
    assert_eq!(axis.arm(), Err(EngineError::Busy));
    axis.stop(StopKind::Immediate);
    let out = axis.tick(&TickInput::at(m, 1000));
    assert!(out.events.stopped);
    assert_eq!(out.state, AxisState::Idle);
    assert_eq!(out.slave, at + 30_000);
    assert_eq!(axis.tick(&TickInput::at(m, 1000)).slave, at + 30_000);
}

#[test]
fn the_velocity_is_bounded_by_the_frequency_limit() {
    let mut axis = running(5_000);
    for m in (0..=2000).step_by(10) {
        let _ = axis.tick(&TickInput::at(m, 1000));
    }
    axis.cam_out_at_velocity().unwrap();
    assert_eq!(axis.coast_velocity(), Some(5_000.0));
}

#[test]
fn cam_out_needs_an_engaged_cam() {
    let mut axis = CamAxis::new(line(), AxisConfig::default()).unwrap();
    assert_eq!(axis.cam_out_at_velocity(), Err(EngineError::NotRunning));
    assert_eq!(
        axis.stop_decelerating(NonZeroU64::new(1000).unwrap()),
        Err(EngineError::NotRunning)
    );
    assert_eq!(axis.state(), AxisState::Idle);
}

#[test]
fn a_decelerating_stop_from_a_running_cam_comes_to_rest() {
    let mut axis = running(200_000);
    let mut m = 0;
    for _ in 0..50 {
        m += 10;
        let _ = axis.tick(&TickInput::at(m, 1000));
    }
    let at = axis.commanded();
    // 30 000 pulses/s down at 300 000 pulses/s²: 0.1 s, 1500 pulses.
    axis.stop_decelerating(NonZeroU64::new(300_000).unwrap())
        .unwrap();
    let mut last = at;
    let mut ticks = 0;
    loop {
        m += 10;
        let out = axis.tick(&TickInput::at(m, 1000));
        assert!(out.slave >= last);
        last = out.slave;
        ticks += 1;
        if out.events.stopped {
            assert_eq!(out.state, AxisState::Idle);
            break;
        }
        assert!(ticks < 1000);
    }
    assert_eq!(ticks, 100);
    assert_eq!(last, at + 1500);
}

#[test]
fn facade_cam_out_variants() {
    let run = |how: CamOut| {
        let mut axis = McCamAxis::new(line()).unwrap();
        axis.cam_in(&CamIn::default()).unwrap();
        for m in (0..=500).step_by(10) {
            let _ = axis.tick(m, 1000);
        }
        axis.cam_out(how);
        let s = axis.tick(500, 1000);
        (s, axis.tick(500, 1000))
    };
    // The standard: the slave moves on at 30 pulses per ms, Busy, not Active.
    let (first, second) = run(CamOut::AtVelocity);
    assert!(first.busy && !first.active && !first.in_sync);
    assert_eq!(second.output.slave - first.output.slave, 30);
    // Hold: stops at once.
    let (first, second) = run(CamOut::Hold);
    assert!(!first.busy && !first.active);
    assert_eq!(second.output.slave, first.output.slave);
    // End of cycle: follows the cam to the cycle end (master 1000).
    let (first, _) = run(CamOut::EndOfCycle);
    assert!(first.active && first.busy);
}

#[test]
fn facade_halt_and_stop_end_the_velocity_motion() {
    let mut axis = McCamAxis::new(line()).unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    for m in (0..=500).step_by(10) {
        let _ = axis.tick(m, 1000);
    }
    axis.cam_out(CamOut::AtVelocity);
    let _ = axis.tick(500, 1000);
    axis.halt(NonZeroU64::new(3_000_000).unwrap()).unwrap();
    let stopped = (0..20)
        .map(|_| axis.tick(500, 1000))
        .position(|s| s.output.events.stopped);
    assert_eq!(stopped, Some(9));
    assert!(!axis.tick(500, 1000).busy);
    assert_eq!(
        axis.halt(NonZeroU64::new(1000).unwrap()),
        Err(EngineError::NotRunning)
    );

    axis.cam_in(&CamIn::default()).unwrap();
    for m in (500..=700).step_by(10) {
        let _ = axis.tick(m, 1000);
    }
    axis.cam_out(CamOut::AtVelocity);
    let moving = axis.tick(700, 1000).output.slave;
    axis.stop();
    let s = axis.tick(700, 1000);
    assert!(!s.busy);
    assert_eq!(s.output.slave, moving);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(64)))]

    /// After a cam-out at any master speed and limit: pulses within the
    /// ceiling, constant velocity (no reversal, at most one pulse of
    /// rounding between ticks), and a decelerating stop that never reverses.
    #[test]
    fn cam_out_motion_is_safe(
        speed in -60i64..60,
        hz in prop_oneof![Just(200_000i64), 1_000i64..200_000],
        dt in 100u32..2000,
        coast_ticks in 1usize..300,
        decel in 1_000u64..10_000_000,
    ) {
        let mut axis = running(hz);
        let mut m = 10_000;
        for _ in 0..64 {
            m += speed;
            let _ = axis.tick(&TickInput::at(m, dt));
        }
        axis.cam_out_at_velocity().unwrap();
        let v = axis.coast_velocity().unwrap();
        prop_assert!(v.abs() <= hz as f64);
        let ceiling = u128::from(hz.unsigned_abs()) * u128::from(dt);
        let expected = v * f64::from(dt) / 1e6;
        // Checked tick by tick (a slow stop from full speed takes millions).
        let mut previous = *axis.status();
        let mut check = |i: usize, out: &TickOutput| -> Result<(), TestCaseError> {
            let ds = out.slave - previous.slave;
            prop_assert!(ds == 0 || (ds > 0) == (v > 0.0), "tick {i}: reversed");
            prop_assert!(u128::from(out.pulses.unsigned_abs()) * 1_000_000 < ceiling + 1_000_000);
            if 0 < i && i < coast_ticks {
                prop_assert!((ds as f64 - expected).abs() <= 1.0, "tick {i}: {ds} vs {expected}");
            }
            previous = *out;
            Ok(())
        };
        for i in 0..coast_ticks {
            let out = axis.tick(&TickInput::at(m, dt));
            check(i, &out)?;
        }
        axis.stop_decelerating(NonZeroU64::new(decel).unwrap()).unwrap();
        // The stop ends within the time the deceleration gives (v / decel),
        // plus the backlog's ticks: it always finishes.
        let stop_ticks = (v.abs() / decel as f64 * 1e6 / f64::from(dt)).ceil() as usize;
        let limit = stop_ticks + stop_ticks / 50 + 100;
        let mut stopped = false;
        for i in 0..limit {
            let out = axis.tick(&TickInput::at(m, dt));
            check(coast_ticks + i, &out)?;
            if out.events.stopped {
                stopped = true;
                break;
            }
        }
        prop_assert!(stopped, "no stop within {limit} ticks ({stop_ticks} expected)");
    }
}
