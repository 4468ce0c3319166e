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

use crate::coupling::{Engagement, Place};
use crate::ramp::Ramp;
use crate::ramp_in::{RampDirection, RampInLimits};
use crate::rounding::exact_f64;
use crate::steady::Steady;
use crate::{EngineError, RampIn, StartMode};

use super::CamAxis;
use super::lane_constants::LaneConstants;
use super::phase::{Armed, Engaged, Phase};
use super::underway::Underway;

/// An engagement worked out before the tick that engages: of master `at`
/// from slave `slave`, on the table, geometry and configuration the axis
/// had when it was armed (they cannot change while it is armed without
/// preparing it again, see [`CamAxis::prepare_engagement`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ReadyEngagement {
    at: i64,
    slave: i64,
    engagement: Engagement,
    place: Place,
}

/// The cam's command at the engage master: what sizing a ramp-in under
/// limits needs of it.
#[derive(Clone, Copy, Debug)]
struct CamAt {
    slave: i64,
    velocity_ratio: f64,
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
                .map(|(engagement, place)| ReadyEngagement {
                    at: position,
                    slave: self.commanded,
                    engagement,
                    place,
                })
            }
            _ => None,
        };
    }

    /// Engages the cam at master `at` from the slave where it stands.
    pub(super) fn engage(&mut self, at: i64) -> Result<(), EngineError> {
        // Prepared at arm when it is of this master and slave (the slave
        // may have been moved since, see `discard_backlog`).
        let ready = match &self.phase {
            Phase::Armed(Armed {
                ready: Some(ready), ..
            }) if ready.at == at && ready.slave == self.commanded => {
                Some((ready.engagement, ready.place))
            }
            _ => None,
        };
        // The place of `at` comes with it (the table input there is the
        // one the engagement fixed).
        let (mut engagement, place) = match ready {
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
        // Under limits the lane's constants are taken to size the ramp,
        // and kept for the ramp-in tick.
        let (ramp_in, constants) = match self.ramp_limits {
            Some(limits) => self.limited_ramp(limits, &mut engagement, at, place)?,
            None => (self.config.ramp_in, None),
        };
        self.phase = Phase::Running(Engaged {
            engagement,
            place,
            followed: i128::from(at) << 32,
            underway: Underway::at_engage(ramp_in.map(|ramp| Ramp::new(ramp, at, self.commanded))),
            lane: None,
            plan: None,
        });
        // Without a ramp-in the cam is settled from the first tick: its
        // constants taken here let that tick be a steady one (set in
        // place: the phase is not built twice).
        // With one, the ramp-in tick follows the cam with the lane's
        // constants: taken here too.
        if let Phase::Running(engaged) = &mut self.phase {
            if engaged.underway.is_settled() {
                engaged
                    .underway
                    .settle(engaged.engagement.steady(&self.geometry));
            } else {
                if let Some(cam) = constants {
                    engaged.lane = Some(LaneConstants { cam, target: None });
                }
                engaged.take_lane_constants(&self.geometry);
            }
        }
        Ok(())
    }

    /// The ramp-in that keeps to `limits` for the engagement at master
    /// `at` (at `place`), after moving its target by whole strokes for a
    /// restricted direction; with the lane's constants of the engagement
    /// as it ends up, when they could be taken.
    fn limited_ramp(
        &mut self,
        limits: RampInLimits,
        engagement: &mut Engagement,
        at: i64,
        place: Place,
    ) -> Result<(Option<RampIn>, Option<Steady>), EngineError> {
        let hold = i128::from(self.commanded);
        let mut constants = engagement.steady(&self.geometry);
        let mut cam = self.cam_at(engagement, constants.as_ref(), at, place)?;
        let wrong_way = |slave: i64| {
            let gap = i128::from(slave) - hold;
            match limits.direction {
                RampDirection::Either => false,
                RampDirection::Positive => gap < 0,
                RampDirection::Negative => gap > 0,
            }
        };
        if wrong_way(cam.slave) {
            let stroke = self.geometry.stroke_pulses();
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
            engagement.add_strokes(n as i128);
            constants = engagement.steady(&self.geometry);
            cam = self.cam_at(engagement, constants.as_ref(), at, place)?;
            if wrong_way(cam.slave) {
                // Rounding left it a pulse short: one stroke more.
                engagement.add_strokes(libm::copysign(1.0, n) as i128);
                constants = engagement.steady(&self.geometry);
                cam = self.cam_at(engagement, constants.as_ref(), at, place)?;
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
        Ok((ramp, constants))
    }

    /// The cam at master `at` (at `place`) under `engagement`: from its
    /// 64-bit `constants` when they hold it (the same values, see
    /// `steady.rs`, for a fraction of the work), else on the general
    /// route, which reports any error.
    fn cam_at(
        &mut self,
        engagement: &Engagement,
        constants: Option<&Steady>,
        at: i64,
        place: Place,
    ) -> Result<CamAt, EngineError> {
        if let Some(cam) = constants.and_then(|c| c.sample(at, &self.curve, &mut self.cursor)) {
            return Ok(CamAt {
                slave: cam.slave,
                velocity_ratio: cam.velocity_ratio,
            });
        }
        let cam = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
        Ok(CamAt {
            slave: cam.slave,
            velocity_ratio: cam.velocity_ratio,
        })
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
            if let (Some(ready), Ok((engagement, place))) = (ready(&axis), fresh) {
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
        /// What sizing a ramp-in under limits reads of the cam at the
        /// engage master is the same from the 64-bit constants as on the
        /// general route (`cam_at` takes the first where it can).
        #[test]
        fn the_cam_at_engage_is_the_same_by_either_route(
            slaves in proptest::collection::vec(-20_000i64..20_000, 2..12),
            step in 1i64..3000,
            coupling in prop_oneof![
                Just(Coupling::Periodic),
                Just(Coupling::Repeat { min_stroke: 1 }),
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
            let Ok(mut axis) = CamAxis::new(table(&slaves, step), config) else {
                return Ok(());
            };
            let mut cursor = ecam_core::Cursor::new();
            let Ok((mut engagement, place)) = Engagement::placed(
                &axis.geometry, &axis.config, &axis.curve, &mut cursor, at, slave,
            ) else {
                return Ok(());
            };
            // As a restricted direction moves it.
            engagement.add_strokes(strokes);
            let constants = engagement.steady(&axis.geometry);
            let fast = axis.cam_at(&engagement, constants.as_ref(), at, place);
            let general = axis.cam_at(&engagement, None, at, place);
            match (fast, general) {
                (Ok(a), Ok(b)) => {
                    prop_assert_eq!(a.slave, b.slave);
                    prop_assert_eq!(a.velocity_ratio.to_bits(), b.velocity_ratio.to_bits());
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
