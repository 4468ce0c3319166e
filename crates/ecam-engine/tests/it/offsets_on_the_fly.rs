//! Master and slave offsets changed while the cam runs (PLCopen
//! `MasterOffset`/`SlaveOffset` in sync): ramped in over a master distance,
//! never a step; the final offsets are exact and nothing drifts afterwards.

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::{AxisConfig, CamAxis, Coupling, EngineError, OffsetChange, TickInput, Zoom};
use proptest::prelude::*;

const TICK_US: u32 = 100;

fn repeat() -> AxisConfig {
    AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        ..AxisConfig::default()
    }
}

#[test]
fn a_slave_offset_is_ramped_in_and_ends_exact() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 2000)]).unwrap();
    let mut axis = CamAxis::new(table, repeat()).unwrap();
    assert_eq!(
        axis.change_offsets(OffsetChange {
            master: 0,
            slave: 1,
            distance: NonZeroU64::MIN,
        }),
        Err(EngineError::NotRunning)
    );
    axis.arm().unwrap();
    for m in 0..=1000 {
        let _ = axis.tick(&TickInput::at(m, TICK_US));
    }
    let change = OffsetChange {
        master: 0,
        slave: 500,
        distance: NonZeroU64::new(1000).unwrap(),
    };
    axis.change_offsets(change).unwrap();
    assert_eq!(axis.change_offsets(change), Err(EngineError::Busy));
    let mut last = axis.commanded();
    for m in 1001..=2000 {
        let out = axis.tick(&TickInput::at(m, TICK_US));
        let step = out.slave - last;
        // The cam's 2 per count plus at most 1.875 × 500 / 1000 (rounded).
        assert!((2..=4).contains(&step), "master {m}: step {step}");
        assert_eq!(out.following, m >= 2000);
        last = out.slave;
    }
    assert!(!axis.is_changing_offsets());
    assert_eq!(axis.commanded(), 4000 + 500);
    assert_eq!(axis.tick(&TickInput::at(5000, TICK_US)).slave, 10_000 + 500);
    assert_eq!(axis.tick(&TickInput::at(1500, TICK_US)).slave, 3000 + 500);
}

#[test]
fn a_master_offset_shifts_the_profile_without_a_step() {
    // A flat dwell then a rise: a master offset of 100 moves the rise
    // 100 counts earlier.
    let table = PointTable::from_pairs(&[(0, 0), (500, 0), (1000, 1000)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Periodic,
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(table, config).unwrap();
    axis.arm().unwrap();
    let _ = axis.tick(&TickInput::at(0, TICK_US));
    axis.change_offsets(OffsetChange {
        master: 100,
        slave: 0,
        distance: NonZeroU64::new(300).unwrap(),
    })
    .unwrap();
    let mut last = 0;
    for m in 1..=400 {
        let out = axis.tick(&TickInput::at(m, TICK_US));
        assert_eq!(out.slave, 0, "still on the dwell at {m}");
        last = out.slave;
    }
    assert_eq!(last, 0);
    // Table input = master + 100: the rise starts at master 400.
    assert_eq!(axis.tick(&TickInput::at(700, TICK_US)).slave, 600);
}

/// A monotonic table and its steepest slope (slave per table count).
fn any_monotonic_points() -> impl Strategy<Value = (PointTable, f64)> {
    prop::collection::vec((1i64..400, 0i64..900), 1..10).prop_map(|steps| {
        let mut points = vec![(0i64, 0i64)];
        let (mut m, mut s) = (0, 0);
        let mut steepest: f64 = 0.0;
        for (dm, ds) in steps {
            m += dm;
            s += ds;
            steepest = steepest.max(ds as f64 / dm as f64);
            points.push((m, s));
        }
        if s == 0 {
            points.last_mut().unwrap().1 = 1;
            steepest = steepest.max(1.0 / m as f64);
        }
        (PointTable::from_pairs(&points).unwrap(), steepest)
    })
}

proptest! {
    // A change tick past the run is skipped (`prop_assume!`): about one
    // case in six, so a long run (`PROPTEST_CASES`) needs room for them.
    #![proptest_config(ProptestConfig {
        max_global_rejects: crate::cases(64).saturating_mul(2),
        ..ProptestConfig::with_cases(crate::cases(64))
    })]

    /// No step: each tick's change within the cam's slope plus the ramp's
    /// bounded extra; exact: afterwards the slave is that of an axis
    /// engaged at the same place whose offsets changed at once (the start
    /// rule counts strokes from the cycle a cam engages in, so an axis
    /// engaged with the offsets would count from another cycle); no drift.
    #[test]
    fn offset_changes_never_step_and_end_exact(
        (table, steep) in any_monotonic_points(),
        zoom in (1u16..5, 1u16..5),
        d_master in -500i64..500,
        d_slave in -5_000i64..5_000,
        distance in 1u64..5_000,
        motion in prop::collection::vec((-20_000i64..60_000, 1u32..300), 1..6),
        change_tick in 0usize..300,
    ) {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            master_zoom: Zoom::new(zoom.0, 1).unwrap(),
            slave_zoom: Zoom::new(1, zoom.1).unwrap(),
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(table.clone(), config).unwrap();
        axis.arm().unwrap();
        let change = OffsetChange {
            master: d_master,
            slave: d_slave,
            distance: NonZeroU64::new(distance).unwrap(),
        };
        let d = distance as f64;
        let sz = 1.0 / f64::from(zoom.1);
        let bound = |dm: f64| {
            steep * sz * (f64::from(zoom.0) + 1.875 * d_master.unsigned_abs() as f64 / d) * dm
                + 1.875 * d_slave.unsigned_abs() as f64 / d * dm
                + steep * sz
                + 3.0
        };
        let mut micro = 0i64;
        let mut last: Option<(i64, i64)> = None;
        let mut readings = Vec::new();
        let mut changed = false;
        let speeds = motion
            .iter()
            .flat_map(|&(speed, ticks)| std::iter::repeat_n(speed, ticks as usize));
        for (i, speed) in speeds.enumerate() {
            micro += speed * i64::from(TICK_US);
            let master = micro.div_euclid(1_000_000);
            readings.push(master);
            let out = axis.tick(&TickInput::at(master, TICK_US));
            if let Some((m0, s0)) = last {
                let dm = (master - m0).unsigned_abs() as f64;
                let ds = (out.slave - s0).unsigned_abs() as f64;
                prop_assert!(ds <= bound(dm), "tick {i}: {ds} for {dm} counts");
            }
            last = Some((master, out.slave));
            if i == change_tick {
                axis.change_offsets(change).unwrap();
                changed = true;
            }
        }
        prop_assume!(changed);
        // Past the ramp, wherever it started.
        let far = readings.iter().copied().max().unwrap() + distance as i64 + 10;
        let start = *readings.last().unwrap();
        for m in start..=far {
            let out = axis.tick(&TickInput::at(m, TICK_US));
            let (m0, s0) = last.unwrap();
            let ds = (out.slave - s0).unsigned_abs() as f64;
            prop_assert!(ds <= bound((m - m0).unsigned_abs() as f64));
            last = Some((m, out.slave));
        }
        prop_assert!(!axis.is_changing_offsets());
        let mut reference = CamAxis::new(table, config).unwrap();
        reference.arm().unwrap();
        let _ = reference.tick(&TickInput::at(readings[0], TICK_US));
        reference
            .change_offsets(OffsetChange {
                distance: NonZeroU64::MIN,
                ..change
            })
            .unwrap();
        for x in [far, far - 7_777, far + 123_456] {
            let slave = axis.tick(&TickInput::at(x, TICK_US)).slave;
            prop_assert_eq!(slave, reference.tick(&TickInput::at(x, TICK_US)).slave);
        }
    }
}
