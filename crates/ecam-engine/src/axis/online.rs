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
        self.queue(curve, then, None)
    }

    /// [`CamAxis::queue_curve_then`] with the blend of the seam switch;
    /// a running cam's switch is prepared here (`plan.rs`).
    fn queue(
        &mut self,
        curve: C,
        then: AfterPass,
        blend: Option<NonZeroU64>,
    ) -> Result<(), EngineError> {
        let geometry = Geometry::new(&curve, &self.config)?;
        match &mut self.phase {
            Phase::Running(engaged) | Phase::Stopping(engaged, _) => {
                if geometry.extent == Extent::Single {
                    return Err(EngineError::NoSeam);
                }
                engaged.pending = None;
                engaged.seam_blend = blend;
                engaged.queued = Some((curve, then));
                engaged.steady = None;
                self.plan_waiting();
            }
            Phase::Idle | Phase::Armed(_) | Phase::Finished | Phase::Velocity(_) => {
                self.geometry = geometry;
                self.cursor = Cursor::new();
                self.retired = Some(core::mem::replace(&mut self.curve, curve));
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
            SwitchAt::NextSeam { blend } => return self.queue(curve, AfterPass::Repeat, blend),
            SwitchAt::MasterPosition { position, blend } => (Trigger::Position(position), blend),
            SwitchAt::Now { blend } => (Trigger::Now, blend),
        };
        Geometry::new(&curve, &self.config)?;
        match &mut self.phase {
            Phase::Running(engaged) if engaged.offsets.is_some() || engaged.scaling.is_some() => {
                Err(EngineError::Busy)
            }
            Phase::Running(engaged) => {
                engaged.queued = None;
                engaged.pending = Some(Pending::new(Takeover::Table(curve), trigger, blend));
                engaged.steady = None;
                self.plan_waiting();
                Ok(())
            }
            Phase::Stopping(..) => Err(EngineError::Busy),
            Phase::Idle | Phase::Armed(_) | Phase::Finished | Phase::Velocity(_) => {
                self.queue_curve(curve)
            }
        }
    }

    /// True while a queued table waits for the next seam, a master
    /// position or the next tick.
    pub fn has_queued_curve(&self) -> bool {
        self.phase
            .engaged()
            .is_some_and(|e| e.queued.is_some() || e.pending.is_some())
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
                if engaged.changing() {
                    return Err(EngineError::Busy);
                }
                let from = i64::try_from(engaged.followed >> 32).unwrap_or(i64::MAX);
                engaged.offsets = Some(OffsetRamp::new(change, from, mden));
                engaged.steady = None;
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
                if engaged.changing() {
                    return Err(EngineError::Busy);
                }
                let from = i64::try_from(engaged.followed >> 32).unwrap_or(i64::MAX);
                engaged.scaling = Some(ScalingRamp::new(target, from, distance));
                engaged.steady = None;
                // The lane's constants on the new scaling, taken here
                // rather than in the cycle.
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
                if engaged.changing() {
                    return Err(EngineError::Busy);
                }
                engaged.pending = Some(Pending::new(
                    Takeover::MasterScaling(zoom),
                    Trigger::Now,
                    blend,
                ));
                engaged.steady = None;
                self.plan_waiting();
                Ok(())
            }
            _ => Err(EngineError::NotRunning),
        }
    }

    /// True while an offset change is being ramped in.
    pub fn is_changing_offsets(&self) -> bool {
        self.phase.engaged().is_some_and(|e| e.offsets.is_some())
    }

    /// True while a switch's blend runs.
    pub fn is_blending(&self) -> bool {
        self.phase.engaged().is_some_and(|e| e.blend.is_some())
    }

    /// The table the last switch or replacement retired, if not yet taken.
    pub fn take_retired_curve(&mut self) -> Option<C> {
        self.retired.take()
    }
}
