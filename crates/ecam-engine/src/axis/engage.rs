//! Engaging the cam: the engagement at the start position and the ramp-in
//! that catches the slave up, under limits when they are set.
//!
//! A start at a master position knows where it engages when it is armed,
//! so its engagement (the table search and the start rule's stroke choice,
//! most of the engaging tick's work) is worked out then, and the tick that
//! engages takes it if nothing it depends on moved since: the same
//! engagement, off the real-time path (docs/engine.md, "Benchmarks").

use core::num::NonZeroU64;

use ecam_core::CamCurve;

use crate::coupling::{Engagement, Place, Sample};
use crate::ramp::Ramp;
use crate::ramp_in::{RampDirection, RampInLimits};
use crate::rounding::exact_f64;
use crate::steady::Table;
use crate::{EngineError, RampIn, StartMode};

use super::phase::{Armed, Engaged, Phase};
use super::underway::Underway;
use super::{CamAxis, FollowSample, clamp_i64};

/// An engagement worked out before the tick that engages: of master `at`
/// from slave `slave`, on the table, geometry and configuration the axis
/// had when it was armed (they cannot change while it is armed without
/// preparing it again, see [`CamAxis::prepare_engagement`]), with the
/// table's value and slope at the place.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ReadyEngagement {
    at: i64,
    slave: i64,
    engagement: Engagement,
    place: Place,
    table: Table,
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
                .map(|(engagement, place, table)| ReadyEngagement {
                    at: position,
                    slave: self.commanded,
                    engagement,
                    place,
                    table,
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
                Some((ready.engagement, ready.place, ready.table))
            }
            _ => None,
        };
        // The place of `at` and the table there come with it (the table
        // input there is the one the engagement fixed).
        let (mut engagement, place, table) = match ready {
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
        // engaging tick's sample.
        let (ramp_in, mut cam) = match self.ramp_limits {
            Some(limits) => {
                let (ramp, cam) = self.limited_ramp(limits, &mut engagement, place, table)?;
                (ramp, Some(cam))
            }
            None => (self.config.ramp_in, None),
        };
        let ramp = ramp_in.map(|ramp| Ramp::new(ramp, at, self.commanded));
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
                .sample_of(&self.geometry, place, table)
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

    /// The ramp-in that keeps to `limits` for the engagement at `place`
    /// (the table's value and slope there `table`), after moving its
    /// target by whole strokes for a restricted direction; with the cam's
    /// sample there under the engagement as it ends up.
    fn limited_ramp(
        &mut self,
        limits: RampInLimits,
        engagement: &mut Engagement,
        place: Place,
        table: Table,
    ) -> Result<(Option<RampIn>, Sample), EngineError> {
        let hold = i128::from(self.commanded);
        let geo = &self.geometry;
        let mut cam = engagement.sample_of(geo, place, table)?;
        let wrong_way = |slave: i64| {
            let gap = i128::from(slave) - hold;
            match limits.direction {
                RampDirection::Either => false,
                RampDirection::Positive => gap < 0,
                RampDirection::Negative => gap > 0,
            }
        };
        if wrong_way(cam.slave) {
            let stroke = geo.stroke_pulses();
            if stroke == 0.0 {
                return Err(EngineError::RampDirection);
            }
            let gap = exact_f64(i128::from(cam.slave) - hold);
            let strokes = libm::ceil(libm::fabs(gap / stroke));
            let toward = match limits.direction {
                RampDirection::Negative => -1.0,
                _ => 1.0,
            };
            let n = strokes * toward * libm::copysign(1.0, stroke);
            // Whole strokes move the cam's output, not its place: the
            // table there is the same.
            engagement.add_strokes(n as i128);
            cam = engagement.sample_of(geo, place, table)?;
            if wrong_way(cam.slave) {
                // Rounding left it a pulse short: one stroke more.
                engagement.add_strokes(libm::copysign(1.0, n) as i128);
                cam = engagement.sample_of(geo, place, table)?;
            }
        }
        let gap = exact_f64(i128::from(cam.slave) - hold);
        let needed = limits.distance(gap, cam.velocity_ratio, self.speed.bound())?;
        let configured = self.config.ramp_in.map(|r| r.distance.get());
        let ramp = match (needed, configured) {
            (Some(a), Some(b)) => NonZeroU64::new(a.max(b)),
            (Some(d), None) | (None, Some(d)) => NonZeroU64::new(d),
            // A master at rest gives no speed to size the ramp for: one
            // master count per 1/1.875 pulse of gap.
            (None, None) => NonZeroU64::new(libm::ceil(1.875 * libm::fabs(gap)).max(1.0) as u64),
        }
        .map(|distance| RampIn { distance });
        Ok((ramp, cam))
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use core::num::NonZeroU64;

    use ecam_core::PointTable;
    use proptest::prelude::*;
    use std::vec::Vec;

    use super::super::phase::{Armed, Phase};
    use super::super::steady_tests::{limits_towards, table};
    use crate::coupling::Engagement;
    use crate::{AxisConfig, CamAxis, Coupling, RampIn, SlaveAlign, StartMode, TickInput, Zoom};

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
            // As a restricted direction moves it.
            engagement.add_strokes(strokes);
            let known = engagement.sample_of(geo, place, kin);
            let mut fresh = ecam_core::Cursor::new();
            let general = engagement.sample(geo, &axis.curve, &mut fresh, place);
            match (known, general) {
                (Ok(a), Ok(b)) => {
                    prop_assert_eq!(a.place, b.place);
                    prop_assert_eq!(a.slave, b.slave);
                    prop_assert_eq!(a.unzoomed, b.unzoomed);
                    prop_assert_eq!(a.in_cycle_zoomed, b.in_cycle_zoomed);
                    prop_assert_eq!(a.velocity_ratio.to_bits(), b.velocity_ratio.to_bits());
                    let steady = engagement
                        .steady(geo)
                        .and_then(|c| Some((c, c.sample(at, &axis.curve, &mut fresh)?)));
                    if let Some((constants, s)) = steady {
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
                (a, b) => prop_assert_eq!(a.is_ok(), b.is_ok()),
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
}
