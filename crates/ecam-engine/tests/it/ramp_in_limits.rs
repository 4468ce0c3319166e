//! Ramp-in under limits: engaging a moving master, the slave catches up
//! within its velocity, acceleration and (optional) jerk limits, and a direction-restricted
//! ramp-in closes the gap only that way (PLCopen `ramp_in_pos`/`_neg`).

use core::num::{NonZeroU32, NonZeroU64};

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, AxisState, CamAxis, Coupling, EngineError, RampDirection, RampIn, RampInLimits,
    TickInput,
};
use proptest::prelude::*;

const TICK_US: u32 = 1000;

#[test]
fn a_cam_without_a_stroke_cannot_be_caught_up_one_way_only() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 0)]).unwrap();
    let mut axis = CamAxis::new(table, AxisConfig::default()).unwrap();
    axis.set_slave_position(500).unwrap();
    axis.set_ramp_in_limits(Some(RampInLimits {
        max_jerk: None,
        max_velocity: NonZeroU32::new(10_000).unwrap(),
        max_acceleration: NonZeroU64::new(1_000_000).unwrap(),
        direction: RampDirection::Positive,
    }));
    axis.arm().unwrap();
    let out = axis.tick(&TickInput::at(0, TICK_US));
    assert_eq!(out.fault, Some(EngineError::RampDirection));
}

/// PLCopen: in sync when the master reaches `MasterSyncPosition`, the
/// ramp starting `MasterStartDistance` before it.
#[test]
fn master_sync_position_and_start_distance() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 3000)]).unwrap();
    let (start, ramp) = RampIn::sync_at(5_000, NonZeroU64::new(1_000).unwrap(), true);
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        start,
        ramp_in: Some(ramp),
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(table, config).unwrap();
    axis.arm().unwrap();
    for m in (0..6_000).step_by(7) {
        let out = axis.tick(&TickInput::at(m, TICK_US));
        assert_eq!(out.state == AxisState::Running, m >= 4_000, "master {m}");
        assert_eq!(out.following, m >= 5_000, "master {m}");
        if m >= 5_000 {
            // The cycle it engaged in (from 4000) counts as the first.
            assert_eq!(out.slave, 3 * (m - 4_000));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(48)))]

    #[test]
    fn ramp_in_respects_its_limits_over_random_master_speeds(
        ratio in 1i64..5,
        speed in prop_oneof![-20_000i64..-500, 500i64..20_000],
        start in -5_000i64..5_000,
        headroom in 1.5f64..5.0,
        max_acceleration in 200_000u64..10_000_000,
        restrict in any::<bool>(),
        max_jerk in prop::option::of(10_000_000u64..1_000_000_000),
    ) {
        let table = PointTable::from_pairs(&[(0, 0), (1000, 1000 * ratio)]).unwrap();
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(table, config).unwrap();
        axis.set_slave_position(start).unwrap();
        let cam_speed = (ratio * speed.abs()) as f64;
        let max_velocity = (1.78 * cam_speed * headroom).max(5_000.0) as u32;
        // Restricted to the way the master drives the cam.
        let direction = match (restrict, speed > 0) {
            (false, _) => RampDirection::Either,
            (true, true) => RampDirection::Positive,
            (true, false) => RampDirection::Negative,
        };
        axis.set_ramp_in_limits(Some(RampInLimits {
            max_jerk: max_jerk.and_then(NonZeroU64::new),
            max_velocity: NonZeroU32::new(max_velocity).unwrap(),
            max_acceleration: NonZeroU64::new(max_acceleration).unwrap(),
            direction,
        }));
        // The master is already moving when the axis is armed.
        let master = |tick: i64| (speed * tick * i64::from(TICK_US)).div_euclid(1_000_000);
        for tick in 0..40 {
            let _ = axis.tick(&TickInput::at(master(tick), TICK_US));
        }
        axis.arm().unwrap();
        let mut slaves = vec![start];
        let mut synced = None;
        for tick in 40..100_000 {
            let out = axis.tick(&TickInput::at(master(tick), TICK_US));
            prop_assert!(out.fault.is_none(), "{:?}", out.fault);
            slaves.push(out.slave);
            if out.following && synced.is_none() {
                synced = Some(slaves.len());
            }
            if synced.is_some_and(|s| slaves.len() > s + 200) {
                break;
            }
        }
        prop_assert!(synced.is_some(), "never in sync");
        // Velocity and acceleration over 20 ms windows. A position is off
        // by a pulse of rounding and a count of master quantisation (the
        // master is read in whole counts: up to `ratio` pulses), so a
        // difference of two is off by 2 × (ratio + 1) pulses, 50 pulses/s
        // of velocity per pulse, and a second difference by 4 × (ratio + 1),
        // 2 500 pulses/s² of acceleration per pulse. (Found at 20 000
        // cases: ratio 4, a ramp at its limit of 214 709 pulses/s² measured
        // at 227 500 with whole counts, 217 500 with the master's fraction.)
        const K: usize = 20;
        let window = K as f64 * f64::from(TICK_US) / 1e6;
        let quantum = ratio as f64 + 1.0;
        let velocities: Vec<f64> = slaves
            .windows(K + 1)
            .map(|w| (w[K] - w[0]) as f64 / window)
            .collect();
        for (i, v) in velocities.iter().enumerate() {
            prop_assert!(v.abs() <= f64::from(max_velocity) * 1.01 + 2.0 * quantum / window,
                "tick {i}: {v} pulses/s above {max_velocity}");
        }
        for (i, w) in velocities.windows(K + 1).enumerate() {
            let a = (w[K] - w[0]) / window;
            prop_assert!(a.abs() <= max_acceleration as f64 * 1.01 + 4.0 * quantum / (window * window),
                "tick {i}: {a} pulses/s² above {max_acceleration}");
        }
        if let Some(max_jerk) = max_jerk {
            // Jerk over 50 ms windows: third differences of positions, so
            // a pulse of rounding (and a count of master quantisation, up
            // to `ratio` pulses) is 8 × (ratio + 1) / window³.
            const J: usize = 50;
            let window = J as f64 * f64::from(TICK_US) / 1e6;
            let v: Vec<f64> = slaves
                .windows(J + 1)
                .map(|w| (w[J] - w[0]) as f64 / window)
                .collect();
            let a: Vec<f64> = v.windows(J + 1).map(|w| (w[J] - w[0]) / window).collect();
            let noise = 8.0 * (ratio as f64 + 1.0) / (window * window * window);
            for (i, w) in a.windows(J + 1).enumerate() {
                let jerk = (w[J] - w[0]) / window;
                prop_assert!(jerk.abs() <= max_jerk as f64 * 1.01 + noise,
                    "tick {i}: {jerk} pulses/s³ above {max_jerk}");
            }
        }
        if restrict {
            let sign = speed.signum();
            prop_assert!(slaves.windows(2).all(|w| (w[1] - w[0]) * sign >= 0),
                "a restricted ramp-in moved against its direction");
        }
    }
}
