//! The slave scaling changed while the cam runs (PLCopen `SlaveScaling` in
//! sync): ramped from the cam with the old scaling to the cam with the new
//! one, never a step; exactly the new cam afterwards, no drift.

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::{AxisConfig, CamAxis, Coupling, EngineError, TickInput, Zoom};
use proptest::prelude::*;

const TICK_US: u32 = 100;

#[test]
fn a_slave_scaling_is_ramped_in_and_ends_exact() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 1000)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(table, config).unwrap();
    let double = Zoom::new(2, 1).unwrap();
    let distance = NonZeroU64::new(1000).unwrap();
    assert_eq!(
        axis.change_slave_scaling(double, distance),
        Err(EngineError::NotRunning)
    );
    axis.arm().unwrap();
    for m in 0..=1000 {
        let _ = axis.tick(&TickInput::at(m, TICK_US));
    }
    axis.change_slave_scaling(double, distance).unwrap();
    assert_eq!(
        axis.change_slave_scaling(double, distance),
        Err(EngineError::Busy)
    );
    let mut last = axis.commanded();
    for m in 1001..=2000 {
        let out = axis.tick(&TickInput::at(m, TICK_US));
        let step = out.slave - last;
        // From 1 to 2 per count, plus the mix of a gap growing to 2000.
        assert!((0..=6).contains(&step), "master {m}: step {step}");
        last = out.slave;
    }
    assert_eq!(axis.commanded(), 4000);
    assert_eq!(axis.config().slave_zoom, double);
    assert_eq!(axis.tick(&TickInput::at(2500, TICK_US)).slave, 5000);
    assert!(axis.status().following);
}

#[test]
fn a_master_scaling_keeps_phase_and_position() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 1000)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(table.clone(), config).unwrap();
    axis.arm().unwrap();
    for m in 0..=500 {
        let _ = axis.tick(&TickInput::at(m, TICK_US));
    }
    let double = Zoom::new(2, 1).unwrap();
    axis.change_master_scaling(double, None).unwrap();
    let out = axis.tick(&TickInput::at(600, TICK_US));
    assert!(out.events.table_switched);
    // From master 500 (slave 500) on, two table counts per master count.
    assert_eq!(out.slave, 700);
    assert_eq!(axis.config().master_zoom, double);

    // With a blend the velocity goes from 1 to 2 per count without a step.
    let mut axis = CamAxis::new(table, config).unwrap();
    axis.arm().unwrap();
    for m in 0..=500 {
        let _ = axis.tick(&TickInput::at(m, TICK_US));
    }
    axis.change_master_scaling(double, NonZeroU64::new(400))
        .unwrap();
    let mut last = axis.commanded();
    let mut steps = Vec::new();
    for m in 501..=1200 {
        let out = axis.tick(&TickInput::at(m, TICK_US));
        steps.push(out.slave - last);
        last = out.slave;
    }
    assert!(steps.iter().all(|s| (1..=2).contains(s)), "{steps:?}");
    assert!(steps[450..].iter().all(|&s| s == 2));
}

fn any_table() -> impl Strategy<Value = PointTable> {
    prop::collection::vec((1i64..400, -300i64..900), 1..8).prop_map(|steps| {
        let mut points = vec![(0i64, 0i64)];
        let (mut m, mut s) = (0, 0);
        for (dm, ds) in steps {
            m += dm;
            s += ds;
            points.push((m, s));
        }
        PointTable::from_pairs(&points).unwrap()
    })
}

proptest! {
    // A change tick past the run is skipped (`prop_assume!`): about one
    // case in six, so a long run (`PROPTEST_CASES`) needs room for them.
    #![proptest_config(ProptestConfig {
        max_global_rejects: crate::cases(64).saturating_mul(2),
        ..ProptestConfig::with_cases(crate::cases(64))
    })]

    /// Each tick's change stays within the faster cam's plus the mix's
    /// bounded share of the gap between them; afterwards the slave is
    /// exactly that of an axis engaged at the same place whose scaling
    /// changed at once, and a fixed offset (whole strokes, the start rule's)
    /// from an axis engaged with the new scaling from the start; no drift.
    #[test]
    fn scaling_changes_never_step_and_end_exact(
        table in any_table(),
        periodic in any::<bool>(),
        old in (1u16..6, 1u16..6),
        new in (1u16..6, 1u16..6),
        distance in 1u64..5_000,
        motion in prop::collection::vec((-20_000i64..60_000, 1u32..300), 1..6),
        change_tick in 0usize..300,
    ) {
        let coupling = if periodic { Coupling::Periodic } else { Coupling::Repeat { min_stroke: 1 } };
        let config = AxisConfig {
            coupling,
            slave_zoom: Zoom::new(old.0, old.1).unwrap(),
            ..AxisConfig::default()
        };
        let new_zoom = Zoom::new(new.0, new.1).unwrap();
        let stroke = table.points().last().map_or(0, |p| p.slave).abs();
        let mut axis = CamAxis::new(table.clone(), config).unwrap();
        let mut before = CamAxis::new(table.clone(), config).unwrap();
        let mut after = CamAxis::new(table.clone(), AxisConfig { slave_zoom: new_zoom, ..config }).unwrap();
        for a in [&mut axis, &mut before, &mut after] {
            a.arm().unwrap();
        }
        let mut micro = 0i64;
        let mut readings = Vec::new();
        let mut rows = Vec::new();
        let speeds: Vec<i64> = motion
            .iter()
            .flat_map(|&(speed, ticks)| std::iter::repeat_n(speed, ticks as usize))
            .collect();
        let mut changed = false;
        for (i, speed) in speeds.iter().enumerate() {
            micro += speed * i64::from(TICK_US);
            let master = micro.div_euclid(1_000_000);
            readings.push(master);
            let input = TickInput::at(master, TICK_US);
            rows.push((
                master,
                axis.tick(&input).slave,
                before.tick(&input).slave,
                after.tick(&input).slave,
            ));
            if i == change_tick {
                axis.change_slave_scaling(new_zoom, NonZeroU64::new(distance).unwrap()).unwrap();
                changed = true;
            }
        }
        prop_assume!(changed);
        let far = readings.iter().copied().max().unwrap() + distance as i64 + 10;
        let start = *readings.last().unwrap();
        for m in start..=far {
            let input = TickInput::at(m, TICK_US);
            rows.push((m, axis.tick(&input).slave, before.tick(&input).slave, after.tick(&input).slave));
        }
        let gap = rows.iter().map(|r| (r.3 - r.2).unsigned_abs()).max().unwrap() as f64;
        for w in rows.windows(2) {
            let dm = (w[1].0 - w[0].0).unsigned_abs() as f64;
            let ds = (w[1].1 - w[0].1).unsigned_abs() as f64;
            let cams = ((w[1].2 - w[0].2).unsigned_abs()).max((w[1].3 - w[0].3).unsigned_abs()) as f64;
            prop_assert!(ds <= cams + 1.875 * gap / distance as f64 * dm + 2.0,
                "master {}: {ds} (cams {cams}, gap {gap})", w[1].0);
        }
        prop_assert!(!axis.is_changing_offsets());
        let mut reference = CamAxis::new(table, config).unwrap();
        reference.arm().unwrap();
        let _ = reference.tick(&TickInput::at(readings[0], TICK_US));
        reference.change_slave_scaling(new_zoom, NonZeroU64::MIN).unwrap();
        for x in [far, far - 7_777, far + 123_456] {
            let input = TickInput::at(x, TICK_US);
            prop_assert_eq!(axis.tick(&input).slave, reference.tick(&input).slave);
        }
        // The start rule engages a repeating cam at the equivalent of the
        // table value nearest ahead of the slave, a whole number of strokes
        // that depends on the scaling at the start: the axis keeps what it
        // engaged with through the change, so afterwards it runs the new cam
        // at a fixed offset from an axis engaged with the new scaling from
        // the start (none for a periodic cam), never more than a few
        // strokes. Where a scaled stroke is not a whole number of pulses the
        // offset is that number of strokes rounded, so it may differ by one
        // pulse from place to place, never more, and never grows.
        let bound = 4 * stroke.max(1) * i64::from(new.0.max(old.0)) + 1;
        let whole = |z: (u16, u16)| (stroke * i64::from(z.0)) % i64::from(z.1) == 0;
        let ripple = if periodic || (whole(old) && whole(new)) { 0 } else { 1 };
        let offsets: Vec<i64> = [far, far - 7_777, far + 123_456, far + 1_000_003]
            .into_iter()
            .map(|x| {
                let input = TickInput::at(x, TICK_US);
                axis.tick(&input).slave - after.tick(&input).slave
            })
            .collect();
        let (low, high) = (offsets.iter().min().copied().unwrap_or(0), offsets.iter().max().copied().unwrap_or(0));
        if periodic {
            prop_assert_eq!(high, 0);
        }
        prop_assert!(high - low <= ripple, "offsets {offsets:?}");
        prop_assert!(high.abs() <= bound && low.abs() <= bound, "offsets {offsets:?} beyond {bound}");
    }
}
