//! The fast lane of the general tick: a cam that runs (or runs to an
//! end-of-cycle stop) at a whole master count, with a ramp-in, a blend, an
//! offset or a slave-scaling ramp on top or a table waiting, including
//! the tick an end-of-cycle stop is reached. The cam comes from the 64-bit
//! constants of the engagement in effect (`steady.rs`), kept with the
//! engagement from tick to tick ([`LaneConstants`]), and the ramps go on
//! top exactly as the general tick puts them; so a ramp, blend or change
//! costs little more than a steady tick instead of the general tick's
//! 128-bit route (docs/engine.md, "Benchmarks": the worst tick).
//!
//! Everything is computed before anything is changed: when a value would
//! leave 64 bits or a step would fail, the lane gives up and the general
//! tick takes the same tick from the start (and reports any error). The
//! steps and their order are the general tick's (`Coupled::follow`), and
//! the steady-vs-general property test compares the two.

use ecam_core::CamCurve;

use crate::coupling::{Geometry, Place};
use crate::steady::Steady;
use crate::stop::CycleEnd;
use crate::{Events, MasterPosition};

use super::phase::Engaged;
use super::{Coupled, FollowSample};

/// What the lane hands back: whether the run ended (an end-of-cycle
/// stop reached), the sample followed and what happened.
pub(super) type Followed = (bool, FollowSample, Events);

/// The lane's 64-bit constants of an engagement (`Engaged::lane`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LaneConstants {
    /// On the axis' geometry.
    pub(super) cam: Steady,
    /// On a slave-scaling ramp's target geometry, while one runs.
    pub(super) target: Option<Steady>,
}

impl<C: CamCurve> Coupled<'_, C> {
    /// One tick of the fast lane at whole master count `master` (see the
    /// module docs); `None` leaves the tick, untouched, to the general path.
    #[inline(never)]
    pub(super) fn follow_lane(
        &mut self,
        engaged: &mut Engaged<C>,
        stop_at: Option<&CycleEnd>,
        master: i64,
    ) -> Option<Followed> {
        if engaged.queued.is_some() {
            return None;
        }
        let at = MasterPosition {
            counts: master,
            fraction: 0,
        };
        // Ramps that end here end first, as in the general tick: the
        // engagement and the geometry in effect from this tick on. Only
        // what ends is copied; the rest is read where it is.
        let offsets_end = engaged.offsets.is_some_and(|ramp| ramp.finished_at(at));
        let scaling_end = engaged
            .scaling
            .as_ref()
            .is_some_and(|ramp| ramp.finished_at(at));
        let blend_shift = engaged.blend.as_ref().and_then(|b| b.finished_at(at));
        let offsets = engaged.offsets.as_ref().filter(|_| !offsets_end);
        let scaling = engaged.scaling.as_ref().filter(|_| !scaling_end);
        let blend = engaged.blend.as_ref().filter(|_| blend_shift.is_none());
        if offsets.is_some() && scaling.is_some() {
            return None;
        }
        let geo: &Geometry = match &engaged.scaling {
            Some(ramp) if scaling_end => &ramp.target,
            _ => self.geometry,
        };
        // The kept constants describe the engagement and geometry as they
        // are: taken here when missing, so that the rest reads them in place.
        if engaged.lane.is_none() {
            engaged.lane = Some(LaneConstants {
                cam: engaged.engagement.steady(self.geometry)?,
                target: None,
            });
        }
        if let (Some(ramp), Some(lane)) = (&engaged.scaling, &mut engaged.lane)
            && lane.target.is_none()
        {
            lane.target = Some(engaged.engagement.steady(&ramp.target)?);
        }
        let lane = engaged.lane.as_ref()?;
        // The engagement changes only when a ramp or blend ends here: then
        // new constants (rare ticks), else the kept ones.
        let changed = if offsets_end || scaling_end || blend_shift.is_some() {
            let mut base = engaged.engagement;
            let mut constants = match &engaged.offsets {
                Some(ramp) if offsets_end => {
                    base = ramp.apply(&base, master).ok()?;
                    base.steady(geo)?
                }
                _ if scaling_end => lane.target?,
                _ => lane.cam,
            };
            // A blend this master completes moves the new cam by its
            // shift (only the output offset: the place is the same).
            if let Some(shift) = blend_shift {
                base.shift_output(shift).ok()?;
                constants = constants.shifted(0, shift)?;
            }
            Some((base, constants))
        } else {
            None
        };
        let base_c: &Steady = match &changed {
            Some((_, constants)) => constants,
            None => &lane.cam,
        };
        let target_c: Option<&Steady> = match scaling {
            Some(_) => Some(lane.target.as_ref()?),
            None => None,
        };
        let ramped;
        let now_c: &Steady = match offsets {
            Some(ramp) => {
                let (input, output) = ramp.parts(master);
                ramped = base_c.shifted(input, output)?;
                &ramped
            }
            None => base_c,
        };
        let (mut k, mut r_num) = now_c.place(master)?;
        let mut stopped = None;
        if let Some(end) = stop_at
            && let Some((place, forward)) = end.reached_place(geo, k, r_num)
        {
            k = i64::try_from(place.k).ok()?;
            r_num = i64::try_from(place.r_num).ok()?;
            stopped = Some(forward);
        }
        // A switch waiting for its position: looked at, not yet taken.
        let mut trigger = None;
        let mut missed = false;
        if stopped.is_none()
            && stop_at.is_none()
            && let Some(pending) = &engaged.pending
        {
            let (fired, next) = pending.trigger().fires(
                engaged.followed,
                i128::from(master) << 32,
                blend.is_some(),
                self.missed_policy,
                self.config.single_turn,
            );
            if fired.at.is_some() {
                return None;
            }
            missed = fired.missed;
            trigger = Some(next);
        }
        let kin = now_c.table(r_num, &*self.curve, self.cursor)?;
        let cam = now_c.zoom(k, r_num, kin)?;
        let (slave, ratio) = match (blend, scaling, target_c) {
            (Some(blend), _, _) => {
                let blended = blend.command(master).ok()?;
                (blended.slave, blended.velocity_ratio)
            }
            (None, Some(ramp), Some(target_c)) => {
                // The same table, place and engagement under the new
                // slave zoom: one lookup serves both cams.
                let new = target_c.zoom(k, r_num, kin)?;
                ramp.mix(
                    master,
                    (cam.slave, cam.velocity_ratio),
                    (new.slave, new.velocity_ratio),
                )
            }
            _ => (cam.slave, cam.velocity_ratio),
        };
        let (slave, ratio, ramping) = match engaged
            .ramp
            .and_then(|ramp| Some((ramp, ramp.blend(master, slave)?)))
        {
            Some((ramp, blended)) => (blended, ratio * ramp.weight(master), true),
            None => (slave, ratio, false),
        };

        // Nothing failed: the tick is the lane's.
        let ended_ramp = engaged.ramp.is_some_and(|ramp| ramp.finished_at(at));
        let following = !ramping && blend.is_none() && offsets.is_none() && scaling.is_none();
        let k_wide = i128::from(k);
        let sample = FollowSample {
            master_in_cycle: cam.master_in_cycle,
            master_in_cycle_raw: cam.master_in_cycle_raw,
            cycle: super::clamp_i64(k_wide - i128::from(base_c.k_engage)),
            unzoomed: cam.unzoomed,
            in_cycle_zoomed: cam.in_cycle_zoomed,
            velocity_ratio: ratio,
            following,
            input_offset: base_c.input_offset,
            slave,
        };
        let jumps_at_seam = geo.jumps_at_seam;
        let scaling_runs = scaling.is_some();
        let mut events = Events {
            activation_missed: missed,
            ..Events::default()
        };
        if engaged.place.k != k_wide {
            events.cycle_completed = true;
            events.seam_jump |= jumps_at_seam;
        }
        if offsets_end {
            engaged.offsets = None;
        }
        if blend_shift.is_some() {
            engaged.blend = None;
        }
        if ended_ramp {
            engaged.ramp = None;
        }
        if let (Some(pending), Some(trigger)) = (engaged.pending.as_mut(), trigger) {
            pending.set_trigger(trigger);
        }
        if let Some((base, constants)) = changed {
            engaged.engagement = base;
            if scaling_end
                && let Some(ramp) = engaged.scaling.take()
            {
                *self.geometry = ramp.target;
            }
            if let Some(lane) = engaged.lane.as_mut() {
                lane.cam = constants;
                if !scaling_runs {
                    lane.target = None;
                }
            }
        }
        engaged.followed = i128::from(master) << 32;
        engaged.place = Place {
            k: k_wide,
            r_num: i128::from(r_num),
        };
        let settled = engaged.ramp.is_none() && stop_at.is_none() && !engaged.changing();
        if settled {
            // Settled: the constants are the engagement's own.
            engaged.steady = engaged.lane.as_ref().map(|lane| lane.cam);
        } else if engaged.steady.is_some() {
            engaged.steady = None;
        }
        if let Some(forward) = stopped {
            events.cycle_completed |= forward;
            events.stopped = true;
        }
        Some((stopped.is_some(), sample, events))
    }
}
