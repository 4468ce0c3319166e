//! The steady tick and the fast lane against the general tick: the same
//! axis driven twice, once as `tick` runs it and once with the steady path
//! and the lane switched off, must give identical outputs every tick,
//! through engages, ramp-ins, seams, jumps, master fractions, online offset
//! and scaling changes, switches with blends and stops.

use core::num::{NonZeroU32, NonZeroU64};

use ecam_core::PointTable;
use proptest::prelude::*;
use std::vec;
use std::vec::Vec;

use crate::{
    AxisConfig, CamAxis, Coupling, OffsetChange, RampDirection, RampIn, RampInLimits, SlaveAlign,
    StopKind, SwitchAt, SyncWindow, TickInput, Zoom,
};

/// Ramp-in limits with a jerk limit, either way (0), positive (1) or
/// negative (2) only (shared with the engage tests).
pub(super) fn limits_towards(direction: u8) -> RampInLimits {
    RampInLimits {
        max_velocity: NonZeroU32::new(2_000_000).unwrap(),
        max_acceleration: NonZeroU64::new(400_000_000).unwrap(),
        direction: match direction {
            0 => RampDirection::Either,
            1 => RampDirection::Positive,
            _ => RampDirection::Negative,
        },
        max_jerk: NonZeroU64::new(100_000_000_000),
    }
}

/// A table of `slaves` at masters `step` apart (shared with the engage tests).
pub(super) fn table(slaves: &[i64], step: i64) -> PointTable {
    let pairs: Vec<(i64, i64)> = slaves
        .iter()
        .enumerate()
        .map(|(i, &s)| (i as i64 * step, s))
        .collect();
    PointTable::from_pairs(&pairs).unwrap()
}

fn coupling() -> impl Strategy<Value = Coupling> {
    prop_oneof![
        Just(Coupling::Periodic),
        Just(Coupling::Repeat { min_stroke: 1 }),
        Just(Coupling::Normal),
        (0u16..3).prop_map(|repeats| Coupling::OneShot { repeats }),
    ]
}

fn align() -> impl Strategy<Value = SlaveAlign> {
    prop_oneof![
        Just(SlaveAlign::Relative),
        Just(SlaveAlign::Absolute),
        Just(SlaveAlign::NearestEquivalent),
        (-5000i64..5000).prop_map(SlaveAlign::Offset),
    ]
}

/// One tick's master move and what else happens on it.
#[derive(Clone, Copy, Debug)]
enum Move {
    Step(i64),
    Fraction(i64, u32),
    Offsets(i64, i64),
    Stop,
    Rearm,
    /// A table queued for the next seam (its slaves scaled by this factor).
    Queue(i64),
    /// Slave scaling changed on the fly to this signed numerator / 4.
    SlaveScaling(i32),
    /// MC_CamOut as the standard: continue at the current velocity.
    CamOut,
    /// A table switched in at once with a blend (slaves scaled by this factor).
    Switch(i64),
    /// A table switched in at a master position this far ahead (or
    /// behind), with a blend or without (slaves scaled by the factor).
    SwitchAt(i64, i64, bool),
    /// A table queued for the next seam with a blend (slaves scaled).
    SeamSwitch(i64),
    /// Master scaling changed on the fly to this signed numerator / 3,
    /// with a blend or without.
    MasterScaling(i32, bool),
}

fn moves() -> impl Strategy<Value = Vec<Move>> {
    proptest::collection::vec(
        prop_oneof![
            20 => (-40i64..200).prop_map(Move::Step),
            2 => (-1_000_000i64..1_000_000).prop_map(Move::Step),
            2 => ((0i64..50), any::<u32>()).prop_map(|(s, f)| Move::Fraction(s, f)),
            1 => ((-300i64..300), (-300i64..300)).prop_map(|(m, s)| Move::Offsets(m, s)),
            1 => Just(Move::Stop),
            1 => Just(Move::Rearm),
            1 => (-3i64..4).prop_map(Move::Queue),
            1 => prop_oneof![(-12i32..-1), (1i32..12)].prop_map(Move::SlaveScaling),
            1 => Just(Move::CamOut),
            1 => (-3i64..4).prop_map(Move::Switch),
            1 => ((-3i64..4), (-400i64..400), any::<bool>())
                .prop_map(|(f, d, b)| Move::SwitchAt(f, d, b)),
            1 => (-3i64..4).prop_map(Move::SeamSwitch),
            1 => (prop_oneof![(-9i32..-1), (1i32..9)], any::<bool>())
                .prop_map(|(n, b)| Move::MasterScaling(n, b)),
        ],
        1..300,
    )
}

/// 64 cases, or `PROPTEST_CASES` for a longer hunt.
fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(64)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]
    #[test]
    fn steady_tick_equals_general_tick(
        slaves in proptest::collection::vec(-20_000i64..20_000, 2..20),
        step in 1i64..5000,
        coupling in coupling(),
        align in align(),
        mzoom in (prop_oneof![(-19i32..-1), (1i32..20)], 1u16..20),
        szoom in (prop_oneof![(-19i32..-1), (1i32..20)], 1u16..20),
        start in -100_000i64..100_000,
        ramp_in in proptest::option::of(1u64..3000),
        turn in proptest::option::of(0i64..5000),
        limits in proptest::option::of((0u8..3, -100_000i64..100_000)),
        moves in moves(),
    ) {
        let config = AxisConfig {
            coupling,
            slave_align: align,
            master_zoom: Zoom::signed(mzoom.0, mzoom.1).unwrap(),
            slave_zoom: Zoom::signed(szoom.0, szoom.1).unwrap(),
            sync_windows: [
                SyncWindow::new(0, step),
                SyncWindow::new(step, 3 * step),
                SyncWindow::OFF,
                SyncWindow::new(-5, 5),
            ],
            ramp_in: ramp_in.and_then(NonZeroU64::new).map(|distance| RampIn { distance }),
            // A single-turn master: the table within the turn.
            single_turn: turn.and_then(|extra| {
                NonZeroU64::new((slaves.len() as u64 - 1) * step as u64 + extra as u64)
            }),
            ..AxisConfig::default()
        };
        // Signed scalings are refused where they make no sense (a one-shot
        // run backwards): both paths see the same refusal.
        let Ok(mut fast) = CamAxis::new(table(&slaves, step), config) else {
            return Ok(());
        };
        // A ramp-in under limits, from a slave away from the cam.
        if let Some((direction, slave)) = limits {
            fast.set_slave_position(slave).unwrap();
            fast.set_ramp_in_limits(Some(limits_towards(direction)));
        }
        fast.arm().unwrap();
        let mut general = fast.clone();
        let mut master = start;
        for (i, m) in moves.into_iter().enumerate() {
            let mut fraction = 0;
            match m {
                Move::Step(d) => master += d,
                Move::Fraction(d, f) => {
                    master += d;
                    fraction = f;
                }
                Move::Offsets(dm, ds) => {
                    let change = OffsetChange {
                        master: dm,
                        slave: ds,
                        distance: NonZeroU64::new(500).unwrap(),
                    };
                    prop_assert_eq!(fast.change_offsets(change), general.change_offsets(change));
                }
                Move::Stop => {
                    fast.stop(StopKind::EndOfCycle);
                    general.stop(StopKind::EndOfCycle);
                }
                Move::Rearm => {
                    prop_assert_eq!(fast.arm(), general.arm());
                }
                Move::Queue(factor) => {
                    let scaled: Vec<i64> = slaves.iter().map(|s| s * factor).collect();
                    prop_assert_eq!(
                        fast.queue_curve(table(&scaled, step)),
                        general.queue_curve(table(&scaled, step))
                    );
                }
                Move::SlaveScaling(num) => {
                    let zoom = Zoom::signed(num, 4).unwrap();
                    let distance = NonZeroU64::new(700).unwrap();
                    prop_assert_eq!(
                        fast.change_slave_scaling(zoom, distance),
                        general.change_slave_scaling(zoom, distance)
                    );
                }
                Move::CamOut => {
                    prop_assert_eq!(fast.cam_out_at_velocity(), general.cam_out_at_velocity());
                }
                Move::Switch(factor) => {
                    let scaled: Vec<i64> = slaves.iter().map(|s| s * factor).collect();
                    let at = SwitchAt::Now { blend: NonZeroU64::new(800) };
                    prop_assert_eq!(
                        fast.switch_curve(table(&scaled, step), at),
                        general.switch_curve(table(&scaled, step), at)
                    );
                }
                Move::SwitchAt(factor, ahead, blended) => {
                    let scaled: Vec<i64> = slaves.iter().map(|s| s * factor).collect();
                    let at = SwitchAt::MasterPosition {
                        position: master + ahead,
                        blend: NonZeroU64::new(600).filter(|_| blended),
                    };
                    prop_assert_eq!(
                        fast.switch_curve(table(&scaled, step), at),
                        general.switch_curve(table(&scaled, step), at)
                    );
                }
                Move::SeamSwitch(factor) => {
                    let scaled: Vec<i64> = slaves.iter().map(|s| s * factor).collect();
                    let at = SwitchAt::NextSeam { blend: NonZeroU64::new(700) };
                    prop_assert_eq!(
                        fast.switch_curve(table(&scaled, step), at),
                        general.switch_curve(table(&scaled, step), at)
                    );
                }
                Move::MasterScaling(num, blended) => {
                    let zoom = Zoom::signed(num, 3).unwrap();
                    let blend = NonZeroU64::new(500).filter(|_| blended);
                    prop_assert_eq!(
                        fast.change_master_scaling(zoom, blend),
                        general.change_master_scaling(zoom, blend)
                    );
                }
            }
            let input = TickInput {
                master_fraction: fraction,
                ..TickInput::at(master, 100)
            };
            let a = fast.tick(&input);
            let b = *general.step(&input, false);
            prop_assert_eq!(a, b, "tick {} at master {}", i, master);
            prop_assert_eq!(fast.commanded(), general.commanded());
        }
    }
}

#[test]
fn a_settled_cam_takes_the_steady_path() {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(table(&[0, 700, 1000], 100), config).unwrap();
    axis.arm().unwrap();
    for m in 0..5 {
        let _ = axis.tick(&TickInput::at(m, 100));
    }
    let super::Phase::Running(engaged) = &axis.phase else {
        panic!("not running");
    };
    assert!(engaged.underway.steady().is_some());
}
