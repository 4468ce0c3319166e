//! The fast lane of the general tick: a cam that runs (or runs to an
//! end-of-cycle stop it has not reached) with a ramp-in, a blend, an
//! offset or a slave-scaling ramp on top, no table waiting to switch, at a
//! whole master count. The cam comes from the 64-bit constants of the
//! engagement in effect this tick (`steady.rs`, taken once per tick) and
//! the ramps go on top exactly as the general tick puts them; so a ramp,
//! blend or change costs a little more than a steady tick instead of the
//! general tick's 128-bit route (docs/engine.md, "Benchmarks": the worst
//! tick).
//!
//! Everything is computed before anything is changed: when a value would
//! leave 64 bits or a step would fail, the lane gives up and the general
//! tick takes the same tick from the start (and reports any error). The
//! steps and their order are the general tick's (`Coupled::follow`), and
//! the steady-vs-general property test compares the two.

use ecam_core::{CamCurve, Cursor};

use crate::coupling::{Engagement, Geometry};
use crate::stop::CycleEnd;
use crate::{Events, MasterPosition};

use super::FollowSample;
use super::phase::Engaged;

/// What the lane hands back: the sample followed and what happened.
pub(super) type Followed = (FollowSample, Events);

impl<C> Engaged<C> {
    /// One tick of the fast lane at whole master count `master` (see the
    /// module docs); `None` leaves the tick, untouched, to the general path.
    #[inline(never)]
    pub(super) fn follow_lane<K: CamCurve>(
        &mut self,
        geometry: &mut Geometry,
        curve: &K,
        cursor: &mut Cursor,
        stop_at: Option<&CycleEnd>,
        master: i64,
    ) -> Option<Followed> {
        if self.queued.is_some() || self.pending.is_some() {
            return None;
        }
        let at = MasterPosition {
            counts: master,
            fraction: 0,
        };
        // Ramps that end here end first, as in the general tick.
        let offsets = self.offsets.filter(|ramp| !ramp.finished_at(at));
        let mut base = match self.offsets {
            Some(ramp) if offsets.is_none() => ramp.apply(&self.engagement, master).ok()?,
            _ => self.engagement,
        };
        let scaling = self.scaling.filter(|ramp| !ramp.finished_at(at));
        let target = self.scaling.as_ref().filter(|_| scaling.is_none());
        let geo: &Geometry = match target {
            Some(ramp) => &ramp.target,
            None => geometry,
        };
        let blend = match self.blend {
            Some(blend) => match blend.finished_at(at) {
                Some(shift) => {
                    let mut shifted = base;
                    shifted.shift_output(shift).ok()?;
                    base = shifted;
                    None
                }
                None => Some(blend),
            },
            None => None,
        };
        let now: Engagement = match &offsets {
            Some(ramp) => ramp.apply(&base, master).ok()?,
            None => base,
        };
        if let Some(end) = stop_at
            && end.reached(geo, now.table_input(geo, master)).is_some()
        {
            return None;
        }
        let constants = now.steady(geo)?;
        let cam = constants.sample(master, curve, cursor)?;
        let (slave, ratio) = match (&blend, &scaling) {
            (Some(blend), _) => {
                let blended = blend.command(master).ok()?;
                (blended.slave, blended.velocity_ratio)
            }
            (None, Some(ramp)) => {
                let new = now.steady(&ramp.target)?.sample(master, curve, cursor)?;
                ramp.mix(
                    master,
                    (cam.slave, cam.velocity_ratio),
                    (new.slave, new.velocity_ratio),
                )
            }
            (None, None) => (cam.slave, cam.velocity_ratio),
        };
        let (slave, ratio, ramping) = match self
            .ramp
            .and_then(|ramp| Some((ramp, ramp.blend(master, slave)?)))
        {
            Some((ramp, blended)) => (blended, ratio * ramp.weight(master), true),
            None => (slave, ratio, false),
        };
        let ramp = self.ramp.filter(|ramp| !ramp.finished_at(at));
        let input_offset = match offsets {
            // The report names the engagement's own offset, not the ramp's.
            Some(_) => base.input_offset(geo),
            None => constants.input_offset,
        };

        // Nothing failed: the tick is the lane's.
        let k = i128::from(cam.k);
        let mut events = Events::default();
        if self.place.k != k {
            events.cycle_completed = true;
            events.seam_jump |= geo.jumps_at_seam;
        }
        if let Some(ramp) = target {
            *geometry = ramp.target;
        }
        self.engagement = base;
        self.offsets = offsets;
        self.scaling = scaling;
        self.blend = blend;
        self.ramp = ramp;
        self.followed = i128::from(master) << 32;
        self.place = crate::coupling::Place {
            k,
            r_num: i128::from(cam.r_num),
        };
        let following = !ramping && blend.is_none() && offsets.is_none() && scaling.is_none();
        self.steady = None;
        if ramp.is_none() && stop_at.is_none() && !self.changing() {
            // Settled: the constants just used are the engagement's own.
            self.steady = Some(constants);
        }
        let sample = FollowSample {
            master_in_cycle: cam.master_in_cycle,
            master_in_cycle_raw: cam.master_in_cycle_raw,
            cycle: super::clamp_i64(k - i128::from(constants.k_engage)),
            unzoomed: cam.unzoomed,
            in_cycle_zoomed: cam.in_cycle_zoomed,
            velocity_ratio: ratio,
            following,
            input_offset,
            slave,
        };
        Some((sample, events))
    }
}
