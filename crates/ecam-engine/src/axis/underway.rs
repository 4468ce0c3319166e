//! What runs on top of an engaged cam, as types of what can coexist.
//!
//! - The **ramp-in** eases the slave onto whatever the cam commands, so it
//!   goes with anything else; it only starts at engage.
//! - An **offset or slave-scaling change** is ramped in only on a cam with
//!   nothing else changing; a table queued for the seam meanwhile waits for
//!   the ramp's end (a position or at-once switch is refused).
//! - A switch's **blend** runs from the switch on; the next table (for the
//!   seam, a master position or the next tick) waits for its end.
//! - A **table waits** for the next seam or for its switch position (or the
//!   next tick): one slot, a new request replaces the waiting one.
//! - **Settled**: none of these; once taken, the steady tick's constants
//!   live in a variant of their own, so they cannot outlive what they were
//!   taken from (every change replaces that variant) and the steady tick
//!   checks one discriminant.
//!
//! [`Underway`] and [`Change`] hold exactly these combinations, so what
//! may coexist is the shape of the types, not a rule each change request
//! has to keep by hand.

use core::num::NonZeroU64;

use crate::blend::Blend;
use crate::offset_ramp::OffsetRamp;
use crate::ramp::Ramp;
use crate::scaling::ScalingRamp;
use crate::steady::Steady;
use crate::switch::{Pending, Takeover};
use crate::{EngineError, Zoom};

use super::AfterPass;

/// What is under way on top of the engaged cam.
#[derive(Clone, Debug)]
#[repr(u8)]
pub(super) enum Underway<C> {
    /// Nothing, and the steady tick's 64-bit constants not taken (not yet,
    /// while stopping, or when they leave 64 bits).
    Settled,
    /// Nothing, and the steady tick's constants, taken by the general tick.
    Steady(Steady),
    /// The ramp-in runs, with a change beside it or not.
    RampIn(Ramp, Option<Change<C>>),
    /// A change, the ramp-in over.
    Changing(Change<C>),
}

/// A change of the running cam: a ramp, a blend or a table waiting.
#[derive(Clone, Debug)]
#[repr(u8)]
pub(super) enum Change<C> {
    /// An offset change being ramped in ([`crate::CamAxis::change_offsets`]);
    /// a table queued for the seam waits for its end.
    Offsets(OffsetRamp, Option<Queued<C>>),
    /// A slave-scaling change being ramped in
    /// ([`crate::CamAxis::change_slave_scaling`]); as `Offsets`.
    Scaling(ScalingRamp, Option<Queued<C>>),
    /// The blend from the last switch's old cam; the next table waits for
    /// its end.
    Blend(Blend, Option<Next<C>>),
    /// A table waiting, nothing else changing.
    Waiting(Next<C>),
}

/// The table waiting to take over.
#[derive(Clone, Debug)]
pub(super) enum Next<C> {
    /// At the next seam ([`crate::CamAxis::queue_curve`]).
    Seam(Queued<C>),
    /// At a master position or the next tick ([`crate::CamAxis::switch_curve`],
    /// [`crate::CamAxis::change_master_scaling`]).
    Switch(Pending<C>),
}

/// A table queued for the next seam.
#[derive(Clone, Debug)]
pub(super) struct Queued<C> {
    pub(super) curve: C,
    /// What follows its first pass.
    pub(super) then: AfterPass,
    /// The blend of the seam switch.
    pub(super) blend: Option<NonZeroU64>,
}

impl<C> Next<C> {
    /// What takes over: the table, or the master scaling of a switch.
    pub(super) fn into_takeover(self) -> Takeover<C> {
        match self {
            Self::Seam(queued) => Takeover::Table(queued.curve),
            Self::Switch(pending) => pending.takeover,
        }
    }
}

impl<C> Underway<C> {
    /// At engage: the ramp-in, if there is one, and nothing else.
    pub(super) fn at_engage(ramp_in: Option<Ramp>) -> Self {
        match ramp_in {
            Some(ramp) => Self::RampIn(ramp, None),
            None => Self::Settled,
        }
    }

    /// The steady tick's constants, when settled and taken.
    #[inline(always)]
    pub(super) fn steady(&self) -> Option<&Steady> {
        match self {
            Self::Steady(steady) => Some(steady),
            _ => None,
        }
    }

    /// Gives an unsized ramp-in its distance (`Ramp::to_size`).
    #[inline(always)]
    pub(super) fn size_ramp_in(&mut self, distance: NonZeroU64) {
        if let Self::RampIn(ramp, _) = self {
            ramp.size(distance);
        }
    }

    /// A ramp-in with nothing else under way (the ramp-in tick's case).
    #[inline(always)]
    pub(super) fn ramps_in_alone(&self) -> bool {
        matches!(self, Self::RampIn(_, None))
    }

    /// Only a table waits, for the next seam: no ramp-in, ramp, blend or
    /// switch beside it.
    #[inline(always)]
    pub(super) fn waits_alone_for_seam(&self) -> bool {
        matches!(self, Self::Changing(Change::Waiting(Next::Seam(_))))
    }

    /// A table waits alone, with no ramp-in beside it: `Some(true)` for
    /// the next seam, `Some(false)` for a switch position or the next
    /// tick.
    #[inline(always)]
    pub(super) fn waiting_alone(&self) -> Option<bool> {
        match self {
            Self::Changing(Change::Waiting(next)) => Some(matches!(next, Next::Seam(_))),
            _ => None,
        }
    }

    /// Nothing is under way.
    pub(super) fn is_settled(&self) -> bool {
        matches!(self, Self::Settled | Self::Steady(_))
    }

    /// The ramp-in, while it runs.
    pub(super) fn ramp_in(&self) -> Option<&Ramp> {
        match self {
            Self::RampIn(ramp, _) => Some(ramp),
            _ => None,
        }
    }

    /// The change under way.
    pub(super) fn change(&self) -> Option<&Change<C>> {
        match self {
            Self::RampIn(_, change) => change.as_ref(),
            Self::Changing(change) => Some(change),
            Self::Settled | Self::Steady(_) => None,
        }
    }

    /// The ramp-in and the change under way, read at once.
    #[inline]
    pub(super) fn parts(&self) -> (Option<&Ramp>, Option<&Change<C>>) {
        match self {
            Self::RampIn(ramp, change) => (Some(ramp), change.as_ref()),
            Self::Changing(change) => (None, Some(change)),
            Self::Settled | Self::Steady(_) => (None, None),
        }
    }

    /// The change under way, to change it.
    pub(super) fn change_mut(&mut self) -> Option<&mut Change<C>> {
        match self {
            Self::RampIn(_, change) => change.as_mut(),
            Self::Changing(change) => Some(change),
            Self::Settled | Self::Steady(_) => None,
        }
    }

    /// Replaces the change (`None`: none), keeping the ramp-in; gives the
    /// one there was.
    fn replace_change(&mut self, change: Option<Change<C>>) -> Option<Change<C>> {
        match core::mem::replace(self, Self::Settled) {
            Self::RampIn(ramp, old) => {
                *self = Self::RampIn(ramp, change);
                old
            }
            Self::Changing(old) => {
                *self = Self::with_change(change);
                Some(old)
            }
            Self::Settled | Self::Steady(_) => {
                *self = Self::with_change(change);
                None
            }
        }
    }

    /// Without a ramp-in: the change, or settled (constants not yet taken).
    fn with_change(change: Option<Change<C>>) -> Self {
        match change {
            Some(change) => Self::Changing(change),
            None => Self::Settled,
        }
    }

    /// Drops the ramp-in (it has ended); what runs beside it goes on.
    pub(super) fn end_ramp_in(&mut self) {
        if let Self::RampIn(..) = self
            && let Self::RampIn(_, change) = core::mem::replace(self, Self::Settled)
        {
            *self = Self::with_change(change);
        }
    }

    /// Ends the change's ramp or blend: the table waiting beside it, if
    /// any, is what remains.
    pub(super) fn end_change(&mut self) {
        // In place when no table waits (nearly always): the enum, which
        // may hold a table, is not moved out and back.
        match self {
            Self::RampIn(_, change) if !change.as_ref().is_some_and(Change::waiting) => {
                *change = None;
            }
            Self::Changing(change) if !change.waiting() => *self = Self::Settled,
            _ => {
                let change = self.replace_change(None);
                self.replace_change(change.and_then(Change::after_end));
            }
        }
    }

    /// Starts `change` (an offset or scaling ramp, a master-scaling
    /// switch, a switch's blend) on a cam with nothing changing.
    ///
    /// # Errors
    /// [`EngineError::Busy`] while another change is under way.
    pub(super) fn begin(&mut self, change: Change<C>) -> Result<(), EngineError> {
        if self.change().is_some() {
            return Err(EngineError::Busy);
        }
        self.replace_change(Some(change));
        Ok(())
    }

    /// Lets `next` wait in the table slot, replacing the table waiting
    /// there; a ramp or blend under way goes on.
    ///
    /// # Errors
    /// [`EngineError::Busy`] for a switch while an offset or scaling
    /// change is being ramped in (nothing changes).
    pub(super) fn wait(&mut self, next: Next<C>) -> Result<(), EngineError> {
        let (change, answer) = match (self.replace_change(None), next) {
            (Some(Change::Offsets(ramp, _)), Next::Seam(queued)) => {
                (Change::Offsets(ramp, Some(queued)), Ok(()))
            }
            (Some(Change::Scaling(ramp, _)), Next::Seam(queued)) => {
                (Change::Scaling(ramp, Some(queued)), Ok(()))
            }
            // Refused: the ramp goes on as it was.
            (Some(ramp @ (Change::Offsets(..) | Change::Scaling(..))), Next::Switch(_)) => {
                (ramp, Err(EngineError::Busy))
            }
            (Some(Change::Blend(blend, _)), next) => (Change::Blend(blend, Some(next)), Ok(())),
            (Some(Change::Waiting(_)) | None, next) => (Change::Waiting(next), Ok(())),
        };
        self.replace_change(Some(change));
        answer
    }

    /// Takes the switch waiting for its position or the next tick out of
    /// a change that is only that switch (a blend keeps it waiting).
    pub(super) fn take_switch(&mut self) -> Option<Pending<C>> {
        if !matches!(self.change(), Some(Change::Waiting(Next::Switch(_)))) {
            return None;
        }
        match self.replace_change(None) {
            Some(Change::Waiting(Next::Switch(pending))) => Some(pending),
            other => {
                self.replace_change(other);
                None
            }
        }
    }

    /// Takes a switch that fired out of a change that is only that switch
    /// and starts its `blend`, if any, beside the ramp-in, in place: what
    /// takes over is swapped out of the waiting switch (a master scaling
    /// left behind, which holds no table) and the variant rewritten where
    /// it is, so the enum is never moved (it is some 450 bytes, and the
    /// tick a switch lands in is one of the dearest, docs/engine.md,
    /// "Benchmarks"). [`Underway::take_switch`] and
    /// [`Underway::start_blend`] in one step; `None`, with nothing
    /// changed, when no switch waits alone.
    #[inline(always)]
    pub(super) fn land_switch(&mut self, blend: Option<Blend>) -> Option<Takeover<C>> {
        let (Self::RampIn(_, Some(Change::Waiting(Next::Switch(pending))))
        | Self::Changing(Change::Waiting(Next::Switch(pending)))) = self
        else {
            return None;
        };
        let takeover = core::mem::replace(
            &mut pending.takeover,
            Takeover::MasterScaling(Zoom::default()),
        );
        // Each variant written where it goes (no whole-enum temporary).
        match (self, blend) {
            (Self::RampIn(_, slot), blend) => *slot = blend.map(|blend| Change::Blend(blend, None)),
            (this, Some(blend)) => *this = Self::Changing(Change::Blend(blend, None)),
            (this, None) => *this = Self::Settled,
        }
        Some(takeover)
    }

    /// Takes the table queued for the seam out of a change that is only
    /// that table (a ramp or blend keeps it waiting).
    pub(super) fn take_seam_table(&mut self) -> Option<Queued<C>> {
        if !matches!(self.change(), Some(Change::Waiting(Next::Seam(_)))) {
            return None;
        }
        match self.replace_change(None) {
            Some(Change::Waiting(Next::Seam(queued))) => Some(queued),
            other => {
                self.replace_change(other);
                None
            }
        }
    }

    /// Begins a switch's blend once the switch is taken (nothing else
    /// changes then; a change there was is replaced).
    pub(super) fn start_blend(&mut self, blend: Blend) {
        // Written in place (the tick of a switch).
        match self {
            Self::RampIn(_, change) => *change = Some(Change::Blend(blend, None)),
            _ => *self = Self::Changing(Change::Blend(blend, None)),
        }
    }

    /// Sets the steady tick's constants (`None`: drops them): only a
    /// settled cam keeps them.
    #[inline(always)]
    pub(super) fn settle(&mut self, steady: Option<Steady>) {
        // In place where it can be: the tick that refreshes the constants
        // copies them, not the whole enum.
        match (&mut *self, steady) {
            (Self::Steady(constants), Some(new)) => *constants = new,
            (Self::Settled, Some(new)) => *self = Self::Steady(new),
            (Self::Steady(_), None) => *self = Self::Settled,
            _ => {}
        }
    }
}

impl<C> Change<C> {
    /// The offset change being ramped in.
    pub(super) fn offsets(&self) -> Option<&OffsetRamp> {
        match self {
            Self::Offsets(ramp, _) => Some(ramp),
            _ => None,
        }
    }

    /// The switch's blend.
    pub(super) fn blend(&self) -> Option<&Blend> {
        match self {
            Self::Blend(blend, _) => Some(blend),
            _ => None,
        }
    }

    /// A table waits, for the seam or a switch.
    pub(super) fn waiting(&self) -> bool {
        match self {
            Self::Offsets(_, queued) | Self::Scaling(_, queued) => queued.is_some(),
            Self::Blend(_, next) => next.is_some(),
            Self::Waiting(_) => true,
        }
    }

    /// The table queued for the seam, whatever runs beside it.
    #[inline(always)]
    pub(super) fn queued(&self) -> Option<&Queued<C>> {
        match self {
            Self::Offsets(_, queued) | Self::Scaling(_, queued) => queued.as_ref(),
            Self::Blend(_, Some(Next::Seam(queued))) | Self::Waiting(Next::Seam(queued)) => {
                Some(queued)
            }
            Self::Blend(..) | Self::Waiting(Next::Switch(_)) => None,
        }
    }

    /// The switch waiting for its position or the next tick (alone or
    /// beside a blend).
    #[inline(always)]
    pub(super) fn pending(&self) -> Option<&Pending<C>> {
        match self {
            Self::Blend(_, Some(Next::Switch(pending))) | Self::Waiting(Next::Switch(pending)) => {
                Some(pending)
            }
            _ => None,
        }
    }

    /// The switch waiting for its position or the next tick.
    pub(super) fn pending_mut(&mut self) -> Option<&mut Pending<C>> {
        match self {
            Self::Blend(_, Some(Next::Switch(pending))) | Self::Waiting(Next::Switch(pending)) => {
                Some(pending)
            }
            _ => None,
        }
    }

    /// What remains once the ramp or blend has ended: the table waiting
    /// beside it, if any.
    fn after_end(self) -> Option<Self> {
        match self {
            Self::Offsets(_, queued) | Self::Scaling(_, queued) => {
                queued.map(|q| Self::Waiting(Next::Seam(q)))
            }
            Self::Blend(_, next) => next.map(Self::Waiting),
            waiting @ Self::Waiting(_) => Some(waiting),
        }
    }

    /// Everything a run leaves behind when it ends: the scaling a ramp was
    /// moving to, and the table that was waiting.
    pub(super) fn into_leftovers(self) -> (Option<ScalingRamp>, Option<Next<C>>) {
        match self {
            Self::Offsets(_, queued) => (None, queued.map(Next::Seam)),
            Self::Scaling(ramp, queued) => (Some(ramp), queued.map(Next::Seam)),
            Self::Blend(_, next) => (None, next),
            Self::Waiting(next) => (None, Some(next)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::OffsetChange;
    use crate::switch::Trigger;

    fn offsets() -> Change<()> {
        let change = OffsetChange {
            master: 0,
            slave: 10,
            distance: NonZeroU64::MIN,
        };
        Change::Offsets(OffsetRamp::new(change, 0, 1), None)
    }

    fn seam() -> Next<()> {
        Next::Seam(Queued {
            curve: (),
            then: AfterPass::Repeat,
            blend: None,
        })
    }

    fn switch() -> Next<()> {
        Next::Switch(Pending::new(Takeover::Table(()), Trigger::Now, None))
    }

    #[test]
    fn a_seam_table_waits_beside_a_ramp_and_outlasts_it() {
        let mut underway = Underway::at_engage(None);
        underway.begin(offsets()).unwrap();
        underway.wait(seam()).unwrap();
        assert!(underway.change().is_some_and(Change::waiting));
        // Not taken while the ramp runs.
        assert!(underway.take_seam_table().is_none());
        underway.end_change();
        assert!(matches!(
            underway.change(),
            Some(Change::Waiting(Next::Seam(_)))
        ));
        assert!(underway.take_seam_table().is_some());
        assert!(underway.is_settled());
    }

    #[test]
    fn a_switch_beside_a_ramp_is_refused_and_the_ramp_goes_on() {
        let mut underway = Underway::at_engage(None);
        underway.begin(offsets()).unwrap();
        assert_eq!(underway.wait(switch()), Err(EngineError::Busy));
        assert!(underway.change().and_then(Change::offsets).is_some());
        assert_eq!(underway.begin(offsets()), Err(EngineError::Busy));
    }

    #[test]
    fn the_ramp_in_goes_with_anything_and_a_change_keeps_it() {
        let ramp = Ramp::new(
            crate::RampIn {
                distance: NonZeroU64::MIN,
            },
            0,
            0,
        );
        let mut underway = Underway::at_engage(Some(ramp));
        underway.settle(None);
        assert!(underway.steady().is_none() && !underway.is_settled());
        underway.wait(switch()).unwrap();
        assert!(underway.ramp_in().is_some());
        assert!(underway.take_switch().is_some());
        assert!(underway.ramp_in().is_some() && underway.change().is_none());
        underway.end_ramp_in();
        assert!(underway.is_settled());
    }

    /// Landing a switch in place is taking it and starting its blend:
    /// with or without a blend, beside a ramp-in or not; a seam table or
    /// a switch behind a blend is not a switch waiting alone.
    #[test]
    fn landing_a_switch_in_place_is_taking_it_and_starting_its_blend() {
        let ramp = Ramp::new(
            crate::RampIn {
                distance: NonZeroU64::MIN,
            },
            0,
            0,
        );
        let end = crate::blend::BlendEnd {
            slave: 10,
            velocity_ratio: 1.0,
        };
        let blend = Blend::start(0, NonZeroU64::MIN, 0, 1.0, [end, end]).unwrap();
        for ramp_in in [None, Some(ramp)] {
            for with in [None, Some(blend)] {
                let mut landed = Underway::at_engage(ramp_in);
                landed.wait(switch()).unwrap();
                let mut taken = landed.clone();
                let takeover = landed.land_switch(with);
                assert!(matches!(takeover, Some(Takeover::Table(()))));
                assert!(taken.take_switch().is_some());
                if let Some(blend) = with {
                    taken.start_blend(blend);
                }
                assert_eq!(landed.ramp_in(), taken.ramp_in());
                assert_eq!(
                    landed.change().and_then(Change::blend),
                    taken.change().and_then(Change::blend)
                );
                assert_eq!(landed.is_settled(), taken.is_settled());
                assert_eq!(landed.change().is_none(), taken.change().is_none());
            }
        }
        let mut seam_table = Underway::at_engage(None);
        seam_table.wait(seam()).unwrap();
        assert!(seam_table.land_switch(None).is_none());
        assert!(seam_table.change().is_some_and(Change::waiting));
        let mut behind = Underway::at_engage(None);
        behind.begin(Change::Blend(blend, None)).unwrap();
        behind.wait(switch()).unwrap();
        assert!(behind.land_switch(None).is_none());
        assert!(behind.change().and_then(Change::blend).is_some());
    }

    #[test]
    fn a_new_table_replaces_the_waiting_one_whatever_its_kind() {
        let mut underway = Underway::at_engage(None);
        underway.wait(switch()).unwrap();
        underway.wait(seam()).unwrap();
        assert!(underway.take_switch().is_none());
        assert!(underway.take_seam_table().is_some());
        assert!(underway.change().is_none());
    }
}
