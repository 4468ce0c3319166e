//! Changes handed to a running cam: a table switch (at the seam, at a
//! master position, at once), offsets and scalings on the fly. These calls
//! only record the request; the tick carries it out (`takeover.rs`, and
//! the offset and scaling ramps).

use core::num::NonZeroU64;

use ecam_core::{CamCurve, Cursor};

use crate::coupling::{Extent, Geometry};
use crate::offset_ramp::OffsetRamp;
use crate::scaling::ScalingRamp;
use crate::switch::{Pending, Takeover, Trigger};
use crate::{AxisConfig, EngineError, OffsetChange, SwitchAt, Zoom};

use super::CamAxis;
use super::phase::Phase;
use super::underway::{Change, Next, Queued};

/// What an axis does once a table queued at the seam has run its first pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AfterPass {
    /// Keep repeating it as the coupling says.
    #[default]
    Repeat,
    /// Finish at the end of the pass (the slave holds there).
    Finish,
}

impl<C: CamCurve> CamAxis<C> {
    /// Hands a new table to the axis. Idle, armed or finished, it replaces
    /// the table at once. While the cam is engaged it takes over at the next
    /// seam (cycle boundary) the master crosses, in either direction: the
    /// new table's cycle starts there and the output continues from the
    /// slave position at the seam, without a step (velocity is continuous
    /// when the tables' slopes agree at the seam). A second call before the
    /// seam replaces the waiting table. After the switch the old table can
    /// be taken back with [`CamAxis::take_retired_curve`].
    ///
    /// # Errors
    /// As [`CamAxis::new`] for a table that does not fit the configuration,
    /// and [`EngineError::NoSeam`] for an engaged normal (non-repeating)
    /// cam; the running cam is left untouched.
    pub fn queue_curve(&mut self, curve: C) -> Result<(), EngineError> {
        self.queue_curve_then(curve, AfterPass::Repeat)
    }

    /// As [`CamAxis::queue_curve`], and says what follows the new table's
    /// first pass: with [`AfterPass::Finish`] the axis runs the table once
    /// from the seam and finishes at its end (the PLC's midCAMend table,
    /// which ends at standstill). Idle or armed, `then` is ignored: the
    /// configuration's coupling decides.
    ///
    /// # Errors
    /// As [`CamAxis::queue_curve`].
    pub fn queue_curve_then(&mut self, curve: C, then: AfterPass) -> Result<(), EngineError> {
        self.queue_for_seam(Queued {
            curve,
            then,
            blend: None,
        })
    }

    /// Queues a table for the next seam (engaged; its switch prepared
    /// here, `plan.rs`), or replaces the table at once (not engaged;
    /// `then` and the blend are the engaged cam's).
    fn queue_for_seam(&mut self, queued: Queued<C>) -> Result<(), EngineError> {
        let geometry = Geometry::new(&queued.curve, &self.config)?;
        match &mut self.phase {
            Phase::Running(engaged) | Phase::Stopping(engaged, _) => {
                if geometry.extent == Extent::Single {
                    return Err(EngineError::NoSeam);
                }
                // A seam table never meets a refusal: it may wait beside
                // any ramp or blend.
                engaged.underway.wait(Next::Seam(queued))?;
                self.plan_waiting();
                self.clear_retired_slot();
            }
            Phase::Idle | Phase::Armed(_) | Phase::Finished | Phase::Velocity(_) => {
                self.geometry = geometry;
                self.cursor = Cursor::new();
                self.retired = Some(core::mem::replace(&mut self.curve, queued.curve));
                // An armed axis' prepared engagement was of the old table.
                self.prepare_engagement();
            }
        }
        Ok(())
    }

    /// Hands a new table to the axis, taking over where `at` says. Idle,
    /// armed or finished, it replaces the table at once. While the cam is
    /// running, [`SwitchAt::NextSeam`] is [`CamAxis::queue_curve`]; with
    /// [`SwitchAt::MasterPosition`] and [`SwitchAt::Now`] the new cam takes
    /// over at that master position (or this tick's master), aligned to
    /// the master as [`AxisConfig::master_align`] says (as at engage) and
    /// anchored on the old cam there: the slave's position is continuous.
    /// With a blend distance the velocity is too: the slave's velocity
    /// moves from the old cam's to the new cam's over that master travel
    /// and stays between them (see docs/engine.md, "Changing the table
    /// while engaged"). A second call before the switch replaces the
    /// waiting table; a switch that comes due while a blend runs waits for
    /// its end. `events.table_switched` marks the tick of the switch; the
    /// old table can be taken back with [`CamAxis::take_retired_curve`].
    ///
    /// # Errors
    /// As [`CamAxis::queue_curve`]; [`EngineError::Busy`] for a position
    /// or at-once switch during an end-of-cycle stop. The running cam is
    /// left untouched.
    pub fn switch_curve(&mut self, curve: C, at: SwitchAt) -> Result<(), EngineError> {
        let (trigger, blend) = match at {
            SwitchAt::NextSeam { blend } => {
                return self.queue_for_seam(Queued {
                    curve,
                    then: AfterPass::Repeat,
                    blend,
                });
            }
            SwitchAt::MasterPosition { position, blend } => (Trigger::Position(position), blend),
            SwitchAt::Now { blend } => (Trigger::Now, blend),
        };
        Geometry::new(&curve, &self.config)?;
        match &mut self.phase {
            // Refused beside an offset or scaling ramp.
            Phase::Running(engaged) => {
                engaged.underway.wait(Next::Switch(Pending::new(
                    Takeover::Table(curve),
                    trigger,
                    blend,
                )))?;
                self.plan_waiting();
                self.clear_retired_slot();
                Ok(())
            }
            Phase::Stopping(..) => Err(EngineError::Busy),
            Phase::Idle | Phase::Armed(_) | Phase::Finished | Phase::Velocity(_) => {
                self.queue_curve(curve)
            }
        }
    }

    /// Drops a retired table the caller has not taken back, here rather
    /// than in the tick: the tick that lands the table now waiting (or
    /// ends the run with it) retires the running one into this slot, and
    /// overwriting a table there would free it inside the control cycle.
    fn clear_retired_slot(&mut self) {
        drop(self.retired.take());
    }

    /// True while a queued table waits for the next seam, a master
    /// position or the next tick.
    pub fn has_queued_curve(&self) -> bool {
        self.phase
            .engaged()
            .and_then(|e| e.underway.change())
            .is_some_and(Change::waiting)
    }

    /// Changes the master and slave offsets of the running cam by
    /// `change`, ramped in over `change.distance` master counts from the
    /// master the axis followed last (PLCopen `MasterOffset` and
    /// `SlaveOffset` changed in sync; see docs/engine.md, "Offsets on the
    /// fly"). Position, velocity and acceleration stay continuous; the
    /// final offsets are exact.
    ///
    /// # Errors
    /// [`EngineError::NotRunning`] unless the cam is running;
    /// [`EngineError::Busy`] while a table switch waits or blends, or an
    /// offset change is still being ramped in.
    pub fn change_offsets(&mut self, change: OffsetChange) -> Result<(), EngineError> {
        let mden = self.geometry.master_den();
        match &mut self.phase {
            Phase::Running(engaged) => {
                let from = i64::try_from(engaged.followed >> 32).unwrap_or(i64::MAX);
                let ramp = OffsetRamp::new(change, from, mden);
                engaged.underway.begin(Change::Offsets(ramp, None))?;
                // The lane's constants, and those of the engagement the
                // ramp ends on, taken here rather than in the cycle.
                engaged.take_lane_constants(&self.geometry);
                let end = ramp.ended(&engaged.engagement);
                if let Some(lane) = engaged.lane.as_mut() {
                    lane.target = end.ok().and_then(|e| e.steady(&self.geometry));
                }
                Ok(())
            }
            _ => Err(EngineError::NotRunning),
        }
    }

    /// Changes the slave scaling (slave zoom) of the running cam, ramped
    /// in over `distance` master counts from the master the axis followed
    /// last (PLCopen `SlaveScaling` changed in sync; see docs/engine.md,
    /// "Scaling on the fly"): the command moves from the cam with the old
    /// scaling to the cam with the new one, position and velocity
    /// continuous; afterwards it is exactly the cam with the new scaling
    /// and [`AxisConfig::slave_zoom`] reads the new value.
    ///
    /// # Errors
    /// As [`CamAxis::change_offsets`].
    pub fn change_slave_scaling(
        &mut self,
        zoom: Zoom,
        distance: NonZeroU64,
    ) -> Result<(), EngineError> {
        let target = self.geometry.with_slave_zoom(zoom);
        match &mut self.phase {
            Phase::Running(engaged) => {
                let from = i64::try_from(engaged.followed >> 32).unwrap_or(i64::MAX);
                let ramp = ScalingRamp::new(target, from, distance);
                engaged.underway.begin(Change::Scaling(ramp, None))?;
                // The lane's constants, on the new scaling too, taken here
                // rather than in the cycle.
                engaged.take_lane_constants(&self.geometry);
                if let Some(lane) = engaged.lane.as_mut() {
                    lane.target = engaged.engagement.steady(&target);
                }
                self.config.slave_zoom = zoom;
                Ok(())
            }
            _ => Err(EngineError::NotRunning),
        }
    }

    /// Changes the master scaling (master zoom) of the running cam at the
    /// next whole master count (as [`SwitchAt::Now`]): the cam's phase (its
    /// table input) and the slave's position are kept there and from then
    /// on the table runs at the new scaling; with `blend` the velocity
    /// moves from the old to the new over that master travel, as a table
    /// switch's blend does. Afterwards [`AxisConfig::master_zoom`] reads
    /// the new value and the cam is an exact function of the master again.
    ///
    /// # Errors
    /// As [`CamAxis::change_offsets`], and as [`CamAxis::new`] for a
    /// scaling that does not fit the table.
    pub fn change_master_scaling(
        &mut self,
        zoom: Zoom,
        blend: Option<NonZeroU64>,
    ) -> Result<(), EngineError> {
        Geometry::new(
            &self.curve,
            &AxisConfig {
                master_zoom: zoom,
                ..self.config
            },
        )?;
        match &mut self.phase {
            Phase::Running(engaged) => {
                engaged
                    .underway
                    .begin(Change::Waiting(Next::Switch(Pending::new(
                        Takeover::MasterScaling(zoom),
                        Trigger::Now,
                        blend,
                    ))))?;
                self.plan_waiting();
                Ok(())
            }
            _ => Err(EngineError::NotRunning),
        }
    }

    /// True while an offset change is being ramped in.
    pub fn is_changing_offsets(&self) -> bool {
        self.phase.engaged().is_some_and(|e| e.offsets().is_some())
    }

    /// True while a switch's blend runs.
    pub fn is_blending(&self) -> bool {
        self.phase.engaged().is_some_and(|e| e.blend().is_some())
    }

    /// The table the last switch or replacement retired, if not yet taken.
    /// It is kept until a new table is queued on the running cam, which
    /// drops it (a tick never frees a table: the tick that switches puts
    /// the old one here, and the slot is empty by then).
    pub fn take_retired_curve(&mut self) -> Option<C> {
        self.retired.take()
    }
}
