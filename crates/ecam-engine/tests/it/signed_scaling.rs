//! Signed scalings: a negative slave scaling mirrors the cam, a negative
//! master scaling runs the profile backwards; PLCopen's relative slave adds
//! the start position, bumpless being our explicit option.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::plcopen::{CamIn, CamInStartMode, CamTableSelect, McCamAxis};
use ecam_engine::{AxisConfig, CamAxis, Coupling, EngineError, TickInput, Zoom};
use proptest::prelude::*;

/// Rises 100 → 400 over master 0..1000 (first value not 0).
fn ramp() -> PointTable {
    PointTable::from_pairs(&[(0, 100), (1000, 400)]).unwrap()
}

#[test]
fn a_negative_slave_scaling_mirrors_the_cam() {
    let mut axis = McCamAxis::new(ramp()).unwrap();
    axis.cam_in(&CamIn {
        slave_scaling: Zoom::signed(-2, 1).unwrap(),
        ..CamIn::default()
    })
    .unwrap();
    assert_eq!(axis.tick(0, 1_000_000).output.slave, -200);
    let s = axis.tick(500, 1_000_000);
    assert_eq!(s.output.slave, -500);
    assert!((s.output.velocity_ratio + 0.6).abs() < 1e-9);
}

#[test]
fn a_negative_master_scaling_runs_the_profile_backwards() {
    let mut axis = McCamAxis::new(ramp()).unwrap();
    axis.cam_in(&CamIn {
        master_scaling: Zoom::signed(-1, 1).unwrap(),
        master_offset: 1000,
        ..CamIn::default()
    })
    .unwrap();
    // Table input = 1000 − master: the profile from its end to its start
    // (at master 0 exactly on the seam, where the periodic table restarts).
    assert_eq!(axis.tick(1, 1_000_000).output.slave, 400);
    let s = axis.tick(250, 1_000_000);
    assert_eq!(s.output.slave, 325);
    assert!((s.output.velocity_ratio + 0.3).abs() < 1e-9);
    assert_eq!(axis.tick(900, 1_000_000).output.slave, 130);
}

#[test]
fn a_negative_master_scaling_on_a_non_periodic_absolute_table_ends_at_the_start() {
    let mut axis = McCamAxis::new(ramp()).unwrap();
    axis.select(CamTableSelect {
        periodic: false,
        ..CamTableSelect::default()
    })
    .unwrap();
    axis.cam_in(&CamIn {
        master_scaling: Zoom::signed(-1, 1).unwrap(),
        master_offset: 1000,
        ..CamIn::default()
    })
    .unwrap();
    assert!(!axis.tick(500, 1_000_000).end_of_profile);
    let s = axis.tick(1500, 1_000_000);
    assert!(s.end_of_profile && s.active);
    assert_eq!(s.output.slave, 100);
}

#[test]
fn a_one_shot_cannot_run_backwards() {
    let mut axis = McCamAxis::new(ramp()).unwrap();
    axis.select(CamTableSelect {
        periodic: false,
        master_absolute: false,
        ..CamTableSelect::default()
    })
    .unwrap();
    let err = axis
        .cam_in(&CamIn {
            master_scaling: Zoom::signed(-1, 1).unwrap(),
            ..CamIn::default()
        })
        .unwrap_err();
    assert_eq!(err, EngineError::ReversedOneShot);
    assert!(!axis.tick(0, 1000).busy);
}

#[test]
fn the_standards_reading_of_master_scaling_is_the_reciprocal() {
    // "The master profile multiplied by 2": one table over 2000 counts.
    let params = CamIn::default().master_profile_scaled(Zoom::new(2, 1).unwrap());
    assert_eq!(params.master_scaling, Zoom::new(1, 2).unwrap());
    let mut axis = McCamAxis::new(ramp()).unwrap();
    axis.cam_in(&params).unwrap();
    assert_eq!(axis.tick(1000, 1_000_000).output.slave, 250);
}

#[test]
fn slave_absolute_false_adds_the_start_position_bumpless_is_an_option() {
    let relative = CamTableSelect {
        slave_absolute: false,
        ..CamTableSelect::default()
    };
    // PLCopen (and RTmotion, CODESYS): table values + the slave's start.
    let mut axis = McCamAxis::new(ramp()).unwrap();
    axis.select(relative).unwrap();
    axis.set_slave_position(5000).unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    assert_eq!(axis.tick(0, 1_000_000).output.slave, 5100);
    assert_eq!(axis.tick(500, 1_000_000).output.slave, 5250);
    // Start mode relative reads the same on an absolute table.
    let mut axis = McCamAxis::new(ramp()).unwrap();
    axis.set_slave_position(5000).unwrap();
    axis.cam_in(&CamIn {
        start_mode: CamInStartMode::Relative,
        slave_offset: 7,
        ..CamIn::default()
    })
    .unwrap();
    assert_eq!(axis.tick(0, 1_000_000).output.slave, 5107);
    // Bumpless: the table value at engage lands where the slave stands.
    let mut axis = McCamAxis::new(ramp()).unwrap();
    axis.select(relative).unwrap();
    axis.set_slave_position(5000).unwrap();
    axis.cam_in(&CamIn {
        start_mode: CamInStartMode::Bumpless,
        ..CamIn::default()
    })
    .unwrap();
    assert_eq!(axis.tick(0, 1_000_000).output.slave, 5000);
    assert_eq!(axis.tick(500, 1_000_000).output.slave, 5150);
}

fn any_zoom() -> impl Strategy<Value = Zoom> {
    (1i32..5, any::<bool>(), 1u16..5)
        .prop_map(|(n, neg, d)| Zoom::signed(if neg { -n } else { n }, d).unwrap())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(64)))]

    /// Signed scalings, at engage and changed on the fly, never break the
    /// slave's continuity, and once a change is ramped in the cam is
    /// exactly the one engaged with the new scaling (zero drift).
    #[test]
    fn signed_scaling_keeps_continuity_and_does_not_drift(
        rise in prop::collection::vec((1i64..300, -400i64..400), 1..6),
        master_zoom in any_zoom(),
        slave_zoom in any_zoom(),
        new_zoom in any_zoom(),
        motion in prop::collection::vec((-40i64..40, 1usize..200), 1..5),
        change_at in 0usize..300,
        distance in 1u64..2000,
    ) {
        let mut points = vec![(0i64, 0i64)];
        let rise_stroke: i64 = rise.iter().map(|r| r.1).sum();
        let (mut m, mut s, mut steepest) = (0, 0, 0.0f64);
        for (dm, ds) in rise {
            m += dm;
            s += ds;
            steepest = steepest.max((ds as f64 / dm as f64).abs());
            points.push((m, s));
        }
        let table = PointTable::from_pairs(&points).unwrap();
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            master_zoom,
            slave_zoom,
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(table.clone(), config).unwrap();
        axis.arm().unwrap();
        let mut master = 0i64;
        // Engaged at 0, as the fresh axis below: both count strokes from there.
        let mut outs = vec![axis.tick(&TickInput::at(master, 1000))];
        let mut changed = false;
        let steps: Vec<i64> = motion
            .iter()
            .flat_map(|&(v, n)| std::iter::repeat_n(v, n))
            .collect();
        for (i, v) in steps.iter().enumerate() {
            if i == change_at && i > 0 {
                axis.change_slave_scaling(new_zoom, NonZeroU64::new(distance).unwrap()).unwrap();
                changed = true;
            }
            master += v;
            outs.push(axis.tick(&TickInput::at(master, 1000)));
        }
        let factor = |z: Zoom| master_zoom.ratio().abs() * z.ratio().abs();
        let most = factor(slave_zoom).max(factor(new_zoom));
        let unzoomed = outs.iter().map(|o| o.slave_unzoomed.unsigned_abs()).max().unwrap_or(0) as f64
            + steepest * 40.0 * master_zoom.ratio().abs();
        let mix = 1.875 * (new_zoom.ratio() - slave_zoom.ratio()).abs() * unzoomed / distance as f64;
        for (i, w) in outs.windows(2).enumerate() {
            let dm = (w[1].master - w[0].master).unsigned_abs() as f64;
            let ds = (w[1].slave - w[0].slave).unsigned_abs() as f64;
            let bound = (steepest * most + if changed { mix } else { 0.0 }) * dm + 2.0;
            prop_assert!(ds <= bound, "tick {}: slave moved {ds} for {dm} (bound {bound})", i + 1);
        }
        // Zero drift: once the change is ramped in (the master far enough
        // from where it was asked, whichever way it went), exactly an axis
        // engaged at the same place whose scaling changed at once: the
        // change keeps the strokes the axis engaged with.
        for m in (master - 50_000..=master).rev().step_by(997) {
            let _ = axis.tick(&TickInput::at(m, 1000));
        }
        for m in (master - 50_000..=master + 50_000).step_by(997) {
            let _ = axis.tick(&TickInput::at(m, 1000));
        }
        let settled = master + 50_000;
        let final_zoom = if changed { new_zoom } else { slave_zoom };
        let engaged = |zoom: Zoom| {
            let mut a = CamAxis::new(table.clone(), AxisConfig { slave_zoom: zoom, ..config }).unwrap();
            a.arm().unwrap();
            let _ = a.tick(&TickInput::at(0, 1000));
            a
        };
        let mut at_once = engaged(slave_zoom);
        if changed {
            at_once.change_slave_scaling(new_zoom, NonZeroU64::MIN).unwrap();
        }
        // And an axis engaged with the final scaling from the start, up to
        // the start rule's whole strokes (start_rule.rs): it takes the first
        // stroke count whose *rounded* value is at or ahead of the slave, so
        // where a scaled stroke is below one pulse several counts round to
        // the slave's 0 and which one it takes depends on the scaling (the
        // shrunk case: 1/1 engages on strokes 0, 1/3 a stroke back, a third
        // of a pulse away). With a stroke of at least one pulse under both
        // scalings (or none) only strokes 0 round to 0: exactly equal.
        // Otherwise a fixed offset of whole strokes: exactly, the old start
        // lies within half a pulse of 0 at the old scaling, so within
        // |new/old| / 2 at the new, the fresh one within 1/2; rounded, at
        // most a pulse more, and varying by at most one pulse from place to
        // place (never growing: no drift).
        let mut fresh = engaged(final_zoom);
        let pulses = |z: Zoom| rise_stroke.unsigned_abs() * u64::from(z.num()) >= u64::from(z.den());
        let same_strokes = rise_stroke == 0 || (pulses(slave_zoom) && pulses(final_zoom));
        let bound = (0.5 * (final_zoom.ratio() / slave_zoom.ratio()).abs() + 0.5).floor() as i64 + 1;
        let mut offsets = Vec::new();
        for m in (settled - 2000..=settled).step_by(37) {
            let input = TickInput::at(m, 1000);
            let a = axis.tick(&input).slave;
            prop_assert_eq!(a, at_once.tick(&input).slave, "master {}", m);
            let offset = a - fresh.tick(&input).slave;
            if same_strokes {
                prop_assert_eq!(offset, 0, "master {}", m);
            }
            prop_assert!(offset.abs() <= bound, "master {}: offset {} beyond {}", m, offset, bound);
            offsets.push(offset);
        }
        let spread = offsets.iter().max().unwrap() - offsets.iter().min().unwrap();
        prop_assert!(spread <= 1, "offsets {:?}", offsets);
    }
}

/// The shrunk proptest case (tests/proptest-regressions/signed_scaling.txt):
/// a repeat cam falling one count per master count, engaged at master 0
/// with the slave at 0, its slave scaling changed from 1/1 to 1/3. The
/// change itself is exact: afterwards the axis is the cam `−master/3`,
/// just as an axis whose scaling changed at once. An axis engaged with 1/3
/// from the start stands one stroke (a third of a pulse) away, `(1 −
/// master)/3`: with a stroke below one pulse, strokes −1, 0 and 1 all
/// round to the slave's 0 at the start (1/3, 0, −1/3), and the start rule
/// takes the first of them in the cam's direction, the least travel: on
/// 1/1 strokes 0 (the only one), on 1/3 strokes −1. A whole stroke, fixed:
/// no drift, one pulse apart wherever the two round differently (master
/// 48074: −16025 against −16024).
#[test]
fn a_scaled_stroke_below_one_pulse_changed_on_the_fly_keeps_the_engaged_strokes() {
    let table = PointTable::from_pairs(&[(0, 0), (1, -1)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        ..AxisConfig::default()
    };
    let third = Zoom::new(1, 3).unwrap();
    let engaged = |zoom: Zoom| {
        let mut axis = CamAxis::new(
            table.clone(),
            AxisConfig {
                slave_zoom: zoom,
                ..config
            },
        )
        .unwrap();
        axis.arm().unwrap();
        let _ = axis.tick(&TickInput::at(0, 1000));
        axis
    };
    let mut axis = engaged(Zoom::ONE);
    let _ = axis.tick(&TickInput::at(0, 1000));
    axis.change_slave_scaling(third, NonZeroU64::MIN).unwrap();
    let mut at_once = engaged(Zoom::ONE);
    at_once
        .change_slave_scaling(third, NonZeroU64::MIN)
        .unwrap();
    let mut fresh = engaged(third);
    // Round to nearest of n/3 (never a tie).
    let third_of = |n: i64| (2 * n + 3).div_euclid(6);
    for m in (-50_000..=50_000)
        .step_by(997)
        .chain(48_000..=48_100)
        .chain(-5..=5)
    {
        let input = TickInput::at(m, 1000);
        let a = axis.tick(&input).slave;
        assert_eq!(a, at_once.tick(&input).slave, "master {m}");
        assert_eq!(a, third_of(-m), "master {m}");
        assert_eq!(fresh.tick(&input).slave, third_of(1 - m), "master {m}");
    }
    assert_eq!(fresh.tick(&TickInput::at(48_074, 1000)).slave, -16024);
    assert_eq!(axis.tick(&TickInput::at(48_074, 1000)).slave, -16025);
}
