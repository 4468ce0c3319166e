//! Switching the table of a running cam at a master position or at once
//! (PLCopen aborting), with and without a blend: the slave's position is
//! continuous, a blend's velocity stays between the two cams' and never
//! reverses, its acceleration stays within the documented bound, and the
//! cam is again a pure function of the master afterwards (zero drift).

use core::num::NonZeroU64;

use ecam_core::{CamCurve, PointTable};
use ecam_engine::{
    AxisConfig, AxisState, CamAxis, Coupling, EngineError, MasterFilter, StopKind, SwitchAt,
    TickInput, TickOutput, Zoom,
};
use proptest::prelude::*;

const TICK_US: u32 = 100;

fn line(slope: i64) -> PointTable {
    PointTable::from_pairs(&[(0, 0), (1000, 1000 * slope)]).unwrap()
}

fn repeat() -> AxisConfig {
    AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        ..AxisConfig::default()
    }
}

fn running(table: PointTable, config: AxisConfig) -> CamAxis<PointTable> {
    let mut axis = CamAxis::new(table, config).unwrap();
    axis.arm().unwrap();
    let _ = axis.tick(&TickInput::at(0, TICK_US));
    axis
}

fn blend(distance: u64) -> Option<NonZeroU64> {
    NonZeroU64::new(distance)
}

#[test]
fn an_aborting_switch_takes_over_at_once_without_a_step() {
    let mut axis = running(line(1), repeat());
    for m in 1..=500 {
        let _ = axis.tick(&TickInput::at(m, TICK_US));
    }
    axis.switch_curve(line(3), SwitchAt::Now { blend: None })
        .unwrap();
    assert!(axis.has_queued_curve());
    let out = axis.tick(&TickInput::at(501, TICK_US));
    assert!(out.events.table_switched);
    // Anchored on the old cam where the axis stood (master 500), then
    // the new slope.
    assert_eq!(out.slave, 503);
    assert_eq!(axis.tick(&TickInput::at(601, TICK_US)).slave, 500 + 303);
    assert!(axis.take_retired_curve().is_some());
}

#[test]
fn a_position_switch_takes_effect_exactly_at_its_position() {
    let mut axis = running(line(1), repeat());
    axis.switch_curve(
        line(3),
        SwitchAt::MasterPosition {
            position: 250,
            blend: None,
        },
    )
    .unwrap();
    assert!(
        !axis
            .tick(&TickInput::at(100, TICK_US))
            .events
            .table_switched
    );
    assert_eq!(axis.tick(&TickInput::at(200, TICK_US)).slave, 200);
    // The tick passes 250: old cam up to 250, the new one from there.
    let out = axis.tick(&TickInput::at(300, TICK_US));
    assert!(out.events.table_switched);
    assert_eq!(out.slave, 250 + 3 * 50);
    // Going back past the position keeps the new cam (a pure function).
    assert_eq!(axis.tick(&TickInput::at(200, TICK_US)).slave, 250 - 3 * 50);
}

#[test]
fn a_position_is_also_crossed_going_backwards() {
    let mut axis = running(line(2), repeat());
    for m in (-400..0).rev() {
        let _ = axis.tick(&TickInput::at(m, TICK_US));
    }
    axis.switch_curve(
        line(1),
        SwitchAt::MasterPosition {
            position: -450,
            blend: None,
        },
    )
    .unwrap();
    let out = axis.tick(&TickInput::at(-500, TICK_US));
    assert!(out.events.table_switched);
    assert_eq!(out.slave, -900 - 50);
}

/// The blend that would reverse if positions were mixed: from a fast cam
/// onto a standing one. Velocity-mixing never turns the slave back.
#[test]
fn a_blend_onto_a_slower_cam_never_reverses() {
    let mut axis = running(line(10), repeat());
    for m in 1..=100 {
        let _ = axis.tick(&TickInput::at(m, TICK_US));
    }
    axis.switch_curve(line(0).clone(), SwitchAt::Now { blend: blend(400) })
        .unwrap_or_else(|e| panic!("{e}"));
    let mut last = axis.commanded();
    let mut last_ratio = 10.0;
    for m in 101..=700 {
        let out = axis.tick(&TickInput::at(m, TICK_US));
        assert!(out.slave >= last, "master {m}: {} after {last}", out.slave);
        assert!(
            out.slave - last <= 11,
            "master {m}: step {}",
            out.slave - last
        );
        assert!((0.0..=10.0).contains(&out.velocity_ratio));
        // Acceleration bound: 1.5 times the velocity gap over the distance.
        assert!((out.velocity_ratio - last_ratio).abs() <= 1.5 * 10.0 / 400.0 + 1e-9);
        last = out.slave;
        last_ratio = out.velocity_ratio;
    }
    assert!(!axis.is_blending());
    // The slave stands still on the new (flat) cam once the blend is over.
    let held = axis.commanded();
    assert_eq!(axis.tick(&TickInput::at(900, TICK_US)).slave, held);
    assert!(axis.status().following);
}

#[test]
fn a_blend_onto_a_faster_cam_ends_on_its_velocity() {
    let mut axis = running(line(1), repeat());
    axis.switch_curve(
        line(5),
        SwitchAt::MasterPosition {
            position: 500,
            blend: blend(1000),
        },
    )
    .unwrap();
    let mut last = 0;
    let mut steps = Vec::new();
    for m in 1..=2000 {
        let out = axis.tick(&TickInput::at(m, TICK_US));
        steps.push(out.slave - last);
        last = out.slave;
        if (501..1500).contains(&m) {
            assert!(!out.following, "not in sync while blending");
        }
    }
    assert!(steps.iter().all(|s| (0..=6).contains(s)));
    // Before the switch the old velocity, after the blend the new one.
    assert!(steps[..500].iter().all(|&s| s == 1));
    assert!(
        steps[1500..].iter().all(|&s| s == 5),
        "{:?}",
        &steps[1490..1510]
    );
    assert!(axis.take_retired_curve().is_some());
}

#[test]
fn a_switch_during_an_end_of_cycle_stop_is_refused_and_idle_replaces() {
    let mut axis = running(line(1), repeat());
    let _ = axis.tick(&TickInput::at(100, TICK_US));
    axis.stop(StopKind::EndOfCycle);
    assert_eq!(
        axis.switch_curve(line(2), SwitchAt::Now { blend: None }),
        Err(EngineError::Busy)
    );
    axis.stop(StopKind::Immediate);
    let _ = axis.tick(&TickInput::at(100, TICK_US));
    assert_eq!(axis.state(), AxisState::Idle);
    axis.switch_curve(line(2), SwitchAt::Now { blend: None })
        .unwrap();
    assert_eq!(axis.curve().slave_last(), 2000);
    assert!(axis.take_retired_curve().is_some());
}

/// A table queued for the seam with a blend, the seam between two whole
/// master counts and the master followed with its fraction (an exact time
/// base; a coarse master's estimate is the same): the blend starts at the
/// last whole count before the seam, on the old cam there, so the ticks
/// between that count and the next move towards the blend's command, not
/// the seam's. Here the seam's value is a half pulse (rounded up) and the
/// last count's just below it (rounded down): aimed at the seam, the slave
/// went a pulse up and stepped back to where the blend began (found by
/// `switches_keep_the_slave_continuous_and_safe` at 3000 cases).
#[test]
fn a_blended_seam_switch_between_whole_counts_never_steps_back() {
    // Master zoom 4: the seam of cycle 0 at master 433.75; slave zoom
    // 1/2: there the cam is 932.5, at master 433 it is 932.47.
    // A master zoom of −4 runs the cycles backwards: the same seams from
    // the other side (the slave then falls).
    let old = PointTable::from_pairs(&[(0, 0), (1387, 1858), (1735, 1865)]).unwrap();
    let cases = [(8u32, 1u64), (8, 3), (8, 50), (4, 3), (2, 3)];
    for ((eighths, distance), zoom) in cases.into_iter().flat_map(|case| [(case, 4), (case, -4)]) {
        let direction = i64::from(zoom).signum();
        let config = AxisConfig {
            master_zoom: Zoom::signed(zoom, 1).unwrap(),
            slave_zoom: Zoom::new(1, 2).unwrap(),
            max_frequency_hz: 1_000_000_000,
            ..repeat()
        };
        let mut axis = running(old.clone(), config);
        axis.switch_curve(
            line(1),
            SwitchAt::NextSeam {
                blend: blend(distance),
            },
        )
        .unwrap();
        let mut last = axis.commanded();
        let mut switched = false;
        for step in 0..(600 * eighths) {
            let out = axis.tick(&TickInput {
                master_fraction: ((u64::from(step % eighths) << 32) / u64::from(eighths)) as u32,
                ..TickInput::at(i64::from(step / eighths), TICK_US)
            });
            assert!(
                (out.slave - last) * direction >= 0,
                "zoom {zoom}, blend {distance}, master {}+{}/{eighths}: {last} to {}",
                step / eighths,
                step % eighths,
                out.slave
            );
            switched |= out.events.table_switched;
            last = out.slave;
        }
        assert!(switched);
    }
}

/// A monotonic table and its steepest slope (slave per master count).
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

fn reversals(values: impl Iterator<Item = i64>) -> usize {
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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(64)))]

    /// The safe-motion properties through a switch: no position step (each
    /// tick's change within the steeper cam's velocity), no reversal the
    /// master did not make, pulses within the ceiling, and zero drift after.
    #[test]
    fn switches_keep_the_slave_continuous_and_safe(
        (old, old_steep) in any_monotonic_points(),
        (new, new_steep) in any_monotonic_points(),
        zoom in (1u16..5, 1u16..5),
        hz in prop_oneof![Just(200_000i64), 1_000i64..200_000],
        motion in prop::collection::vec((-20_000i64..60_000, 1u32..300), 1..6),
        switch_tick in 0usize..200,
        mode in 0u8..4,
        rezoom in 1u16..5,
        position_offset in -300i64..300,
        distance in prop_oneof![Just(0u64), 1u64..3000],
        every in prop_oneof![Just(1u32), 2u32..20],
    ) {
        let master_zoom = Zoom::new(zoom.0, 1).unwrap();
        let slave_zoom = Zoom::new(1, zoom.1).unwrap();
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            master_zoom,
            slave_zoom,
            max_frequency_hz: hz,
            // A master read every tick, or a coarse one the tracker spreads.
            master_filter: if every == 1 { MasterFilter::Direct } else { MasterFilter::INTERPOLATE },
            ..AxisConfig::default()
        };
        let old_cycle = old.master_span();
        let mut axis = CamAxis::new(old, config).unwrap();
        axis.arm().unwrap();
        // Mode 2 changes the master scaling instead of the table.
        let new_steep = if mode == 2 { old_steep * f64::from(rezoom) / f64::from(zoom.0) } else { new_steep };
        let steepest = old_steep.max(new_steep) * f64::from(zoom.0) / f64::from(zoom.1);

        let mut micro: i64 = 0;
        let mut held: i64 = 0;
        let mut readings = Vec::new();
        let mut outputs: Vec<TickOutput> = Vec::new();
        let mut speeds: Vec<i64> = motion
            .iter()
            .flat_map(|&(speed, ticks)| std::iter::repeat_n(speed, ticks as usize))
            .collect();
        speeds.extend(std::iter::repeat_n(0, 500));
        for (i, speed) in speeds.iter().enumerate() {
            if i == switch_tick {
                let at = match mode {
                    0 => SwitchAt::Now { blend: NonZeroU64::new(distance) },
                    3 => SwitchAt::NextSeam { blend: NonZeroU64::new(distance) },
                    _ => SwitchAt::MasterPosition {
                        position: readings.last().copied().unwrap_or(0) + position_offset,
                        blend: NonZeroU64::new(distance),
                    },
                };
                if mode == 2 {
                    // Before the first tick the cam is not running yet.
                    match axis.change_master_scaling(
                        Zoom::new(rezoom, 1).unwrap(),
                        NonZeroU64::new(distance),
                    ) {
                        Ok(()) | Err(EngineError::NotRunning) => {}
                        Err(e) => panic!("{e}"),
                    }
                } else {
                    axis.switch_curve(new.clone(), at).unwrap();
                }
            }
            micro += speed * i64::from(TICK_US);
            if (i as u64).is_multiple_of(u64::from(every)) {
                held = micro.div_euclid(1_000_000);
            }
            let master = held;
            readings.push(master);
            outputs.push(axis.tick(&TickInput::at(master, TICK_US)));
        }

        let ceiling = u128::from(hz.unsigned_abs()) * u128::from(TICK_US);
        for (i, w) in outputs.windows(2).enumerate() {
            // The followed master (the tracker's estimate), to within a count.
            let dm = (w[1].master - w[0].master).unsigned_abs() as f64
                + if every == 1 { 0.0 } else { 1.0 };
            let ds = (w[1].slave - w[0].slave).unsigned_abs() as f64;
            prop_assert!(ds <= steepest * dm * 1.0001 + 2.0,
                "tick {}: slave moved {ds} for {dm} master counts (steepest {steepest})", i + 1);
            prop_assert!(
                u128::from(w[1].pulses.unsigned_abs()) * 1_000_000 < ceiling + 1_000_000,
                "tick {}: {} pulses above {hz} Hz", i + 1, w[1].pulses
            );
        }
        let master_turns = reversals(readings.windows(2).map(|w| w[1] - w[0]));
        let slave_turns = reversals(outputs.windows(2).map(|w| w[1].slave - w[0].slave));
        prop_assert!(slave_turns <= master_turns,
            "slave reversed {slave_turns} times, master {master_turns}");
        prop_assert!(outputs.iter().filter(|o| o.events.table_switched).count() <= 1);

        // Zero drift: past any blend, the cam is a pure function of the master.
        let end = *readings.last().unwrap();
        // Far enough for a seam switch waiting up to one old cycle, then
        // its blend, to be over.
        let far = readings.iter().copied().max().unwrap_or(end)
            + old_cycle
            + distance as i64
            + 1_000;
        for m in end..=far {
            let _ = axis.tick(&TickInput::at(m, TICK_US));
        }
        let waiting = axis.has_queued_curve();
        prop_assert!(!axis.is_blending() || waiting);
        let there = axis.tick(&TickInput::at(far, TICK_US)).slave;
        for m in (far - 9_000..far).rev().step_by(7) {
            let _ = axis.tick(&TickInput::at(m, TICK_US));
        }
        for m in (far - 9_000..=far).step_by(5) {
            let _ = axis.tick(&TickInput::at(m, TICK_US));
        }
        let mut back = axis.tick(&TickInput::at(far, TICK_US));
        if !waiting {
            prop_assert_eq!(back.slave, there);
        }
        for _ in 0..crate::ticks_to_drain(back.backlog, hz, TICK_US) {
            if back.backlog == 0 {
                break;
            }
            back = axis.tick(&TickInput::at(far, TICK_US));
        }
        prop_assert_eq!(back.emitted, back.slave);
    }
}

/// A coarse master spread by the tracker: between two counts that straddle
/// a seam, the command must not run past the seam, or a table switched
/// there (requested after that tick) would take the slave back. Found by
/// `switches_keep_the_slave_continuous_and_safe`: a steep 7-count table
/// under master zoom 4 (several seams per tick), then a flat one.
#[test]
fn an_interpolated_master_never_overshoots_a_seam_switch() {
    let old = PointTable::from_pairs(&[(0, 0), (7, 328)]).unwrap();
    let new = PointTable::from_pairs(&[(0, 0), (348, 1)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        master_zoom: Zoom::new(4, 1).unwrap(),
        max_frequency_hz: 200_000,
        master_filter: MasterFilter::INTERPOLATE,
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(old, config).unwrap();
    axis.arm().unwrap();
    let mut slaves = Vec::new();
    for (i, master) in coarse_master(26_512, 43, 3, 120).into_iter().enumerate() {
        if i == 41 {
            axis.switch_curve(new.clone(), SwitchAt::NextSeam { blend: None })
                .unwrap();
        }
        let out = axis.tick(&TickInput::at(master, TICK_US));
        assert_eq!(out.events.table_switched, i == 41, "tick {i}");
        slaves.push(out.slave);
    }
    assert_one_way(&slaves, 1);
}

/// A blend ends where the position itself reaches its end. Running
/// backwards with a coarse master, the whole count (the floor) reaches
/// the end a count early; ending there put the command on the new cam's
/// line mid-count and took the slave back one pulse. Found by
/// `switches_keep_the_slave_continuous_and_safe` at 40,000 cases.
#[test]
fn a_blend_run_backwards_ends_without_a_reversal() {
    let old = PointTable::from_pairs(&[(0, 0), (109, 1)]).unwrap();
    let new = PointTable::from_pairs(&[(0, 0), (227, 667)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        master_zoom: Zoom::new(3, 1).unwrap(),
        slave_zoom: Zoom::new(1, 4).unwrap(),
        master_filter: MasterFilter::INTERPOLATE,
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(old, config).unwrap();
    axis.arm().unwrap();
    let mut slaves = Vec::new();
    let mut blended = false;
    for (i, master) in coarse_master(-2901, 107, 9, 200).into_iter().enumerate() {
        if i == 30 {
            axis.switch_curve(new.clone(), SwitchAt::Now { blend: blend(25) })
                .unwrap();
        }
        slaves.push(axis.tick(&TickInput::at(master, TICK_US)).slave);
        blended |= axis.is_blending();
    }
    assert!(blended && !axis.is_blending());
    assert_one_way(&slaves, -1);
}

/// A master moving at `speed` counts/s for the first `moving` ticks and
/// then standing, read only every `every` ticks (a coarse counter the
/// tracker spreads): its reading at each of `ticks` ticks.
fn coarse_master(speed: i64, moving: usize, every: usize, ticks: usize) -> Vec<i64> {
    let (mut micro, mut held) = (0i64, 0i64);
    (0..ticks)
        .map(|i| {
            if i < moving {
                micro += speed * i64::from(TICK_US);
            }
            if i % every == 0 {
                held = micro.div_euclid(1_000_000);
            }
            held
        })
        .collect()
}

/// Fails at the first tick where the slave moves against `direction` (±1).
fn assert_one_way(slaves: &[i64], direction: i64) {
    for (i, w) in slaves.windows(2).enumerate() {
        assert!(
            (w[1] - w[0]) * direction >= 0,
            "tick {}: slave {} after {}",
            i + 1,
            w[1],
            w[0]
        );
    }
}

/// A blend shorter than one tick's master travel is over within the tick
/// of the switch: the command is on the new cam there, not held at the
/// blend's end for a tick and then caught up in a burst. Found by
/// `switches_keep_the_slave_continuous_and_safe` at 100,000 cases.
#[test]
fn a_blend_passed_within_the_switch_tick_is_not_held() {
    let old = PointTable::from_pairs(&[(0, 0), (19, 1)]).unwrap();
    let new = PointTable::from_pairs(&[(0, 0), (1, 1)]).unwrap();
    let config = AxisConfig {
        master_zoom: Zoom::new(2, 1).unwrap(),
        ..repeat()
    };
    let mut axis = CamAxis::new(old, config).unwrap();
    axis.arm().unwrap();
    let mut last: Option<(i64, i64)> = None;
    for i in 0..30i64 {
        if i == 11 {
            axis.switch_curve(new.clone(), SwitchAt::Now { blend: blend(1) })
                .unwrap();
        }
        // 2.33 counts a tick, then rest.
        let master = (i.min(14) + 1) * 23_334 * i64::from(TICK_US) / 1_000_000;
        let out = axis.tick(&TickInput::at(master, TICK_US));
        if let Some((m0, s0)) = last {
            // The new cam's 2 pulses a count is the steepest.
            assert!(
                out.slave - s0 <= 2 * (master - m0),
                "tick {i}: {s0} -> {}",
                out.slave
            );
        }
        last = Some((master, out.slave));
    }
    assert!(!axis.is_blending());
}

/// A table that counts how many of its kind were dropped, and where: the
/// tick must never free one (docs/engine.md, "Changing the table").
struct Counted {
    table: PointTable,
    drops: std::rc::Rc<std::cell::Cell<usize>>,
}

impl Drop for Counted {
    fn drop(&mut self) {
        self.drops.set(self.drops.get() + 1);
    }
}

impl CamCurve for Counted {
    fn master_first(&self) -> i64 {
        self.table.master_first()
    }
    fn master_last(&self) -> i64 {
        self.table.master_last()
    }
    fn slave_first(&self) -> i64 {
        self.table.slave_first()
    }
    fn slave_last(&self) -> i64 {
        self.table.slave_last()
    }
    fn segment_count(&self) -> usize {
        self.table.segment_count()
    }
    fn eval(&self, master: f64, cursor: &mut ecam_core::Cursor) -> ecam_core::Kinematics {
        self.table.eval(master, cursor)
    }
}

/// A caller that never takes the retired tables back: each new request
/// drops the one retired before (outside the tick), so the ticks that
/// switch, at once, at a position, at the seam or by ending a run with a
/// table waiting, free nothing.
#[test]
fn a_switch_tick_never_frees_a_table_the_caller_left_retired() {
    let drops = std::rc::Rc::new(std::cell::Cell::new(0));
    let counted = |slope| Counted {
        table: line(slope),
        drops: drops.clone(),
    };
    let mut axis = CamAxis::new(counted(1), repeat()).unwrap();
    axis.arm().unwrap();
    let master = std::cell::Cell::new(0i64);
    let run = |axis: &mut CamAxis<Counted>, ticks: usize| {
        for _ in 0..ticks {
            master.set(master.get() + 7);
            let before = drops.get();
            let out = axis.tick(&TickInput::at(master.get(), TICK_US));
            assert!(out.fault.is_none(), "{out:?}");
            assert_eq!(
                drops.get(),
                before,
                "a tick freed a table at {}",
                master.get()
            );
        }
    };
    run(&mut axis, 3);
    for i in 0..4 {
        let at = match i {
            0 => SwitchAt::Now { blend: None },
            1 => SwitchAt::MasterPosition {
                position: master.get() + 200,
                blend: blend(50),
            },
            2 => SwitchAt::NextSeam { blend: None },
            _ => SwitchAt::Now { blend: blend(30) },
        };
        let slope = 2 + i;
        axis.switch_curve(counted(slope), at).unwrap();
        run(&mut axis, 400);
        assert!(!axis.has_queued_curve(), "request {i} never landed");
    }
    // A table waiting when the run ends takes over then, also without
    // freeing the one retired before it.
    axis.switch_curve(
        counted(9),
        SwitchAt::MasterPosition {
            position: i64::MAX / 2,
            blend: None,
        },
    )
    .unwrap();
    axis.stop(StopKind::EndOfCycle);
    run(&mut axis, 400);
    assert_eq!(axis.state(), AxisState::Finished);
    assert!(axis.take_retired_curve().is_some());
}
