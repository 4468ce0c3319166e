//! Engaging the cam: the engagement at the start position and the ramp-in
//! that catches the slave up, under limits when they are set.

use core::num::NonZeroU64;

use ecam_core::CamCurve;

use crate::coupling::{Engagement, Place, exact_f64};
use crate::ramp::Ramp;
use crate::ramp_in::{RampDirection, RampInLimits};
use crate::{EngineError, RampIn};

use super::CamAxis;
use super::phase::{Engaged, Phase};

impl<C: CamCurve> CamAxis<C> {
    /// Engages the cam at master `at` from the slave where it stands.
    pub(super) fn engage(&mut self, at: i64) -> Result<(), EngineError> {
        // The place of `at` comes with it (the table input there is the
        // one the engagement fixed).
        let (mut engagement, place) = Engagement::placed(
            &self.geometry,
            &self.config,
            &self.curve,
            &mut self.cursor,
            at,
            self.commanded,
        )?;
        let ramp_in = match self.ramp_limits {
            Some(limits) => self.limited_ramp(limits, &mut engagement, place)?,
            None => self.config.ramp_in,
        };
        self.phase = Phase::Running(Engaged {
            engagement,
            ramp: ramp_in.map(|ramp| Ramp::new(ramp, at, self.commanded)),
            place,
            queued: None,
            seam_blend: None,
            pending: None,
            blend: None,
            offsets: None,
            scaling: None,
            followed: i128::from(at) << 32,
            steady: None,
            lane: None,
            plan: None,
        });
        Ok(())
    }

    /// The ramp-in that keeps to `limits` for the engagement at `place`,
    /// after moving its target by whole strokes for a restricted direction.
    fn limited_ramp(
        &mut self,
        limits: RampInLimits,
        engagement: &mut Engagement,
        place: Place,
    ) -> Result<Option<RampIn>, EngineError> {
        let hold = i128::from(self.commanded);
        let mut cam = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
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
            cam = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
            if wrong_way(cam.slave) {
                // Rounding left it a pulse short: one stroke more.
                engagement.add_strokes(libm::copysign(1.0, n) as i128);
                cam = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
            }
        }
        let gap = exact_f64(i128::from(cam.slave) - hold);
        let needed = limits.distance(gap, cam.velocity_ratio, self.speed.bound())?;
        let configured = self.config.ramp_in.map(|r| r.distance.get());
        Ok(match (needed, configured) {
            (Some(a), Some(b)) => NonZeroU64::new(a.max(b)),
            (Some(d), None) | (None, Some(d)) => NonZeroU64::new(d),
            // A master at rest gives no speed to size the ramp for: one
            // master count per 1/1.875 pulse of gap.
            (None, None) => NonZeroU64::new(libm::ceil(1.875 * libm::fabs(gap)).max(1.0) as u64),
        }
        .map(|distance| RampIn { distance }))
    }
}
