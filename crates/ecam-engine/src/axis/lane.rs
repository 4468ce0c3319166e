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
use super::underway::Change;

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
        // At most one ramp or blend; a table waiting is the general
        // tick's (it may switch).
        let (was_offsets, was_scaling, was_blend) = match self.underway.change() {
            None => (None, None, None),
            Some(Change::Offsets(ramp, None)) => (Some(*ramp), None, None),
            Some(Change::Scaling(ramp, None)) => (None, Some(ramp), None),
            Some(Change::Blend(blend, None)) => (None, None, Some(*blend)),
            Some(_) => return None,
        };
        let at = MasterPosition {
            counts: master,
            fraction: 0,
        };
        // Ramps that end here end first, as in the general tick.
        let offsets = was_offsets.filter(|ramp| !ramp.finished_at(at));
        let mut base = match was_offsets {
            Some(ramp) if offsets.is_none() => ramp.apply(&self.engagement, master).ok()?,
            _ => self.engagement,
        };
        let scaling = was_scaling.filter(|ramp| !ramp.finished_at(at));
        let target = was_scaling.filter(|_| scaling.is_none());
        let geo: &Geometry = match target {
            Some(ramp) => &ramp.target,
            None => geometry,
        };
        let blend = match was_blend {
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
            .ramp_in()
            .and_then(|ramp| Some((ramp, ramp.blend(master, slave)?)))
        {
            Some((ramp, blended)) => (blended, ratio * ramp.weight(master), true),
            None => (slave, ratio, false),
        };
        let ramp_in_ends = self.ramp_in().is_some_and(|ramp| ramp.finished_at(at));
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
        let following = !ramping && blend.is_none() && offsets.is_none() && scaling.is_none();
        let scaling_ends = target.is_some();
        if let Some(ramp) = target {
            *geometry = ramp.target;
        }
        self.engagement = base;
        // What ended this tick ends in place; nothing else is written.
        if was_offsets.is_some() && offsets.is_none()
            || scaling_ends
            || was_blend.is_some() && blend.is_none()
        {
            self.underway.end_change();
        }
        if ramp_in_ends {
            self.underway.end_ramp_in();
        }
        // Settled: the constants just used are the engagement's own.
        self.underway.settle(stop_at.is_none().then_some(constants));
        self.followed = i128::from(master) << 32;
        self.place = crate::coupling::Place {
            k,
            r_num: i128::from(cam.r_num),
        };
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
