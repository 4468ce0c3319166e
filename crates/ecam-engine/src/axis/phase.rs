//! The phases of an axis' life and what each one holds.

use core::num::NonZeroU64;

use crate::blend::Blend;
use crate::coast::Coast;
use crate::coupling::{Engagement, Place};
use crate::offset_ramp::OffsetRamp;
use crate::ramp::Ramp;
use crate::scaling::ScalingRamp;
use crate::start::StartWatch;
use crate::steady::Steady;
use crate::stop::CycleEnd;
use crate::switch::Pending;
use crate::{AxisState, EngineError, MasterPosition};

use super::AfterPass;
use super::lane::LaneConstants;
use super::plan::Plan;

/// The life of an axis; each phase holds what only it has, so a stopping
/// axis without a cycle end, or a running one without an engagement,
/// cannot be built.
#[derive(Clone, Debug)]
pub(super) enum Phase<C> {
    /// Not coupled; the slave holds.
    Idle,
    /// Waiting for the start condition.
    Armed(Armed),
    /// Following the cam.
    Running(Engaged<C>),
    /// Following the cam to the end of the current cycle.
    Stopping(Engaged<C>, CycleEnd),
    /// A one-shot ended or an end-of-cycle stop completed; the slave holds.
    Finished,
    /// Out of the cam, moving at velocity (or decelerating to rest).
    Velocity(Coast),
}

/// An armed axis' start watch.
#[derive(Clone, Copy, Debug)]
pub(super) struct Armed {
    pub(super) watch: StartWatch,
    /// The master of the last tick since arming: delays and crossings
    /// count from the first tick after arming, not from motion before it.
    pub(super) previous: Option<i64>,
    /// The start came and a delay is being counted.
    pub(super) delaying: bool,
}

/// What an engaged axis has.
#[derive(Clone, Debug)]
pub(super) struct Engaged<C> {
    pub(super) engagement: Engagement,
    pub(super) ramp: Option<Ramp>,
    /// The place followed at the last tick (where a stop is measured from).
    pub(super) place: Place,
    /// A table waiting for the next seam ([`CamAxis::queue_curve`]).
    pub(super) queued: Option<(C, AfterPass)>,
    /// The blend for the queued table's seam switch.
    pub(super) seam_blend: Option<NonZeroU64>,
    /// A table waiting for a master position or the next tick
    /// ([`CamAxis::switch_curve`]); never together with `queued`.
    pub(super) pending: Option<Pending<C>>,
    /// The blend from the last switch's old cam, while it runs.
    pub(super) blend: Option<Blend>,
    /// An offset change being ramped in ([`CamAxis::change_offsets`]).
    pub(super) offsets: Option<OffsetRamp>,
    /// A slave-scaling change being ramped in
    /// ([`CamAxis::change_slave_scaling`]).
    pub(super) scaling: Option<ScalingRamp>,
    /// The master followed at the last tick, counts × 2^32 plus the
    /// fraction (where a switch position is crossed from).
    pub(super) followed: i128,
    /// The engagement's 64-bit constants once the cam has settled (no
    /// ramp-in, no change under way); the general tick clears and refills
    /// them, and every change request clears them (`online.rs`), so they
    /// never outlive what they were taken from and the steady tick needs
    /// no other check.
    pub(super) steady: Option<Steady>,
    /// The fast lane's 64-bit constants of `engagement` on the axis'
    /// geometry (and on a slave-scaling ramp's target), whatever is under
    /// way (`lane.rs`): taken by the lane or at a request, kept up to date
    /// by the lane, dropped by the general tick, which may change either.
    pub(super) lane: Option<LaneConstants>,
    /// The switch waiting in `pending` or the table in `queued`, prepared
    /// when it was asked for (`plan.rs`).
    pub(super) plan: Option<Plan>,
}

impl<C> Engaged<C> {
    /// A table switch, blend, offset or scaling change is under way.
    pub(super) fn changing(&self) -> bool {
        self.offsets.is_some()
            || self.scaling.is_some()
            || self.blend.is_some()
            || self.pending.is_some()
            || self.queued.is_some()
    }

    /// Drops a blend the position `at` has completed, moving the new
    /// cam's output by the blend's whole shift so that the cam goes on
    /// where the blend ended.
    pub(super) fn end_blend(&mut self, at: MasterPosition) -> Result<(), EngineError> {
        if let Some(shift) = self.blend.as_ref().and_then(|b| b.finished_at(at)) {
            self.engagement.shift_output(shift)?;
            self.blend = None;
        }
        Ok(())
    }

    /// The engagement in effect at `master`, an offset ramp included.
    pub(super) fn engagement_at(&self, master: i64) -> Result<Engagement, EngineError> {
        match &self.offsets {
            Some(ramp) => ramp.apply(&self.engagement, master),
            None => Ok(self.engagement),
        }
    }
}

impl<C> Phase<C> {
    pub(super) fn state(&self) -> AxisState {
        match self {
            Self::Idle => AxisState::Idle,
            Self::Armed(Armed { delaying: true, .. }) => AxisState::Delaying,
            Self::Armed(_) => AxisState::Armed,
            Self::Running(_) => AxisState::Running,
            Self::Stopping(..) => AxisState::Stopping,
            Self::Finished => AxisState::Finished,
            Self::Velocity(_) => AxisState::Velocity,
        }
    }

    pub(super) fn engaged(&self) -> Option<&Engaged<C>> {
        match self {
            Self::Running(e) | Self::Stopping(e, _) => Some(e),
            _ => None,
        }
    }
}
