//! The tick of a running cam with a switch waiting alone (for its master
//! position or the next tick; a table or a master-scaling change), at a
//! whole master count: until the switch fires, the steady tick of the old
//! cam; where it fires, the prepared landing (`plan.rs`) followed and put
//! in place. The lane (`lane.rs`) does the same for any combination of
//! what runs; this shape on its own skips the lane's dispatch, which is
//! much of the tick a switch lands in (docs/engine.md, "Benchmarks": the
//! worst tick). The steps and their order are the lane's, and the
//! steady-vs-general property test compares the ticks with the general
//! tick.

use ecam_core::{CamCurve, Cursor};

use crate::coupling::Place;
use crate::switch::Takeover;
use crate::{Events, MasterPosition};

use super::lane::{Followed, Landed};
use super::phase::Engaged;
use super::prepared::Prepared;
use super::underway::{Change, Next, Underway};
use super::{Coupled, FollowSample, step_to};

impl<C: CamCurve> Coupled<'_, C> {
    /// One tick at whole master count `master` of a running cam with a
    /// switch waiting alone and the lane's constants taken; `None`, with
    /// nothing changed, leaves the tick to the lane (another shape, no
    /// constants or plan, a landing not prepared for where the switch
    /// fires, or a value that leaves 64 bits). Out of line: the other
    /// ticks only check the shape.
    #[inline(never)]
    pub(super) fn switch_tick(
        &mut self,
        engaged: &mut Engaged<C>,
        master: i64,
    ) -> Option<Followed> {
        let Underway::Changing(Change::Waiting(Next::Switch(pending))) = &engaged.underway else {
            return None;
        };
        let lane = engaged.lane.as_ref()?;
        let now = i128::from(master) << 32;
        let (fired, next) = pending.trigger().fires(
            engaged.followed,
            now,
            false,
            self.missed_policy,
            self.config.single_turn,
        );
        let mut events = Events {
            activation_missed: fired.missed,
            ..Events::default()
        };
        let Some(switch_at) = fired.at else {
            // Not yet: the old cam, as a steady tick, and the trigger as
            // this tick left it.
            let constants = &lane.cam;
            let cam = constants.sample(master, self.curve, self.cursor)?;
            let sample =
                FollowSample::of_steady(&cam, constants, cam.slave, cam.velocity_ratio, true);
            step_to(
                &mut engaged.place,
                &mut engaged.followed,
                &cam,
                now,
                self.geometry.jumps_at_seam,
                &mut events,
            );
            if let Some(pending) = engaged.underway.change_mut().and_then(Change::pending_mut) {
                pending.set_trigger(next);
            }
            return Some((false, sample, events));
        };
        // Where it fires: the landing prepared for there, from the cam in
        // effect (checked), followed on the new cam from this master.
        let (i, prepared) = engaged
            .plan
            .as_ref()?
            .switch_landing(&lane.cam, switch_at)?;
        let curve: &C = match &pending.takeover {
            Takeover::Table(curve) => curve,
            Takeover::MasterScaling(_) => self.curve,
        };
        let landed = follow_landing(prepared, curve, master)?;
        events.table_switched = true;
        // Nothing failed: the tick is this one's.
        self.put_landing(engaged, Landed::Switch, i, landed, events)
    }

    /// One tick at whole master count `master` of a running cam with a
    /// table waiting alone for the seam and the lane's constants taken:
    /// the old cam until the master crosses a seam, where the landing
    /// prepared for that seam is followed and put in place; `None`, with
    /// nothing changed, leaves the tick to the lane (as
    /// [`Coupled::switch_tick`]).
    #[inline(never)]
    pub(super) fn seam_tick(&mut self, engaged: &mut Engaged<C>, master: i64) -> Option<Followed> {
        let Underway::Changing(Change::Waiting(Next::Seam(queued))) = &engaged.underway else {
            return None;
        };
        let constants = &engaged.lane.as_ref()?.cam;
        let (k, r_num) = constants.place(master)?;
        let now = i128::from(master) << 32;
        if engaged.place.k == i128::from(k) {
            // Within the cycle: the old cam, as a steady tick.
            let kin = constants.table(r_num, self.curve, self.cursor)?;
            let cam = constants.zoom(k, r_num, kin)?;
            let sample =
                FollowSample::of_steady(&cam, constants, cam.slave, cam.velocity_ratio, true);
            engaged.place = Place {
                k: i128::from(k),
                r_num: i128::from(r_num),
            };
            engaged.followed = now;
            return Some((false, sample, Events::default()));
        }
        // Across the seam the new table takes over: the landing prepared
        // for this seam and way, from the cam in effect (checked).
        let forward = i128::from(k) > engaged.place.k;
        let (i, prepared) =
            engaged
                .plan
                .as_ref()?
                .seam_landing(constants, engaged.place.k, forward)?;
        let landed = follow_landing(prepared, &queued.curve, master)?;
        let events = Events {
            table_switched: true,
            cycle_completed: true,
            ..Events::default()
        };
        self.put_landing(engaged, Landed::Seam, i, landed, events)
    }

    /// Puts what [`follow_landing`] followed in place (prepared landing
    /// `i`, from `kind`) and moves the followed master and place there
    /// (inlined: the landing is not moved on its way); `None`, with
    /// nothing changed, when a blend already over cannot move the new
    /// engagement by its shift.
    #[inline(always)]
    fn put_landing(
        &mut self,
        engaged: &mut Engaged<C>,
        kind: Landed,
        i: usize,
        landed: Landing,
        events: Events,
    ) -> Option<Followed> {
        let Landing {
            sample,
            shift,
            cursor,
            master,
            k,
            r_num,
        } = landed;
        // A master past the whole blend already: the new engagement and
        // its constants moved by the blend's shift (rare; worked out
        // again here rather than carried).
        match shift {
            Some(shift) => {
                let prepared = engaged.plan.as_ref()?.landing(i)?;
                let mut moved = prepared.engagement;
                moved.shift_output(shift).ok()?;
                let shifted = prepared.constants.shifted(0, shift)?;
                self.land_prepared(engaged, kind, i, Some(&moved), Some(&shifted), true, cursor);
            }
            None => self.land_prepared(engaged, kind, i, None, None, false, cursor),
        }
        engaged.followed = i128::from(master) << 32;
        engaged.place = Place {
            k: i128::from(k),
            r_num: i128::from(r_num),
        };
        if engaged.underway.is_settled() {
            let steady = engaged.lane.as_ref().map(|lane| lane.cam);
            engaged.underway.settle(steady);
        }
        Some((false, sample, events))
    }
}

/// What following a prepared landing at one master gave, before it is
/// put in place.
struct Landing {
    sample: FollowSample,
    /// The blend's shift, when the master is past the whole blend already.
    shift: Option<i128>,
    cursor: Cursor,
    master: i64,
    k: i64,
    r_num: i64,
}

/// The new cam of `prepared` on `curve` at whole master count `master`,
/// its blend on top while it runs (a master past the whole blend is on
/// the new cam already, moved by the blend's shift); `None` when a value
/// leaves 64 bits or the blend fails (the lane decides).
#[inline(always)]
fn follow_landing<C: CamCurve>(prepared: &Prepared, curve: &C, master: i64) -> Option<Landing> {
    let at = MasterPosition {
        counts: master,
        fraction: 0,
    };
    let shift = prepared.blend.as_ref().and_then(|b| b.finished_at(at));
    let shifted = match shift {
        Some(shift) => Some(prepared.constants.shifted(0, shift)?),
        None => None,
    };
    let constants = shifted.as_ref().unwrap_or(&prepared.constants);
    let (k, r_num) = constants.place(master)?;
    let mut cursor = prepared.cursor;
    let kin = constants.table(r_num, curve, &mut cursor)?;
    let cam = constants.zoom(k, r_num, kin)?;
    let blend = prepared.blend.as_ref().filter(|_| shift.is_none());
    let (slave, velocity_ratio) = match blend {
        Some(blend) => {
            let blended = blend.command(master).ok()?;
            (blended.slave, blended.velocity_ratio)
        }
        None => (cam.slave, cam.velocity_ratio),
    };
    let sample = FollowSample::of_steady(&cam, constants, slave, velocity_ratio, blend.is_none());
    Some(Landing {
        sample,
        shift,
        cursor,
        master,
        k,
        r_num,
    })
}
