//! A native API shaped like PLCopen Motion Control Part 1 cam blocks:
//! `MC_CamTableSelect`, `MC_CamIn`, `MC_CamOut`, with their `InSync`,
//! `EndOfProfile`, `Busy`, `Error` outputs.
//!
//! It is a thin layer over [`CamAxis`]: the same exact arithmetic, the same
//! tick. Choices where PLCopen leaves room:
//! - a periodic table with an absolute slave is re-evaluated every cycle
//!   ([`Coupling::Periodic`]: the slave jumps at the seam where the first
//!   and last values differ, the jump going out under the frequency
//!   limit); with a relative slave the stroke accumulates
//!   ([`Coupling::Repeat`]), so the slave is continuous;
//! - a relative slave (`SlaveAbsolute = FALSE`, or
//!   [`CamInStartMode::Relative`]) adds the slave's start position to the
//!   table values, as RTmotion and CODESYS do; [`CamInStartMode::Bumpless`]
//!   is the explicit no-step option;
//! - scalings are signed ([`Zoom::signed`]); `MasterScaling` follows
//!   RTmotion's convention, table input = master × scaling + offset
//!   ([`CamIn::master_profile_scaled`] gives the standard's wording);
//! - `ExecutionMode` queued makes a table selected while engaged take over
//!   by itself at the next seam; the blending `BufferMode`s are refused
//!   ([`EngineError::UnsupportedBufferMode`]);
//! - a non-periodic table with an absolute master runs over the table's
//!   own master range and then keeps the slave coupled at the end value
//!   ([`Coupling::Normal`]; `EndOfProfile` set while the master is at or
//!   past the end, still `Active` and `InSync`); with a relative master it
//!   runs once from engage and ends the coupling ([`Coupling::OneShot`]);
//! - `MC_CamOut` as the standard says: the slave leaves the cam and keeps
//!   the velocity it had ([`CamOut::AtVelocity`], the default) until
//!   [`McCamAxis::stop`] or [`McCamAxis::halt`] ends the motion; the
//!   options [`CamOut::Hold`] (stop where it is) and
//!   [`CamOut::EndOfCycle`] (follow to the end of the current cycle, then
//!   hold) are what other controllers offer;
//! - `EndOfProfile` pulses for one cycle each time a cycle of the table
//!   completes, and when a non-periodic table ends;
//! - `InSync` is set once the slave follows the cam (ramp-in, blend and
//!   offset or scaling ramps done) *and* no pulses are owed;
//! - `MC_CamIn` while a cam is engaged changes it on the fly: a table
//!   selected with [`McCamAxis::select_table`] takes over as `BufferMode`
//!   and `ActivationMode` say (with a velocity blend over
//!   [`CamIn::blend`]), and changed offsets or scalings are ramped in over
//!   the same distance, never stepped. See docs/engine.md, "PLCopen
//!   mapping".
//!
//! ```
//! use ecam_core::PointTable;
//! use ecam_engine::plcopen::{CamIn, CamOut, CamTableSelect, McCamAxis};
//!
//! let table = PointTable::from_pairs(&[(0, 0), (500, 200), (1000, 0)])?;
//! let mut axis = McCamAxis::new(table)?;
//! axis.select(CamTableSelect { periodic: true, ..CamTableSelect::default() })?;
//! axis.cam_in(&CamIn::default())?;
//! let status = axis.tick(250, 1000);
//! assert!(status.in_sync && status.busy);
//! assert_eq!(status.output.slave, 100);
//! axis.cam_out(CamOut::Hold);
//! assert!(!axis.tick(300, 1000).busy);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use core::num::NonZeroU64;

use ecam_core::CamCurve;

use crate::{
    AxisConfig, CamAxis, Coupling, EngineError, MasterAlign, OffsetChange, RampIn, RampInLimits,
    SlaveAlign, StartMode, StopKind, SwitchAt, TickInput, TickOutput, Zoom,
};

/// `MC_CamIn` `BufferMode` for a cam-in while a cam is engaged.
///
/// PLCopen's blending modes shape the velocity where two moves meet; a cam
/// switch has no end velocity to choose, it blends from the old cam's
/// velocity to the new one's over [`CamIn::blend`]. The blending modes are
/// therefore refused ([`EngineError::UnsupportedBufferMode`]) rather than
/// read loosely.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BufferMode {
    /// Take over as `ActivationMode` says (at once by default).
    #[default]
    Aborting,
    /// Take over when the running cam's cycle ends (the next seam).
    Buffered,
    /// `mcBlendingLow`: refused.
    BlendingLow,
    /// `mcBlendingPrevious`: refused.
    BlendingPrevious,
    /// `mcBlendingNext`: refused.
    BlendingNext,
    /// `mcBlendingHigh`: refused.
    BlendingHigh,
}

/// `MC_CamTableSelect` `ExecutionMode`: when a table selected while a cam
/// is engaged becomes valid. Idle there is nothing to wait for: both
/// replace the table at once.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ExecutionMode {
    /// `mcImmediate`: valid at once for the next `MC_CamIn`, which switches
    /// to it as its `BufferMode` and `ActivationMode` say.
    #[default]
    Immediate,
    /// `mcQueued`: valid when the running cam's cycle ends: the table takes
    /// over by itself at the next seam (as a buffered `MC_CamIn` would),
    /// `Busy` until then. Refused for a non-periodic cam, which has no seam
    /// ([`EngineError::NoSeam`]).
    Queued,
}

/// `MC_CamIn` `ActivationMode`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ActivationMode {
    /// Now (idle: on the next cycle; engaged: at once).
    #[default]
    Immediate,
    /// When the master reaches this position.
    AtMasterPosition(i64),
    /// At the start of the next table cycle (engaged: the next seam).
    NextCycle,
}

/// `MC_CamTableSelect`: how the selected table is interpreted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CamTableSelect {
    /// The table repeats (otherwise it runs once and ends the coupling).
    pub periodic: bool,
    /// The master's absolute position is the table input (otherwise the
    /// table starts at its beginning when the cam engages).
    pub master_absolute: bool,
    /// The table value is the absolute slave position (otherwise the table
    /// is followed relative to where the slave stands at engage).
    pub slave_absolute: bool,
    /// When a table selected while engaged becomes valid.
    pub execution_mode: ExecutionMode,
}

impl CamTableSelect {
    /// The same interpretation of the table (all but the execution mode).
    fn reads_like(&self, other: &Self) -> bool {
        (self.periodic, self.master_absolute, self.slave_absolute)
            == (other.periodic, other.master_absolute, other.slave_absolute)
    }
}

impl Default for CamTableSelect {
    fn default() -> Self {
        Self {
            periodic: true,
            master_absolute: true,
            slave_absolute: true,
            execution_mode: ExecutionMode::Immediate,
        }
    }
}

/// `MC_CamIn` start modes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CamInStartMode {
    /// As [`CamTableSelect::slave_absolute`] says (an absolute slave may jump).
    #[default]
    Absolute,
    /// The table values are added to the slave's position at engage (plus
    /// `SlaveOffset`), as PLCopen's relative mode and
    /// `SlaveAbsolute = false` read in the standard's implementations
    /// (RTmotion, CODESYS): a table that does not start at 0 where it
    /// engages steps the slave by that value.
    Relative,
    /// The slave follows the table relative to its position at engage,
    /// without a position step: the table value at engage lands where the
    /// slave stands (plus `SlaveOffset`). An option of ours, not PLCopen's.
    Bumpless,
    /// Blend onto the cam over `distance` master counts without a velocity
    /// jump (see [`RampIn`]).
    RampIn {
        /// Master counts of the blend.
        distance: NonZeroU64,
    },
}

/// `MC_CamIn` inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CamIn {
    /// Added to the table input (absolute master) or to the table start
    /// (relative master).
    pub master_offset: i64,
    /// Added to the slave position the table gives.
    pub slave_offset: i64,
    /// Master scaling, signed ([`Zoom::signed`]): table input = master ×
    /// scaling + `master_offset`, the convention of RTmotion (Intel's
    /// PLCopen implementation) and of the engine's master zoom. A scaling
    /// of 2 runs the profile twice as fast; a negative one runs it
    /// backwards. The standard's own sentence ("the master profile is
    /// multiplied by the factor", which stretches it) is the reciprocal:
    /// [`CamIn::master_profile_scaled`] sets it that way.
    pub master_scaling: Zoom,
    /// Slave scaling, signed: slave = table value × scaling (+ offset); a
    /// negative scaling mirrors the cam.
    pub slave_scaling: Zoom,
    /// How the slave engages.
    pub start_mode: CamInStartMode,
    /// When the coupling starts (or, engaged, the new table takes over).
    pub activation: ActivationMode,
    /// Engaged: how the new table relates to the running one.
    pub buffer_mode: BufferMode,
    /// Engaged: master counts over which a new table is blended in and
    /// changed offsets or scalings are ramped in.
    pub blend: NonZeroU64,
    /// PLCopen `MasterSyncPosition` and `MasterStartDistance`: in sync
    /// when the master reaches the first, ramping in from the second's
    /// distance before it (the master's direction: `forward`). Overrides
    /// `activation` and a [`CamInStartMode::RampIn`] distance.
    pub sync_at: Option<SyncAt>,
    /// Limits and direction of the ramp-in (PLCopen ramp-in with limits,
    /// `ramp_in_pos`, `ramp_in_neg`); see [`crate::CamAxis::set_ramp_in_limits`].
    pub ramp_limits: Option<RampInLimits>,
}

impl CamIn {
    /// The same inputs with the master scaling read as the PLCopen
    /// standard words it: the master profile (the table's master
    /// positions) multiplied by `factor`, so a factor of 2 stretches one
    /// table cycle over twice the master travel (table input = master /
    /// `factor`).
    #[must_use]
    pub fn master_profile_scaled(self, factor: Zoom) -> Self {
        Self {
            master_scaling: factor.reciprocal(),
            ..self
        }
    }
}

/// PLCopen `MasterSyncPosition` / `MasterStartDistance` (see [`RampIn::sync_at`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SyncAt {
    /// `MasterSyncPosition`.
    pub position: i64,
    /// `MasterStartDistance`.
    pub start_distance: NonZeroU64,
    /// The master approaches the sync position forwards.
    pub forward: bool,
}

impl Default for CamIn {
    fn default() -> Self {
        Self {
            master_offset: 0,
            slave_offset: 0,
            master_scaling: Zoom::ONE,
            slave_scaling: Zoom::ONE,
            start_mode: CamInStartMode::Absolute,
            activation: ActivationMode::Immediate,
            buffer_mode: BufferMode::Aborting,
            blend: DEFAULT_BLEND,
            sync_at: None,
            ramp_limits: None,
        }
    }
}

/// The default [`CamIn::blend`]: 1000 master counts.
pub const DEFAULT_BLEND: NonZeroU64 = match NonZeroU64::new(1000) {
    Some(v) => v,
    None => NonZeroU64::MIN,
};

/// `MC_CamOut`: how the slave leaves the cam.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CamOut {
    /// As PLCopen says: the slave continues at the velocity it has (see
    /// [`CamAxis::cam_out_at_velocity`]) until [`McCamAxis::stop`] or
    /// [`McCamAxis::halt`].
    #[default]
    AtVelocity,
    /// The slave holds where it is (a velocity step; the behaviour of a
    /// plain disengage).
    Hold,
    /// The slave follows the cam to the end of the current table cycle,
    /// then holds there (an implementation option, e.g. for a knife that
    /// must finish its cut).
    EndOfCycle,
}

/// The outputs of the cam blocks after one cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CamStatus {
    /// `InSync`: the slave follows the cam (any ramp-in, blend or ramped
    /// change done) and no pulses are owed.
    pub in_sync: bool,
    /// `EndOfProfile`: a table cycle (or the non-periodic table) ended this cycle.
    pub end_of_profile: bool,
    /// `Busy`: the coupling is pending or active, or pulses are still owed.
    pub busy: bool,
    /// `Active`: the cam is engaged.
    pub active: bool,
    /// `Error`/`ErrorID`: a fault stopped the cam this cycle.
    pub error: Option<EngineError>,
    /// The full engine output.
    pub output: TickOutput,
}

/// One slave axis driven PLCopen-style.
#[derive(Clone, Debug)]
pub struct McCamAxis<C> {
    axis: CamAxis<C>,
    select: CamTableSelect,
    /// A table selected while engaged, for the next `cam_in`.
    next_table: Option<C>,
    /// The inputs of the cam-in that engaged (offsets and scalings in effect).
    engaged_with: Option<CamIn>,
    /// Counts the commands (`cam_in`, `cam_out`) accepted, so a function
    /// block can tell when another command took over.
    command: u64,
    /// A rotary slave (see [`McCamAxis::set_modulo`]).
    modulo: Option<crate::ModuloAxis>,
}

impl<C: CamCurve> McCamAxis<C> {
    /// An axis with `curve` as its selected table (periodic, absolute).
    ///
    /// # Errors
    /// The curve's master range is empty ([`EngineError::EmptyCycle`]).
    pub fn new(curve: C) -> Result<Self, EngineError> {
        let select = CamTableSelect::default();
        Ok(Self {
            axis: CamAxis::new(curve, AxisConfig::default())?,
            select,
            next_table: None,
            engaged_with: None,
            command: 0,
            modulo: None,
        })
    }

    /// Makes the slave a rotary (modulo) axis for the next `cam_in`s: an
    /// absolute table is placed in the turn the [`crate::ModuloStart`]
    /// picks ([`SlaveAlign::Modulo`]); relative starts are unchanged.
    /// `None` makes it linear again.
    pub fn set_modulo(&mut self, modulo: Option<crate::ModuloAxis>) {
        self.modulo = modulo;
    }

    /// `MC_CamTableSelect`: how the table is read at the next `cam_in`.
    ///
    /// # Errors
    /// [`EngineError::Busy`] while a cam is engaged.
    pub fn select(&mut self, select: CamTableSelect) -> Result<(), EngineError> {
        if self.axis.state().is_active() {
            return Err(EngineError::Busy);
        }
        self.select = select;
        Ok(())
    }

    /// `MC_CamTableSelect` with a table (`CamTableID`): idle, the table
    /// replaces the current one at once; engaged, as
    /// [`CamTableSelect::execution_mode`] says: it waits for the next
    /// [`McCamAxis::cam_in`], which switches to it on the fly
    /// ([`ExecutionMode::Immediate`]), or takes over by itself at the next
    /// seam ([`ExecutionMode::Queued`]; see
    /// [`McCamAxis::has_queued_table`]). The interpretation (periodic,
    /// master and slave absolute) can only change while idle.
    ///
    /// # Errors
    /// As [`CamAxis::new`] for a table that does not fit;
    /// [`EngineError::Busy`] for a different interpretation while engaged;
    /// [`EngineError::NoSeam`] for a queued table on a non-periodic cam.
    pub fn select_table(&mut self, curve: C, select: CamTableSelect) -> Result<(), EngineError> {
        if self.axis.state().is_active() {
            if !select.reads_like(&self.select) {
                return Err(EngineError::Busy);
            }
            return match select.execution_mode {
                ExecutionMode::Immediate => {
                    crate::coupling::Geometry::new(&curve, self.axis.config())?;
                    self.next_table = Some(curve);
                    Ok(())
                }
                ExecutionMode::Queued => self
                    .axis
                    .switch_curve(curve, SwitchAt::NextSeam { blend: None }),
            };
        }
        self.axis.queue_curve(curve)?;
        self.select = select;
        Ok(())
    }

    /// True while a table selected with [`ExecutionMode::Queued`] (or a
    /// switch from a cam-in) waits to take over.
    pub fn has_queued_table(&self) -> bool {
        self.axis.has_queued_curve()
    }

    /// The table a switch replaced, for the caller to take back.
    pub fn take_retired_table(&mut self) -> Option<C> {
        self.axis.take_retired_curve()
    }

    /// `MC_CamIn`. Idle: engage as `ActivationMode` says. Engaged: switch
    /// to a table selected with [`McCamAxis::select_table`] (buffered: at
    /// the next seam; aborting: at once or at the activation position,
    /// blended over [`CamIn::blend`]), else ramp changed offsets and
    /// scalings in over [`CamIn::blend`] (one change at a time).
    ///
    /// # Errors
    /// Engaged: [`EngineError::Busy`] while an earlier change still runs,
    /// or when offsets and a scaling change together; as
    /// [`CamAxis::switch_curve`].
    pub fn cam_in(&mut self, params: &CamIn) -> Result<(), EngineError> {
        if !matches!(
            params.buffer_mode,
            BufferMode::Aborting | BufferMode::Buffered
        ) {
            return Err(EngineError::UnsupportedBufferMode);
        }
        if self.axis.state().is_engaged() {
            self.cam_in_engaged(params)?;
            self.command = self.command.wrapping_add(1);
            return Ok(());
        }
        let master_align = if self.select.master_absolute {
            MasterAlign::Offset(params.master_offset)
        } else {
            MasterAlign::StartAt(
                self.axis
                    .curve()
                    .master_first()
                    .saturating_add(params.master_offset),
            )
        };
        let start = self.axis.commanded().saturating_add(params.slave_offset);
        let (relative, slave_align) = match params.start_mode {
            // The table value at engage lands where the slave stands.
            CamInStartMode::Bumpless => (true, SlaveAlign::At(start)),
            // The table values are added to where the slave stands.
            CamInStartMode::Relative => (true, SlaveAlign::Offset(start)),
            _ if !self.select.slave_absolute => (true, SlaveAlign::Offset(start)),
            _ => (false, SlaveAlign::Offset(params.slave_offset)),
        };
        // A rotary slave places an absolute table in the turn its start
        // mode picks (TwinCAT's modulo start modes; see modulo.rs).
        let slave_align = match self.modulo {
            Some(axis) if !relative => SlaveAlign::Modulo {
                axis,
                offset: params.slave_offset,
            },
            _ => slave_align,
        };
        let ramp_in = match params.start_mode {
            CamInStartMode::RampIn { distance } => Some(RampIn { distance }),
            CamInStartMode::Absolute | CamInStartMode::Relative | CamInStartMode::Bumpless => None,
        };
        let config = AxisConfig {
            coupling: match (self.select.periodic, self.select.master_absolute) {
                (true, _) if relative => Coupling::Repeat { min_stroke: 1 },
                (true, _) => Coupling::Periodic,
                (false, true) => Coupling::Normal,
                (false, false) => Coupling::OneShot { repeats: 0 },
            },
            start: match params.activation {
                ActivationMode::AtMasterPosition(position) => StartMode::AtMasterPosition {
                    position,
                    after_edge: false,
                },
                ActivationMode::NextCycle if self.select.master_absolute => {
                    match self.next_cycle_start(params) {
                        Some(position) => StartMode::AtMasterPosition {
                            position,
                            after_edge: false,
                        },
                        None => StartMode::Immediate,
                    }
                }
                // A relative master starts the table at its beginning on
                // engage: every start is a cycle start.
                ActivationMode::Immediate | ActivationMode::NextCycle => StartMode::Immediate,
            },
            master_align,
            slave_align,
            master_zoom: params.master_scaling,
            slave_zoom: params.slave_scaling,
            ramp_in,
            ..*self.axis.config()
        };
        let config = match params.sync_at {
            Some(sync) => {
                let (start, ramp) =
                    RampIn::sync_at(sync.position, sync.start_distance, sync.forward);
                AxisConfig {
                    start,
                    ramp_in: Some(ramp),
                    ..config
                }
            }
            None => config,
        };
        self.axis.set_config(config)?;
        self.axis.set_ramp_in_limits(params.ramp_limits);
        self.axis.arm()?;
        self.engaged_with = Some(*params);
        self.command = self.command.wrapping_add(1);
        Ok(())
    }

    /// The first master position after the last one read at which the
    /// table input (master × scaling + offset) reaches a cycle start
    /// (assuming a forward master); `None` when it does not fit.
    fn next_cycle_start(&self, params: &CamIn) -> Option<i64> {
        let curve = self.axis.curve();
        let first = i128::from(curve.master_first());
        let period = i128::from(curve.master_last()) - first;
        let signed = i128::from(params.master_scaling.signed_num());
        let num = signed.abs();
        let den = i128::from(params.master_scaling.den());
        if period <= 0 || num == 0 {
            return None;
        }
        let now = i128::from(self.axis.status().master);
        // Table input × den at the master now, relative to a cycle start.
        let t = now * signed + i128::from(params.master_offset) * den - first * den;
        let cycle = period * den;
        // A negative scaling walks the table backwards: the next cycle
        // starts where the table input comes down to a cycle boundary.
        let to_next = if signed < 0 {
            match t.rem_euclid(cycle) {
                0 => cycle,
                r => r,
            }
        } else {
            cycle - t.rem_euclid(cycle)
        };
        // Master travel for that table travel, rounded up to a whole count.
        let travel = (to_next + num - 1).div_euclid(num);
        i64::try_from(now + travel).ok()
    }

    /// The number of commands accepted so far (see [`crate::plcopen_blocks`]).
    pub fn command(&self) -> u64 {
        self.command
    }

    fn cam_in_engaged(&mut self, params: &CamIn) -> Result<(), EngineError> {
        if let Some(curve) = self.next_table.take() {
            let at = match (params.buffer_mode, params.activation) {
                (BufferMode::Buffered, _) | (_, ActivationMode::NextCycle) => SwitchAt::NextSeam {
                    blend: Some(params.blend),
                },
                (BufferMode::Aborting, ActivationMode::AtMasterPosition(position)) => {
                    SwitchAt::MasterPosition {
                        position,
                        blend: Some(params.blend),
                    }
                }
                (_, ActivationMode::Immediate) => SwitchAt::Now {
                    blend: Some(params.blend),
                },
                // Refused in `cam_in`; read as aborting should one get here.
                (_, ActivationMode::AtMasterPosition(position)) => SwitchAt::MasterPosition {
                    position,
                    blend: Some(params.blend),
                },
            };
            return self.axis.switch_curve(curve, at);
        }
        let was = self.engaged_with.unwrap_or_default();
        let offsets = OffsetChange {
            master: params.master_offset.saturating_sub(was.master_offset),
            slave: params.slave_offset.saturating_sub(was.slave_offset),
            distance: params.blend,
        };
        let master_scaling = params.master_scaling != was.master_scaling;
        let slave_scaling = params.slave_scaling != was.slave_scaling;
        let offsets_change = offsets.master != 0 || offsets.slave != 0;
        match (offsets_change, master_scaling, slave_scaling) {
            (false, false, false) => Ok(()),
            (true, false, false) => self.axis.change_offsets(offsets),
            (false, true, false) => self
                .axis
                .change_master_scaling(params.master_scaling, Some(params.blend)),
            (false, false, true) => self
                .axis
                .change_slave_scaling(params.slave_scaling, params.blend),
            _ => Err(EngineError::Busy),
        }?;
        self.engaged_with = Some(*params);
        Ok(())
    }

    /// `MC_CamOut`: leaves the cam as `how` says. A pending (not yet
    /// engaged) cam-in is cancelled whatever `how` says.
    pub fn cam_out(&mut self, how: CamOut) {
        match how {
            CamOut::AtVelocity if self.axis.state().is_engaged() => {
                // Engaged, so this cannot fail; a refusal would only mean
                // nothing was engaged, which a plain stop covers.
                if self.axis.cam_out_at_velocity().is_err() {
                    self.axis.stop(StopKind::Immediate);
                }
            }
            CamOut::AtVelocity | CamOut::Hold => self.axis.stop(StopKind::Immediate),
            CamOut::EndOfCycle => self.axis.stop(StopKind::EndOfCycle),
        }
        self.command = self.command.wrapping_add(1);
    }

    /// `MC_CamOut` with [`CamOut::EndOfCycle`].
    pub fn cam_out_at_end_of_cycle(&mut self) {
        self.cam_out(CamOut::EndOfCycle);
    }

    /// Stops at once (the slave holds where it is): ends a cam, a pending
    /// cam-in or the velocity motion after a cam-out.
    pub fn stop(&mut self) {
        self.axis.stop(StopKind::Immediate);
        self.command = self.command.wrapping_add(1);
    }

    /// Brings the slave to rest at `deceleration` pulses/s² (PLCopen
    /// `MC_Halt`/`MC_Stop` with a deceleration), from a running cam or the
    /// velocity motion after a cam-out; see [`CamAxis::stop_decelerating`].
    ///
    /// # Errors
    /// [`EngineError::NotRunning`] unless the cam is engaged or the slave
    /// moves at velocity.
    pub fn halt(&mut self, deceleration: NonZeroU64) -> Result<(), EngineError> {
        self.axis.stop_decelerating(deceleration)?;
        self.command = self.command.wrapping_add(1);
        Ok(())
    }

    /// Declares the slave's current position (while not engaged).
    ///
    /// # Errors
    /// [`EngineError::Busy`] while a cam is engaged.
    pub fn set_slave_position(&mut self, position: i64) -> Result<(), EngineError> {
        self.axis.set_slave_position(position)
    }

    /// One control cycle with the master at `master`, `dt_us` after the last.
    pub fn tick(&mut self, master: i64, dt_us: u32) -> CamStatus {
        self.tick_input(&TickInput::at(master, dt_us))
    }

    /// One control cycle with every input of a tick (a master with its
    /// fraction, the output enable, ...).
    pub fn tick_input(&mut self, input: &TickInput) -> CamStatus {
        let output = self.axis.tick(input);
        // A non-periodic table on an absolute master holds its end value.
        let config = self.axis.config();
        let past_end = config.coupling == Coupling::Normal
            && output.state.is_engaged()
            && if config.master_zoom.is_negative() {
                // A negative master scaling runs the profile backwards.
                output.master_in_cycle <= self.axis.curve().master_first()
            } else {
                output.master_in_cycle >= self.axis.curve().master_last()
            };
        CamStatus {
            in_sync: output.following && output.backlog == 0,
            end_of_profile: output.events.cycle_completed || output.events.finished || past_end,
            busy: output.busy,
            active: output.state.is_engaged(),
            error: output.fault,
            output,
        }
    }

    /// The underlying engine axis.
    pub fn axis(&self) -> &CamAxis<C> {
        &self.axis
    }
}
