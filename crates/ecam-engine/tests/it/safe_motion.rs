//! Safe motion: a command a drive can follow, whatever the master does.
//!
//! Over random monotonic tables, zooms, couplings, frequency ceilings and
//! master sources (a fine counter read every tick, a coarse counter or
//! register that changes every few ticks, the exact time base with its
//! fraction), with speed changes, reversals and seams:
//! - the pulses of every tick stay within the frequency ceiling;
//! - the emitted direction reverses no more often than the master does (a
//!   monotonic table never asks for more), and never when it does not;
//! - once the master rests, the commanded slave is exactly the cam of the
//!   master (zero drift) and every pulse has gone out;
//! - at constant speed, pulses per tick follow the cam's velocity within
//!   one pulse once the tracker has settled;
//! - on any table (periodic seams that jump included) each tick's pulses
//!   move the output towards the command and never past it;
//! - starts and restarts from anywhere, in every start mode and as every
//!   face sets the engine up, never reverse and move the slave less than
//!   one stroke (`starts`).
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use core::num::{NonZeroU32, NonZeroU64};

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, CamAxis, Coupling, MasterFilter, SlaveAlign, TickInput, TickOutput, TimeBase, Zoom,
};
use proptest::prelude::*;

mod starts;

const TICK_US: u32 = 100;

/// How the master reaches the axis.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// A counter read every tick.
    Fine,
    /// A counter or register that shows a new value every `every` ticks.
    Coarse { every: u32 },
    /// The K time base: one count per `period` × 100 µs, with its fraction.
    TimeBase { period: u32 },
}

fn any_source() -> impl Strategy<Value = Source> {
    prop_oneof![
        Just(Source::Fine),
        (2u32..40).prop_map(|every| Source::Coarse { every }),
        (1u32..50).prop_map(|period| Source::TimeBase { period }),
    ]
}

/// A monotonic table: master strictly increasing, slave never decreasing.
pub(crate) fn any_monotonic_table() -> impl Strategy<Value = PointTable> {
    prop::collection::vec((1i64..400, 0i64..900), 1..12).prop_map(|steps| {
        let mut points = vec![(0i64, 0i64)];
        let (mut m, mut s) = (0, 0);
        for (dm, ds) in steps {
            m += dm;
            s += ds;
            points.push((m, s));
        }
        if s == 0 {
            // A table with no stroke at all would never move the slave.
            points.last_mut().unwrap().1 = 1;
        }
        PointTable::from_pairs(&points).unwrap()
    })
}

fn any_coupling() -> impl Strategy<Value = Coupling> {
    prop_oneof![
        Just(Coupling::Repeat { min_stroke: 1 }),
        (0u16..4).prop_map(|repeats| Coupling::OneShot { repeats }),
        Just(Coupling::OneShot { repeats: u16::MAX }),
    ]
}

fn any_zoom() -> impl Strategy<Value = Zoom> {
    (1u16..8, 1u16..8).prop_map(|(n, d)| Zoom::new(n, d).unwrap())
}

/// Master speed segments: (counts per second, ticks).
fn any_motion() -> impl Strategy<Value = Vec<(i64, u32)>> {
    prop::collection::vec((-20_000i64..60_000, 1u32..400), 1..8)
}

/// Feeds the master through `source` and ticks the axis; returns every
/// tick's output and the readings the axis got.
struct Run {
    outputs: Vec<TickOutput>,
    readings: Vec<i64>,
    final_master: i64,
    /// A time base at rest still stands between two counts.
    final_fraction: u32,
}

fn run(axis: &mut CamAxis<PointTable>, source: Source, motion: &[(i64, u32)], rest: u32) -> Run {
    let mut outputs = Vec::new();
    let mut readings = Vec::new();
    // The true master in 1/10^6 count per tick resolution.
    let mut true_micro: i64 = 0;
    let mut held = 0i64;
    let mut time_base = match source {
        Source::TimeBase { period } => Some(TimeBase::new(NonZeroU32::new(period).unwrap())),
        _ => None,
    };
    let mut tick = 0u64;
    let mut final_fraction = 0;
    let mut step = |speed: i64, axis: &mut CamAxis<PointTable>| {
        let (master, fraction) = match (&mut time_base, source) {
            (Some(tb), _) => {
                // The time base only runs forwards; its speed is its period.
                let m = tb.advance(if speed == 0 { 0 } else { TICK_US });
                (m, tb.fraction())
            }
            (None, Source::Coarse { every }) => {
                true_micro += speed * i64::from(TICK_US);
                if tick.is_multiple_of(u64::from(every)) {
                    held = true_micro.div_euclid(1_000_000);
                }
                (held, 0)
            }
            (None, _) => {
                true_micro += speed * i64::from(TICK_US);
                (true_micro.div_euclid(1_000_000), 0)
            }
        };
        tick += 1;
        final_fraction = fraction;
        readings.push(master);
        outputs.push(axis.tick(&TickInput {
            master_fraction: fraction,
            ..TickInput::at(master, TICK_US)
        }));
    };
    for &(speed, ticks) in motion {
        for _ in 0..ticks {
            step(speed, axis);
        }
    }
    for _ in 0..rest {
        step(0, axis);
    }
    let final_master = *readings.last().unwrap();
    Run {
        outputs,
        readings,
        final_master,
        final_fraction,
    }
}

pub(crate) fn reversals(values: impl Iterator<Item = i64>) -> usize {
    let mut last = 0i64;
    let mut count = 0;
    for d in values {
        if d != 0 {
            if last != 0 && d.signum() != last.signum() {
                count += 1;
            }
            last = d;
        }
    }
    count
}

fn filter_for(source: Source) -> MasterFilter {
    match source {
        Source::Coarse { .. } => MasterFilter::INTERPOLATE,
        Source::Fine | Source::TimeBase { .. } => MasterFilter::Direct,
    }
}

/// The commanded slave for `master` computed afresh (no history): the cam
/// is a pure function of the master and the engage instant.
fn fresh_command(
    table: &PointTable,
    config: AxisConfig,
    engage_at: i64,
    master: i64,
    fraction: u32,
) -> i64 {
    let mut axis = CamAxis::new(
        table.clone(),
        AxisConfig {
            master_filter: MasterFilter::Direct,
            ..config
        },
    )
    .unwrap();
    axis.arm().unwrap();
    let _ = axis.tick(&TickInput::at(engage_at, TICK_US));
    axis.tick(&TickInput {
        master_fraction: fraction,
        ..TickInput::at(master, TICK_US)
    })
    .slave
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(64)))]

    #[test]
    fn a_drive_can_follow_every_command(
        table in any_monotonic_table(),
        coupling in any_coupling(),
        master_zoom in any_zoom(),
        slave_zoom in any_zoom(),
        hz in prop_oneof![Just(200_000i64), 1_000i64..200_000],
        source in any_source(),
        motion in any_motion(),
    ) {
        let config = AxisConfig {
            coupling,
            master_zoom,
            slave_zoom,
            max_frequency_hz: hz,
            master_filter: filter_for(source),
            // Bumpless: an absolute engage may ask for a jump back to the
            // table value, which is a reversal the command did ask for.
            slave_align: SlaveAlign::Relative,
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(table.clone(), config).unwrap();
        axis.arm().unwrap();
        // Long enough a rest for the tracker to land and the backlog to drain.
        let r = run(&mut axis, source, &motion, 2_000);

        let ceiling = u128::from(hz.unsigned_abs()) * u128::from(TICK_US);
        for (i, out) in r.outputs.iter().enumerate() {
            prop_assert!(
                u128::from(out.pulses.unsigned_abs()) * 1_000_000 < ceiling + 1_000_000,
                "tick {i}: {} pulses above {hz} Hz", out.pulses
            );
        }
        // A monotonic table never asks the slave to turn back on its own.
        let master_turns = reversals(r.readings.windows(2).map(|w| w[1] - w[0]));
        let slave_turns = reversals(r.outputs.iter().map(|o| o.pulses));
        prop_assert!(slave_turns <= master_turns,
            "slave reversed {slave_turns} times, master {master_turns}");

        // Zero drift: at rest, exactly the cam of the master, all emitted.
        let mut last = *r.outputs.last().unwrap();
        let mut drained = 0i64;
        // A low ceiling may still owe pulses: drain them at rest.
        for _ in 0..crate::ticks_to_drain(last.backlog, hz, TICK_US) {
            if last.backlog == 0 {
                break;
            }
            last = axis.tick(&TickInput {
                master_fraction: r.final_fraction,
                ..TickInput::at(r.final_master, TICK_US)
            });
            drained += last.pulses;
        }
        let engage_at = r.readings[0];
        match r.outputs.iter().find(|o| o.events.finished) {
            // A one-shot that finished holds where it finished, wherever
            // the master went afterwards.
            Some(end) => prop_assert_eq!(last.slave, end.slave),
            None => prop_assert_eq!(
                last.slave,
                fresh_command(&table, config, engage_at, r.final_master, r.final_fraction)
            ),
        }
        prop_assert_eq!(last.backlog, 0);
        prop_assert_eq!(last.emitted, last.slave);
        let total: i64 = r.outputs.iter().map(|o| o.pulses).sum::<i64>() + drained;
        prop_assert_eq!(total, last.slave);
    }

    #[test]
    fn pulses_never_overshoot_the_command_on_any_table(
        points in prop::collection::vec((1i64..400, -900i64..900), 1..10),
        coupling in prop_oneof![
            Just(Coupling::Periodic),
            Just(Coupling::Repeat { min_stroke: 1 }),
            (0u16..3).prop_map(|repeats| Coupling::OneShot { repeats }),
            Just(Coupling::Normal),
        ],
        master_zoom in any_zoom(),
        slave_zoom in any_zoom(),
        hz in prop_oneof![Just(200_000i64), 1_000i64..200_000],
        source in any_source(),
        motion in any_motion(),
    ) {
        // Any table, seams that jump included: each tick's pulses move the
        // output towards the command and never past it, so the output turns
        // only when the command asks, and the ceiling holds.
        let mut pairs = vec![(0i64, 0i64)];
        let mut m = 0;
        for (dm, s) in points {
            m += dm;
            pairs.push((m, s));
        }
        let table = PointTable::from_pairs(&pairs).unwrap();
        let config = AxisConfig {
            coupling,
            master_zoom,
            slave_zoom,
            max_frequency_hz: hz,
            master_filter: filter_for(source),
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(table, config).unwrap();
        axis.arm().unwrap();
        let r = run(&mut axis, source, &motion, 200);
        let ceiling = u128::from(hz.unsigned_abs()) * u128::from(TICK_US);
        let mut emitted = 0i64;
        for (i, out) in r.outputs.iter().enumerate() {
            prop_assert!(u128::from(out.pulses.unsigned_abs()) * 1_000_000 < ceiling + 1_000_000);
            let (low, high) = (emitted.min(out.slave), emitted.max(out.slave));
            prop_assert!((low..=high).contains(&out.emitted),
                "tick {i}: emitted {} outside [{low}, {high}]", out.emitted);
            prop_assert_eq!(out.emitted, emitted + out.pulses);
            emitted = out.emitted;
        }
    }

    #[test]
    fn pulses_follow_the_cam_velocity_at_constant_speed(
        ratio in 1i64..20,
        counts_per_update in 1i64..4,
        every in 2u32..25,
    ) {
        // A straight table of `ratio` pulses per count; a coarse master that
        // moves `counts_per_update` every `every` ticks, below the ceiling.
        prop_assume!(ratio * counts_per_update <= 20 * i64::from(every));
        let table = PointTable::from_pairs(&[(0, 0), (1000, 1000 * ratio)]).unwrap();
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            master_filter: MasterFilter::INTERPOLATE,
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(table, config).unwrap();
        axis.arm().unwrap();
        let ideal = (ratio * counts_per_update) as f64 / f64::from(every);
        let mut master = 0i64;
        for tick in 0..(every * 40) {
            if tick > 0 && tick % every == 0 {
                master += counts_per_update;
            }
            let out = axis.tick(&TickInput::at(master, TICK_US));
            // Settled after the tracker has seen five updates.
            if tick > every * 6 {
                prop_assert!((out.pulses as f64 - ideal).abs() <= 1.0,
                    "tick {tick}: {} pulses, cam velocity {ideal} per tick", out.pulses);
            }
        }
    }
}

/// The case: K10 time base (one count per ms), 100 µs ticks, a cam
/// cruising at 50 kHz: 5 pulses every tick, never 50 in one and 0 in nine.
#[test]
fn a_coarse_time_base_cruises_without_bursts() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 50_000)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(table, config).unwrap();
    axis.arm().unwrap();
    let mut tb = TimeBase::new(NonZeroU32::new(10).unwrap());
    for tick in 0..5_000 {
        let (m, f) = if tick == 0 {
            (0, 0)
        } else {
            (tb.advance(TICK_US), tb.fraction())
        };
        let out = axis.tick(&TickInput {
            master_fraction: f,
            ..TickInput::at(m, TICK_US)
        });
        if tick > 0 {
            assert!(
                (4..=6).contains(&out.pulses),
                "tick {tick}: {} pulses",
                out.pulses
            );
        }
        if f == 0 {
            // Exact at every whole count.
            assert_eq!(out.slave, m * 50);
        }
    }
}

/// The same cruise from a counter fed at 1 kHz: the tracker spreads it.
#[test]
fn a_coarse_counter_cruises_without_bursts() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 50_000)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        master_filter: MasterFilter::INTERPOLATE,
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(table.clone(), config).unwrap();
    axis.arm().unwrap();
    let mut bursts = 0;
    for tick in 0..5_000i64 {
        let out = axis.tick(&TickInput::at(tick / 10, TICK_US));
        if tick > 100 && !(4..=6).contains(&out.pulses) {
            bursts += 1;
        }
    }
    assert_eq!(bursts, 0);
    // Without the tracker the same master comes out as 50-pulse bursts.
    let mut direct = CamAxis::new(
        table,
        AxisConfig {
            master_filter: MasterFilter::Direct,
            ..config
        },
    )
    .unwrap();
    direct.arm().unwrap();
    let peak = (0..100i64)
        .map(|tick| direct.tick(&TickInput::at(tick / 10, TICK_US)).pulses)
        .max();
    assert_eq!(peak, Some(20), "held at the 200 kHz ceiling: 20 per tick");
}

/// Document 001: a step of more than half a turn cannot be told from a
/// step the other way round; the guard faults instead of reversing.
#[test]
fn a_master_step_above_the_guard_faults_instead_of_reversing() {
    let table = PointTable::from_pairs(&[(0, 0), (36_000, 36_000)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        single_turn: NonZeroU64::new(36_000),
        max_master_step: NonZeroU64::new(9_000),
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(table, config).unwrap();
    axis.arm().unwrap();
    let _ = axis.tick(&TickInput::at(0, TICK_US));
    let out = axis.tick(&TickInput::at(8_000, TICK_US));
    assert!(out.fault.is_none());
    // 20 000 forwards reads as 16 000 backwards: refused, not followed.
    let out = axis.tick(&TickInput::at(28_000, TICK_US));
    assert_eq!(out.fault, Some(ecam_engine::EngineError::MasterStep));
    assert_eq!(out.slave, 8_000, "held where it was");
    assert!(!out.state.is_active());
}

/// A seam whose command is an exact half pulse: the cycle's end (the
/// table's last value plus `k` strokes) and the next cycle's start (its
/// first value plus `k + 1`) are the same value split differently into
/// whole and fraction. Between whole counts the tick aims at the seam from
/// the old cycle; the next count takes it from the new one. Rounded halves
/// away from zero, the two sides came out a pulse apart, and a falling cam
/// stepped back up by one (found by `starts` at 30 000 cases: a motion
/// processor's cam on a coarse master, slave zoom −2/4).
#[test]
fn a_seam_on_an_exact_half_pulse_never_steps_back() {
    use ecam_core::CamCurve;
    for (table, num, den) in [
        (vec![(0, 0), (294, 47)], -2, 4),
        (vec![(0, 0), (294, 47)], 2, 4),
        (vec![(0, 0), (100, 5), (300, 31)], -1, 2),
        (vec![(0, 0), (120, -45)], 3, 6),
        (vec![(0, 0), (120, -45)], -3, 6),
    ] {
        let table = PointTable::from_pairs(&table).unwrap();
        let zoom = Zoom::signed(num, den).unwrap();
        let direction = (table.stroke() * i64::from(num)).signum();
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            slave_zoom: zoom,
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(table.clone(), config).unwrap();
        axis.set_max_frequency(1_000_000_000);
        axis.arm().unwrap();
        let mut last: Option<TickOutput> = None;
        // Quarter counts through 20 seams, each one landing on a whole count.
        for quarter in 0..(table.master_span() * 20 * 4) {
            let out = axis.tick(&TickInput {
                master_fraction: ((quarter % 4) as u32) << 30,
                ..TickInput::at(quarter / 4, TICK_US)
            });
            if let Some(last) = last {
                let step = out.slave - last.slave;
                assert!(
                    step == 0 || step.signum() == direction,
                    "zoom {num}/{den}, master {}+{}/4: {} to {}",
                    quarter / 4,
                    quarter % 4,
                    last.slave,
                    out.slave
                );
            }
            last = Some(out);
        }
    }
}
