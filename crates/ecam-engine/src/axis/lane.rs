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

use ecam_core::{CamCurve, Cursor};

use crate::coupling::Engagement;
use crate::coupling::{Geometry, Place};
use crate::steady::Steady;
use crate::stop::CycleEnd;
use crate::switch::Takeover;
use crate::{Events, MasterPosition};

use super::lane_constants::LaneConstants;
use super::phase::Engaged;
use super::underway::{Change, Next};
use super::{Coupled, FollowSample};

/// What the lane hands back: whether the run ended (an end-of-cycle
/// stop reached), the sample followed and what happened.
pub(super) type Followed = (bool, FollowSample, Events);

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
        let at = MasterPosition {
            counts: master,
            fraction: 0,
        };
        // Ramps that end here end first, as in the general tick: the
        // engagement and the geometry in effect from this tick on. Only
        // what ends is copied; the rest is read where it is.
        // One change at most (`underway.rs`): an offset or scaling ramp
        // or a blend, a table waiting beside it or alone.
        let (ramp_in, change) = engaged.underway.parts();
        // All of it read in one match.
        let (engaged_offsets, engaged_scaling, engaged_blend, pending, queued) = match change {
            None => (None, None, None, None, None),
            Some(Change::Offsets(ramp, queued)) => (Some(ramp), None, None, None, queued.as_ref()),
            Some(Change::Scaling(ramp, queued)) => (None, Some(ramp), None, None, queued.as_ref()),
            Some(Change::Blend(blend, None)) => (None, None, Some(blend), None, None),
            Some(Change::Blend(blend, Some(Next::Switch(pending)))) => {
                (None, None, Some(blend), Some(pending), None)
            }
            Some(Change::Blend(blend, Some(Next::Seam(queued)))) => {
                (None, None, Some(blend), None, Some(queued))
            }
            Some(Change::Waiting(Next::Switch(pending))) => (None, None, None, Some(pending), None),
            Some(Change::Waiting(Next::Seam(queued))) => (None, None, None, None, Some(queued)),
        };
        let offsets_end = engaged_offsets.is_some_and(|ramp| ramp.finished_at(at));
        let scaling_end = engaged_scaling.is_some_and(|ramp| ramp.finished_at(at));
        let blend_shift = engaged_blend.and_then(|b| b.finished_at(at));
        let offsets = engaged_offsets.filter(|_| !offsets_end);
        let scaling = engaged_scaling.filter(|_| !scaling_end);
        let blend = engaged_blend.filter(|_| blend_shift.is_none());
        let geo: &Geometry = match engaged_scaling {
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
        if let (Some(ramp), Some(lane)) = (engaged_scaling, &mut engaged.lane)
            && lane.target.is_none()
        {
            lane.target = Some(engaged.engagement.steady(&ramp.target)?);
        }
        let lane = engaged.lane.as_ref()?;
        // The engagement changes only when a ramp or blend ends here: then
        // new constants (rare ticks), else the kept ones.
        let changed = if offsets_end || scaling_end || blend_shift.is_some() {
            let mut base = engaged.engagement;
            let mut constants = match engaged_offsets {
                Some(ramp) if offsets_end => {
                    base = ramp.apply(&base, master).ok()?;
                    // Taken when the change was asked for, if they could be.
                    match lane.target {
                        Some(target) => target,
                        None => base.steady(geo)?,
                    }
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
        // A waiting switch where it fires, a table queued for the seam
        // where the master crosses one: both prepared when they were asked
        // for (`plan.rs`), so here they are only looked up. The switch is
        // looked at first: when it fires, the old cam's place is not needed.
        // (Never with a stop: a switch is refused while one runs.)
        let mut events = Events::default();
        let mut landing = None;
        let mut trigger = None;
        if stop_at.is_none()
            && let Some(pending) = pending
        {
            let (fired, next) = pending.trigger().fires(
                engaged.followed,
                i128::from(master) << 32,
                blend.is_some(),
                self.missed_policy,
                self.config.single_turn,
            );
            events.activation_missed = fired.missed;
            trigger = Some(next);
            if let Some(switch_at) = fired.at {
                let (i, prepared) = engaged.plan.as_ref()?.switch_landing(base_c, switch_at)?;
                let curve = match &pending.takeover {
                    Takeover::Table(curve) => curve,
                    Takeover::MasterScaling(_) => &*self.curve,
                };
                landing = Some((Landed::Switch, i, prepared, curve));
                events.table_switched = true;
            }
        }
        let (mut k, mut r_num) = (0, 0);
        let mut stopped = None;
        if landing.is_none() {
            (k, r_num) = now_c.place(master)?;
            if let Some(end) = stop_at
                && let Some((place, forward)) = end.reached_place(geo, k, r_num)
            {
                k = i64::try_from(place.k).ok()?;
                r_num = i64::try_from(place.r_num).ok()?;
                stopped = Some(forward);
            }
        }
        if landing.is_none()
            && stopped.is_none()
            && queued.is_some()
            && engaged.place.k != i128::from(k)
            && engaged_blend.is_none()
            && offsets.is_none()
            && scaling.is_none()
        {
            // The general tick's seam switch (`switch_at_seam`).
            if stop_at.is_some() {
                return None;
            }
            let forward = i128::from(k) > engaged.place.k;
            let (i, prepared) =
                engaged
                    .plan
                    .as_ref()?
                    .seam_landing(base_c, engaged.place.k, forward)?;
            landing = Some((Landed::Seam, i, prepared, &queued?.curve));
            events.table_switched = true;
            events.cycle_completed = true;
        }
        // After a switch: the new cam from this master on (its blend may
        // be over already, a master past its whole distance).
        let mut landed = None;
        let mut landed_cursor = Cursor::new();
        let mut shifted = None;
        if let Some((kind, i, prepared, _)) = &landing {
            let shift = prepared.blend.as_ref().and_then(|b| b.finished_at(at));
            let mut engagement = None;
            if let Some(shift) = shift {
                let mut moved = prepared.engagement;
                moved.shift_output(shift).ok()?;
                engagement = Some(moved);
                shifted = Some(prepared.constants.shifted(0, shift)?);
            }
            landed = Some((*kind, *i, engagement, shift.is_some()));
            landed_cursor = prepared.cursor;
        }
        let (geo, now_c, base_c, blend, curve, cursor) = match (&landing, &landed) {
            (Some((_, _, prepared, curve)), Some((_, _, _, blend_ended))) => {
                let constants = shifted.as_ref().unwrap_or(&prepared.constants);
                (k, r_num) = constants.place(master)?;
                (
                    &prepared.geometry,
                    constants,
                    constants,
                    prepared.blend.as_ref().filter(|_| !blend_ended),
                    *curve,
                    &mut landed_cursor,
                )
            }
            _ => (geo, now_c, base_c, blend, &*self.curve, &mut *self.cursor),
        };
        let kin = now_c.table(r_num, curve, cursor)?;
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
        let (slave, ratio, ramping) =
            match ramp_in.and_then(|ramp| Some((ramp, ramp.blend(master, slave)?))) {
                Some((ramp, blended)) => (blended, ratio * ramp.weight(master), true),
                None => (slave, ratio, false),
            };

        // Nothing failed: the tick is the lane's.
        let ended_ramp = ramp_in.is_some_and(|ramp| ramp.finished_at(at));
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
        if landed.is_none() && engaged.place.k != k_wide {
            events.cycle_completed = true;
            events.seam_jump |= jumps_at_seam;
        }
        let target_geometry = engaged_scaling
            .filter(|_| scaling_end)
            .map(|ramp| ramp.target);
        if offsets_end || scaling_end || blend_shift.is_some() {
            // The table waiting beside the ramp or blend, if any, remains.
            engaged.underway.end_change();
        }
        if ended_ramp {
            engaged.underway.end_ramp_in();
        }
        if let (Some(pending), Some(trigger)) = (
            engaged.underway.change_mut().and_then(Change::pending_mut),
            trigger,
        ) {
            pending.set_trigger(trigger);
        }
        if let Some((base, constants)) = changed {
            engaged.engagement = base;
            if let Some(target) = target_geometry {
                *self.geometry = target;
            }
            if let Some(lane) = engaged.lane.as_mut() {
                lane.cam = constants;
                if !scaling_runs {
                    lane.target = None;
                }
            }
        }
        if let Some((kind, i, engagement, blend_ended)) = landed {
            self.land_prepared(
                engaged,
                kind,
                i,
                engagement.as_ref(),
                shifted.as_ref(),
                blend_ended,
                landed_cursor,
            );
        }
        engaged.followed = i128::from(master) << 32;
        engaged.place = Place {
            k: k_wide,
            r_num: i128::from(r_num),
        };
        if engaged.underway.is_settled() {
            // Settled: the constants are the engagement's own (a stop
            // drops them).
            let steady = match stop_at {
                None => engaged.lane.as_ref().map(|lane| lane.cam),
                Some(_) => None,
            };
            engaged.underway.settle(steady);
        }
        if let Some(forward) = stopped {
            events.cycle_completed |= forward;
            events.stopped = true;
        }
        Some((stopped.is_some(), sample, events))
    }
}

/// What a switch in the lane came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Landed {
    /// The table queued for the seam.
    Seam,
    /// The switch waiting for its position or the next tick.
    Switch,
}

impl<C: CamCurve> Coupled<'_, C> {
    /// Puts prepared landing `i` in place (the lane has looked it up and
    /// followed the new cam with `constants`, the cursor left at `cursor`):
    /// the new table (the old one retired) or scaling, engagement
    /// (`engagement` when its blend is over already, then without the
    /// blend), geometry and constants.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn land_prepared(
        &mut self,
        engaged: &mut Engaged<C>,
        kind: Landed,
        i: usize,
        engagement: Option<&Engagement>,
        constants: Option<&Steady>,
        blend_ended: bool,
        cursor: Cursor,
    ) {
        let prepared = engaged.plan.as_ref().and_then(|plan| plan.landing(i));
        // The switch taken, nothing changes beside the ramp-in and the
        // switch's blend.
        let blend = prepared.and_then(|p| p.blend).filter(|_| !blend_ended);
        let takeover = match kind {
            Landed::Seam => {
                let queued = engaged.underway.take_seam_table();
                if let Some(blend) = blend {
                    engaged.underway.start_blend(blend);
                }
                queued.map(|queued| Takeover::Table(queued.curve))
            }
            Landed::Switch => engaged.underway.land_switch(blend),
        };
        // Copied field by field where they go, the plan dropped after.
        if let Some(prepared) = prepared {
            if let Some(zoom) = prepared.master_zoom {
                self.config.master_zoom = zoom;
            }
            engaged.engagement = *engagement.unwrap_or(&prepared.engagement);
            *self.geometry = prepared.geometry;
            let cam = constants.unwrap_or(&prepared.constants);
            match engaged.lane.as_mut() {
                Some(lane) => {
                    lane.cam = *cam;
                    lane.target = None;
                }
                None => {
                    engaged.lane = Some(LaneConstants {
                        cam: *cam,
                        target: None,
                    });
                }
            }
        }
        engaged.plan = None;
        if let Some(Takeover::Table(curve)) = takeover {
            *self.retired = Some(core::mem::replace(self.curve, curve));
        }
        *self.cursor = cursor;
    }
}
