//! Engaging the cam: the engagement at the start position and the ramp-in
//! that catches the slave up, under limits when they are set.
//!
//! A start at a master position knows where it engages when it is armed,
//! so its engagement (the table search and the start rule's stroke choice,
//! most of the engaging tick's work) is worked out then, and the tick that
//! engages takes it if nothing it depends on moved since: the same
//! engagement, off the real-time path (docs/engine.md, "Benchmarks").

use ecam_core::CamCurve;

use crate::coupling::{AtEngage, Engagement, Place, Sample};
use crate::ramp::Ramp;
use crate::ramp_in::{LimitedLength, RampDirection, RampInLimits};
use crate::rounding::{ceil_whole, exact_f64, whole_to_i128};
use crate::{EngineError, StartMode};

use super::phase::{Armed, Engaged, Phase};
use super::underway::Underway;
use super::{CamAxis, FollowSample, clamp_i64};

/// An engagement worked out before the tick that engages: of master `at`
/// from slave `slave`, on the table, geometry and configuration the axis
/// had when it was armed (they cannot change while it is armed without
/// preparing it again, see [`CamAxis::prepare_engagement`]), with what
/// it found at its place (the table's value and slope, the slave).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ReadyEngagement {
    at: i64,
    slave: i64,
    engagement: Engagement,
    place: Place,
    found: AtEngage,
}

impl<C: CamCurve> CamAxis<C> {
    /// Works out an armed axis' engagement ahead when its master position
    /// is known now: a start at a master position on a master that is not
    /// single-turn (there the position comes round each turn). Anything
    /// else, or an engagement that fails (the tick that engages reports
    /// it), leaves it to that tick. Called at arm and whenever the table
    /// or geometry changes while armed.
    pub(super) fn prepare_engagement(&mut self) {
        let Phase::Armed(armed) = &mut self.phase else {
            return;
        };
        armed.ready = match self.config.start {
            StartMode::AtMasterPosition { position, .. } if self.config.single_turn.is_none() => {
                Engagement::placed(
                    &self.geometry,
                    &self.config,
                    &self.curve,
                    &mut self.cursor,
                    position,
                    self.commanded,
                )
                .ok()
                .map(|(engagement, place, found)| ReadyEngagement {
                    at: position,
                    slave: self.commanded,
                    engagement,
                    place,
                    found,
                })
            }
            _ => None,
        };
    }

    /// Engages the cam at master `at` from the slave where it stands.
    ///
    /// With a ramp-in, the engaging tick commands the slave where it
    /// stands (the ramp's weight is 0 where it starts): at a whole master
    /// count on the fast route (`whole`), that tick's sample is given
    /// back from the engagement's own table lookup, so the tick needs
    /// neither the lane nor its constants (the next tick takes them).
    /// The general route (`whole` off) follows the tick as any other, and
    /// the steady-vs-general property test holds the two the same.
    pub(super) fn engage(
        &mut self,
        at: i64,
        whole: bool,
    ) -> Result<Option<FollowSample>, EngineError> {
        // Prepared at arm when it is of this master and slave (the slave
        // may have been moved since, see `discard_backlog`).
        let ready = match &self.phase {
            Phase::Armed(Armed {
                ready: Some(ready), ..
            }) if ready.at == at && ready.slave == self.commanded => {
                Some((ready.engagement, ready.place, ready.found))
            }
            _ => None,
        };
        // The place of `at` and what the cam gives there come with it
        // (the table input there is the one the engagement fixed).
        let (mut engagement, place, found) = match ready {
            Some(ready) => ready,
            None => Engagement::placed(
                &self.geometry,
                &self.config,
                &self.curve,
                &mut self.cursor,
                at,
                self.commanded,
            )?,
        };
        // Under limits the cam at `at` sizes the ramp, and is the
        // engaging tick's sample. The ramp is sized where it is first
        // read, after this (`CamAxis::size_ramp_in`): on the next tick
        // when this one answers from the engagement (below), where the
        // ramp holds the slave whatever its length (`Ramp::to_size`).
        let (ramp, mut cam) = match self.ramp_limits {
            Some(limits) => {
                let cam = self.limited_ramp(limits, &mut engagement, place, found)?;
                (Some(Ramp::to_size(at, self.commanded)), Some(cam))
            }
            None => {
                self.ramp_sizing = None;
                let ramp = self.config.ramp_in;
                (ramp.map(|ramp| Ramp::new(ramp, at, self.commanded)), None)
            }
        };
        self.phase = Phase::Running(Engaged {
            engagement,
            place,
            followed: i128::from(at) << 32,
            underway: Underway::at_engage(ramp),
            lane: None,
            plan: None,
        });
        let Phase::Running(engaged) = &mut self.phase else {
            return Ok(None);
        };
        // Without a ramp-in the cam is settled from the first tick: its
        // constants taken here let that tick be a steady one (set in
        // place: the phase is not built twice).
        let Some(ramp) = ramp else {
            engaged
                .underway
                .settle(engaged.engagement.steady(&self.geometry));
            return Ok(None);
        };
        // A one-shot of no length ends where it engages: the general
        // tick's business.
        let ends_here = engaged
            .engagement
            .span
            .is_some_and(|(begin, end)| end <= begin);
        if !whole || ends_here {
            // The ramp-in tick follows the cam with the lane's constants.
            engaged.take_lane_constants(&self.geometry);
            return Ok(None);
        }
        if cam.is_none() {
            // An error here is the general tick's to report, as it would.
            cam = engaged
                .engagement
                .sample_at_engage(&self.geometry, place, found)
                .ok();
        }
        let Some(cam) = cam else {
            engaged.take_lane_constants(&self.geometry);
            return Ok(None);
        };
        // What the general tick follows at `at`: the place the engagement
        // fixed, the slave held (the ramp's start).
        let Some(slave) = ramp.blend(at, cam.slave) else {
            engaged.take_lane_constants(&self.geometry);
            return Ok(None);
        };
        Ok(Some(FollowSample {
            master_in_cycle: self.geometry.input_in_cycle(place),
            master_in_cycle_raw: self.geometry.raw_in_cycle(place),
            cycle: clamp_i64(place.k.saturating_sub(engaged.engagement.k_engage)),
            unzoomed: cam.unzoomed,
            in_cycle_zoomed: cam.in_cycle_zoomed,
            velocity_ratio: cam.velocity_ratio * ramp.weight(at),
            following: false,
            input_offset: engaged.engagement.input_offset(&self.geometry),
            slave,
        }))
    }

    /// Keeps what sizes the ramp-in that keeps to `limits` for the
    /// engagement at `place` (what the cam gives there `found`) for the
    /// tick that sizes it (`ramp_sizing`), after moving its target by
    /// whole strokes for a restricted direction; gives the cam's sample
    /// there under the engagement as it ends up.
    fn limited_ramp(
        &mut self,
        limits: RampInLimits,
        engagement: &mut Engagement,
        place: Place,
        found: AtEngage,
    ) -> Result<Sample, EngineError> {
        let hold = i128::from(self.commanded);
        let geo = &self.geometry;
        let wrong_way = |slave: i64| {
            let gap = i128::from(slave) - hold;
            match limits.direction {
                RampDirection::Either => false,
                RampDirection::Positive => gap < 0,
                RampDirection::Negative => gap > 0,
            }
        };
        // The slave alone while the strokes are chosen, the whole sample
        // once, where they end up (the same sample, fewer steps).
        let cam = match engagement.slave_at_engage(found) {
            Some(slave) if !wrong_way(slave) => {
                engagement.sample_with_slave(geo, place, found.table, slave)?
            }
            first => {
                let mut slave = match first {
                    Some(slave) => slave,
                    None => engagement.sample_of(geo, place, found.table)?.slave,
                };
                if wrong_way(slave) {
                    let stroke = geo.stroke_pulses();
                    if stroke == 0.0 {
                        return Err(EngineError::RampDirection);
                    }
                    let gap = exact_f64(i128::from(slave) - hold);
                    let strokes = ceil_whole(libm::fabs(gap / stroke));
                    let toward = match limits.direction {
                        RampDirection::Negative => -1.0,
                        _ => 1.0,
                    };
                    let n = strokes * toward * libm::copysign(1.0, stroke);
                    // Whole strokes move the cam's output, not its place:
                    // the table there is the same.
                    let n = whole_to_i128(n);
                    engagement.add_strokes(n);
                    slave = engagement.slave_after_strokes(geo, place, found.table, slave, n)?;
                    if wrong_way(slave) {
                        // Rounding left it a pulse short: one stroke more.
                        let one = if n < 0 { -1 } else { 1 };
                        engagement.add_strokes(one);
                        slave =
                            engagement.slave_after_strokes(geo, place, found.table, slave, one)?;
                    }
                }
                engagement.sample_with_slave(geo, place, found.table, slave)?
            }
        };
        let gap = exact_f64(i128::from(cam.slave) - hold);
        self.ramp_sizing = Some(LimitedLength::new(
            limits,
            gap,
            cam.velocity_ratio,
            self.speed.bound(),
            self.config.ramp_in.map(|r| r.distance),
        )?);
        Ok(cam)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use core::num::{NonZeroU32, NonZeroU64};

    use ecam_core::PointTable;
    use proptest::prelude::*;
    use std::vec::Vec;

    use super::super::phase::{Armed, Phase};
    use super::super::steady_tests::{limits_towards, table};
    use crate::coupling::Engagement;
    use crate::{
        AxisConfig, CamAxis, Coupling, RampIn, RampInLimits, SlaveAlign, StartMode, TickInput, Zoom,
    };

    /// The engagement an armed axis holds ready.
    fn ready(axis: &CamAxis<PointTable>) -> Option<super::ReadyEngagement> {
        match &axis.phase {
            Phase::Armed(Armed { ready, .. }) => *ready,
            _ => None,
        }
    }

    /// An armed copy of `axis` that holds nothing ready: its engaging
    /// tick works the engagement out, as every start did before.
    fn unprepared(axis: &CamAxis<PointTable>) -> CamAxis<PointTable> {
        let mut copy = axis.clone();
        if let Phase::Armed(armed) = &mut copy.phase {
            armed.ready = None;
        }
        copy
    }

    /// Two routes' samples are the same, field for field, or both fail.
    fn same_sample(
        a: Result<crate::coupling::Sample, crate::EngineError>,
        b: Result<crate::coupling::Sample, crate::EngineError>,
    ) -> Result<(), TestCaseError> {
        match (a, b) {
            (Ok(a), Ok(b)) => {
                prop_assert_eq!(a.place, b.place);
                prop_assert_eq!(a.slave, b.slave);
                prop_assert_eq!(a.unzoomed, b.unzoomed);
                prop_assert_eq!(a.in_cycle_zoomed, b.in_cycle_zoomed);
                prop_assert_eq!(a.velocity_ratio.to_bits(), b.velocity_ratio.to_bits());
            }
            (a, b) => prop_assert_eq!(a.is_ok(), b.is_ok()),
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// An engagement prepared at arm (and again after a table change
        /// while armed) gives the engaging tick, and every tick after it,
        /// exactly what working it out in that tick gives.
        #[test]
        fn a_prepared_engagement_is_the_one_the_tick_would_work_out(
            slaves in proptest::collection::vec(-20_000i64..20_000, 2..12),
            step in 1i64..3000,
            coupling in prop_oneof![
                Just(Coupling::Periodic),
                Just(Coupling::Repeat { min_stroke: 1 }),
                Just(Coupling::Normal),
                Just(Coupling::OneShot { repeats: 1 }),
            ],
            align in prop_oneof![
                Just(SlaveAlign::Relative),
                Just(SlaveAlign::Absolute),
                Just(SlaveAlign::NearestEquivalent),
                (-5000i64..5000).prop_map(SlaveAlign::Offset),
            ],
            mzoom in (1i32..20, 1u16..20),
            szoom in (prop_oneof![(-19i32..-1), (1i32..20)], 1u16..20),
            position in -100_000i64..100_000,
            slave in -1_000_000i64..1_000_000,
            after_edge in any::<bool>(),
            ramp_in in proptest::option::of(1u64..3000),
            requeue in proptest::option::of(-3i64..4),
            limits in proptest::option::of(0u8..3),
            start in -100_000i64..100_000,
            steps in proptest::collection::vec(-500i64..3000, 1..60),
        ) {
            let config = AxisConfig {
                coupling,
                slave_align: align,
                master_zoom: Zoom::signed(mzoom.0, mzoom.1).unwrap(),
                slave_zoom: Zoom::signed(szoom.0, szoom.1).unwrap(),
                start: StartMode::AtMasterPosition { position, after_edge },
                ramp_in: ramp_in.and_then(NonZeroU64::new).map(|distance| RampIn { distance }),
                ..AxisConfig::default()
            };
            let Ok(mut axis) = CamAxis::new(table(&slaves, step), config) else {
                return Ok(());
            };
            axis.set_slave_position(slave).unwrap();
            axis.set_ramp_in_limits(limits.map(limits_towards));
            axis.arm().unwrap();
            if let Some(factor) = requeue {
                let scaled: Vec<i64> = slaves.iter().map(|s| s * factor).collect();
                axis.queue_curve(table(&scaled, step)).unwrap();
            }
            // Ready exactly when the engagement can be worked out.
            let mut cursor = ecam_core::Cursor::new();
            let fresh = Engagement::placed(
                &axis.geometry, &axis.config, &axis.curve, &mut cursor, position, slave,
            );
            prop_assert_eq!(ready(&axis).is_some(), fresh.is_ok());
            if let (Some(ready), Ok((engagement, place, _))) = (ready(&axis), fresh) {
                prop_assert_eq!((ready.engagement, ready.place), (engagement, place));
            }
            let mut reference = unprepared(&axis);
            let mut master = start;
            // Through the start position from the start, then on.
            let mut moves = Vec::from([0, position - start]);
            moves.extend(steps);
            for (i, d) in moves.into_iter().enumerate() {
                master += d;
                let input = TickInput {
                    start_input: i >= 1,
                    ..TickInput::at(master, 100)
                };
                let a = axis.tick(&input);
                let b = reference.tick(&input);
                prop_assert_eq!(a, b, "tick {} at master {}", i, master);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]
        /// The engaging tick's sample, from the table value and slope the
        /// engagement looked up (what sizing a ramp-in under limits reads
        /// and a ramp-in's engaging tick reports), is the general route's
        /// sample with its own lookup, and the steady constants' sample
        /// where they hold it (what the lane reads on the ticks after),
        /// also after a restricted direction moved it by whole strokes.
        #[test]
        fn the_engaging_sample_is_the_same_by_every_route(
            slaves in proptest::collection::vec(-20_000i64..20_000, 2..12),
            step in 1i64..3000,
            coupling in prop_oneof![
                Just(Coupling::Periodic),
                Just(Coupling::Repeat { min_stroke: 1 }),
                Just(Coupling::Normal),
                Just(Coupling::OneShot { repeats: 2 }),
            ],
            align in prop_oneof![
                Just(SlaveAlign::Relative),
                Just(SlaveAlign::Absolute),
                Just(SlaveAlign::NearestEquivalent),
                (-5000i64..5000).prop_map(SlaveAlign::Offset),
            ],
            mzoom in (prop_oneof![(-19i32..-1), (1i32..20)], 1u16..20),
            szoom in (prop_oneof![(-19i32..-1), (1i32..20)], 1u16..20),
            at in -10_000_000i64..10_000_000,
            slave in -1_000_000i64..1_000_000,
            strokes in -3i128..4,
        ) {
            let config = AxisConfig {
                coupling,
                slave_align: align,
                master_zoom: Zoom::signed(mzoom.0, mzoom.1).unwrap(),
                slave_zoom: Zoom::signed(szoom.0, szoom.1).unwrap(),
                ..AxisConfig::default()
            };
            let Ok(axis) = CamAxis::new(table(&slaves, step), config) else {
                return Ok(());
            };
            let geo = &axis.geometry;
            let mut cursor = ecam_core::Cursor::new();
            let Ok((mut engagement, place, kin)) = Engagement::placed(
                geo, &axis.config, &axis.curve, &mut cursor, at, slave,
            ) else {
                return Ok(());
            };
            // As the engaging tick reads it, with the slave `placed`
            // worked out: the general sample, field for field.
            let mut fresh = ecam_core::Cursor::new();
            let at_engage = engagement.sample_at_engage(geo, place, kin);
            same_sample(at_engage, engagement.sample(geo, &axis.curve, &mut fresh, place))?;
            // As a restricted direction moves it: the slave alone, from
            // the one before (where it is known), and the whole sample.
            let before = engagement.slave_of(geo, place, kin.table);
            engagement.add_strokes(strokes);
            let known = engagement.sample_of(geo, place, kin.table);
            if let Ok(before) = before {
                let after = engagement.slave_after_strokes(geo, place, kin.table, before, strokes);
                prop_assert_eq!(after, engagement.slave_of(geo, place, kin.table));
                prop_assert_eq!(after.ok(), known.ok().map(|k| k.slave));
            }
            let general = engagement.sample(geo, &axis.curve, &mut fresh, place);
            same_sample(known, general)?;
            // The steady constants' sample where they hold it.
            let steady = engagement
                .steady(geo)
                .and_then(|c| Some((c, c.sample(at, &axis.curve, &mut fresh)?)));
            if let (Ok(a), Some((constants, s))) = (known, steady) {
                prop_assert_eq!((i128::from(s.k), i128::from(s.r_num)), (place.k, place.r_num));
                prop_assert_eq!(s.slave, a.slave);
                prop_assert_eq!(s.unzoomed, a.unzoomed);
                prop_assert_eq!(s.in_cycle_zoomed, a.in_cycle_zoomed);
                prop_assert_eq!(s.velocity_ratio.to_bits(), a.velocity_ratio.to_bits());
                prop_assert_eq!(s.master_in_cycle, geo.input_in_cycle(place));
                prop_assert_eq!(s.master_in_cycle_raw, geo.raw_in_cycle(place));
                prop_assert_eq!(constants.input_offset, engagement.input_offset(geo));
            }
        }
    }

    #[test]
    fn only_a_known_start_position_is_prepared() {
        let curve = table(&[0, 700, 1000], 100);
        let at = |start| AxisConfig {
            start,
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        };
        let position = StartMode::AtMasterPosition {
            position: 150,
            after_edge: false,
        };
        let mut axis = CamAxis::new(curve.clone(), at(position)).unwrap();
        axis.arm().unwrap();
        assert!(ready(&axis).is_some());
        // Engaging there takes it, and the engagement it holds is the one
        // in use.
        let kept = ready(&axis).map(|r| r.engagement);
        let _ = axis.tick(&TickInput::at(100, 100));
        let _ = axis.tick(&TickInput::at(200, 100));
        let Phase::Running(engaged) = &axis.phase else {
            panic!("not engaged");
        };
        assert_eq!(Some(engaged.engagement), kept);

        let mut now = CamAxis::new(curve.clone(), at(StartMode::Immediate)).unwrap();
        now.arm().unwrap();
        assert!(ready(&now).is_none());
        // A single-turn master's position comes round each turn.
        let turn = AxisConfig {
            single_turn: NonZeroU64::new(1000),
            ..at(position)
        };
        let mut turning = CamAxis::new(curve, turn).unwrap();
        turning.arm().unwrap();
        assert!(ready(&turning).is_none());
    }

    /// A ramp-in under limits that engages on a tick the engagement
    /// answers is sized on the next tick, from the figures of the tick
    /// that engaged: limits changed in between (they are for the next
    /// engagements) and the master's speed on the tick after do not
    /// change it, and the ticks are those of an axis that sized it at
    /// once (the general route); a stop before the next tick leaves
    /// nothing for a later engagement to pick up.
    #[test]
    fn a_limited_ramp_is_sized_on_the_next_tick_from_the_engaging_figures() {
        let curve = table(&[0, 700, 1500, 1000, 2600], 300);
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(curve, config).unwrap();
        axis.set_slave_position(-4000).unwrap();
        axis.set_ramp_in_limits(Some(limits_towards(1)));
        let mut master = 0;
        for _ in 0..40 {
            master += 13;
            let _ = axis.tick(&TickInput::at(master, 100));
        }
        axis.arm().unwrap();
        master += 13;
        let input = TickInput::at(master, 100);
        let mut general = axis.clone();
        assert!(axis.tick(&input).events.engaged);
        assert!(general.step(&input, false).events.engaged);
        // Held, unsized, the figures kept; the general route sized it.
        let unsized_ramp = |a: &CamAxis<PointTable>| match &a.phase {
            Phase::Running(engaged) => engaged.ramp_in().map(|ramp| !ramp.sized()),
            _ => None,
        };
        assert_eq!(unsized_ramp(&axis), Some(true));
        assert!(axis.ramp_sizing.is_some());
        assert_eq!(unsized_ramp(&general), Some(false));
        assert!(general.ramp_sizing.is_none());
        // Other limits for later engagements, set before the next tick,
        // and a master that then runs four times as fast.
        axis.set_ramp_in_limits(Some(RampInLimits {
            max_velocity: NonZeroU32::new(50_000).unwrap(),
            ..limits_towards(0)
        }));
        general.set_ramp_in_limits(axis.ramp_limits);
        let mut following = false;
        for i in 0..2000 {
            master += 52;
            let input = TickInput::at(master, 100);
            let a = axis.tick(&input);
            let b = *general.step(&input, false);
            assert_eq!(a, b, "tick {i}");
            assert_eq!(unsized_ramp(&axis), unsized_ramp(&general));
            following |= a.following;
            if a.following {
                break;
            }
        }
        assert!(following, "the ramp ends");
        assert!(axis.ramp_sizing.is_none());

        // Stopped on the tick after engaging, before any tick sized it:
        // the next engagement, without limits, has its own ramp.
        let ramped = AxisConfig {
            ramp_in: NonZeroU64::new(300).map(|distance| RampIn { distance }),
            ..config
        };
        let mut axis = CamAxis::new(table(&[0, 700, 1500, 1000, 2600], 300), ramped).unwrap();
        axis.set_slave_position(-4000).unwrap();
        axis.set_ramp_in_limits(Some(limits_towards(0)));
        for _ in 0..40 {
            master += 13;
            let _ = axis.tick(&TickInput::at(master, 100));
        }
        axis.arm().unwrap();
        master += 13;
        assert!(axis.tick(&TickInput::at(master, 100)).events.engaged);
        assert!(axis.ramp_sizing.is_some());
        axis.stop(crate::StopKind::Immediate);
        axis.set_ramp_in_limits(None);
        let mut fresh = axis.clone();
        fresh.ramp_sizing = None;
        axis.arm().unwrap();
        fresh.arm().unwrap();
        for i in 0..200 {
            master += 13;
            let input = TickInput::at(master, 100);
            assert_eq!(axis.tick(&input), fresh.tick(&input), "tick {i}");
        }
    }
}
