//! The phases of an axis' life and what each one holds.

use crate::blend::Blend;
use crate::coast::Coast;
use crate::coupling::{Engagement, Geometry, Place};
use crate::offset_ramp::OffsetRamp;
use crate::ramp::Ramp;
use crate::start::StartWatch;
use crate::stop::CycleEnd;
use crate::{AxisState, EngineError, MasterPosition};

use super::engage::ReadyEngagement;
use super::lane_constants::LaneConstants;
use super::prepared::Plan;
use super::underway::{Change, Underway};

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
    /// The engagement worked out at arm for a start whose master position
    /// is known then (`engage.rs`), so that the tick that engages only
    /// takes it.
    pub(super) ready: Option<ReadyEngagement>,
}

/// What an engaged axis has.
#[derive(Clone, Debug)]
pub(super) struct Engaged<C> {
    pub(super) engagement: Engagement,
    /// The place followed at the last tick (where a stop is measured from).
    pub(super) place: Place,
    /// The master followed at the last tick, counts × 2^32 plus the
    /// fraction (where a switch position is crossed from).
    pub(super) followed: i128,
    /// The ramp-in, a change, a blend or a table waiting, or nothing
    /// (settled, with the steady tick's constants): `underway.rs`.
    pub(super) underway: Underway<C>,
    /// The fast lane's 64-bit constants of `engagement` on the axis'
    /// geometry (and on a slave-scaling ramp's target), whatever is under
    /// way (`lane.rs`): taken by the lane or at a request, kept up to date
    /// by the lane, dropped by the general tick, which may change either.
    pub(super) lane: Option<LaneConstants>,
    /// The switch or the seam table waiting in `underway`, prepared when
    /// it was asked for (`plan.rs`).
    pub(super) plan: Option<Plan>,
}

impl<C> Engaged<C> {
    /// The ramp-in, while it runs.
    pub(super) fn ramp_in(&self) -> Option<&Ramp> {
        self.underway.ramp_in()
    }

    /// The offset change being ramped in.
    pub(super) fn offsets(&self) -> Option<&OffsetRamp> {
        self.underway.change().and_then(Change::offsets)
    }

    /// The blend from the last switch's old cam, while it runs.
    pub(super) fn blend(&self) -> Option<&Blend> {
        self.underway.change().and_then(Change::blend)
    }

    /// Drops a blend the position `at` has completed, moving the new
    /// cam's output by the blend's whole shift so that the cam goes on
    /// where the blend ended.
    pub(super) fn end_blend(&mut self, at: MasterPosition) -> Result<(), EngineError> {
        if let Some(shift) = self.blend().and_then(|b| b.finished_at(at)) {
            self.engagement.shift_output(shift)?;
            self.underway.end_change();
        }
        Ok(())
    }

    /// Takes the fast lane's constants of the engagement on `geometry` if
    /// they are missing (a cam settled since engaging runs on the steady
    /// tick's own): at a request, so that the tick the change starts in
    /// does not. `None` when they leave 64 bits (the lane then leaves
    /// the ticks to the general path, as it would have).
    pub(super) fn take_lane_constants(&mut self, geometry: &Geometry) {
        if self.lane.is_none() {
            self.lane = self
                .engagement
                .steady(geometry)
                .map(|cam| LaneConstants { cam, target: None });
        }
    }

    /// The engagement in effect at `master`, an offset ramp included.
    pub(super) fn engagement_at(&self, master: i64) -> Result<Engagement, EngineError> {
        match self.offsets() {
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
