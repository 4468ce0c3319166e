//! The PLCopen face of a slave axis with several couplings: the cam blocks
//! of [`crate::plcopen`] (`MC_CamTableSelect`, `MC_CamIn`, `MC_CamOut`)
//! plus `MC_GearIn`, `MC_GearInPos`, `MC_GearOut`,
//! `MC_PhasingAbsolute`/`MC_PhasingRelative`, `MC_MoveSuperimposed`,
//! `MC_HaltSuperimposed` and `MC_TouchProbe` latches for registration, all
//! on one slave ([`SlaveAxis`] around [`McCamAxis`]).
//!
//! Where this reads PLCopen its own way (see docs/engine.md, "Couplings
//! beyond the documents"):
//! - the cam, the gear and the superimposed move are *summed* (as Siemens'
//!   superimposed synchronous operation does); a `MC_GearIn` does not end
//!   the cam, nor the cam the gear. Each keeps its own status;
//! - `MC_Phasing` shifts the master the slave sees, for the cam and the
//!   gear alike, its limits in master counts (TwinCAT's reading for
//!   camming; for gearing TwinCAT turns it into a superimposed move);
//! - a gear command takes effect at the next tick, on its master.
//!
//! ```
//! use core::num::NonZeroU64;
//! use ecam_core::PointTable;
//! use ecam_engine::plcopen::{CamIn, CamTableSelect};
//! use ecam_engine::plcopen_slave::McSlaveAxis;
//! use ecam_engine::{GearIn, GearRamp, MoveLimits, Phasing, PhasingMode, SlaveConfig, Zoom};
//!
//! let table = PointTable::from_pairs(&[(0, 0), (1000, 1000)])?;
//! let mut axis = McSlaveAxis::new(table, SlaveConfig::default())?;
//! axis.cam_table_select(CamTableSelect { periodic: true, slave_absolute: false, ..CamTableSelect::default() })?;
//! axis.cam_in(&CamIn::default())?;
//! axis.phasing(&Phasing {
//!     shift: 250,
//!     mode: PhasingMode::Absolute,
//!     limits: MoveLimits::new(5_000.0, 50_000.0, 50_000.0)?,
//! })?;
//! let mut status = axis.tick(0, 1000);
//! for ms in 1..=1000 {
//!     status = axis.tick(ms * 10, 1000);
//! }
//! // The cam sees the master 250 counts further on: 10 000 + 250.
//! assert_eq!(status.axis.slave, 10_250);
//! assert!(status.axis.phasing.done && status.in_sync);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use core::num::NonZeroU64;

use ecam_core::CamCurve;

use crate::plcopen::{CamIn, CamOut, CamStatus, CamTableSelect, McCamAxis};
use crate::{
    CamAxis, CamPart, CouplingError, EngineError, GearIn, GearInPos, GearOut, MoveSuperimposed,
    Phasing, SlaveAxis, SlaveConfig, SlaveInput, SlaveOutput, TickInput, TickOutput,
};

impl<C: CamCurve> CamPart for McCamAxis<C> {
    type Curve = C;
    type Status = CamStatus;

    fn tick_cam(&mut self, input: &TickInput) -> CamStatus {
        self.tick_input(input)
    }

    fn output(status: &CamStatus) -> &TickOutput {
        &status.output
    }

    fn engine(&self) -> &CamAxis<C> {
        self.axis()
    }

    fn set_position(&mut self, position: i64) -> Result<(), EngineError> {
        self.set_slave_position(position)
    }
}

/// What a slave axis reports after a cycle, PLCopen-style.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlaveStatus {
    /// The cam blocks' outputs; its `in_sync` counts the axis' own backlog.
    pub cam: CamStatus,
    /// The axis: the sum, and each coupling's status.
    pub axis: SlaveOutput,
    /// `MC_CamIn.InSync`: the cam follows and no pulses are owed.
    pub in_sync: bool,
}

/// One slave axis driven PLCopen-style, with a cam, a gear, phasing, a
/// superimposed move and registration.
#[derive(Clone, Debug)]
pub struct McSlaveAxis<C: CamCurve> {
    axis: SlaveAxis<McCamAxis<C>>,
}

impl<C: CamCurve> McSlaveAxis<C> {
    /// A slave axis with `curve` as its selected table (periodic,
    /// absolute), configured by `config` (a modulo slave also places
    /// absolute cams in the turn its start mode picks).
    ///
    /// # Errors
    /// As [`McCamAxis::new`] and [`SlaveAxis::new`].
    pub fn new(curve: C, config: SlaveConfig) -> Result<Self, CouplingError> {
        let mut cam = McCamAxis::new(curve)?;
        cam.set_modulo(config.modulo);
        Ok(Self {
            axis: SlaveAxis::new(cam, config)?,
        })
    }

    /// `MC_CamTableSelect` (how the table is read at the next `MC_CamIn`).
    ///
    /// # Errors
    /// As [`McCamAxis::select`].
    pub fn cam_table_select(&mut self, select: CamTableSelect) -> Result<(), CouplingError> {
        Ok(self.axis.cam_mut().select(select)?)
    }

    /// `MC_CamTableSelect` with a table.
    ///
    /// # Errors
    /// As [`McCamAxis::select_table`].
    pub fn select_table(&mut self, curve: C, select: CamTableSelect) -> Result<(), CouplingError> {
        Ok(self.axis.cam_mut().select_table(curve, select)?)
    }

    /// `MC_CamIn`.
    ///
    /// # Errors
    /// As [`McCamAxis::cam_in`].
    pub fn cam_in(&mut self, params: &CamIn) -> Result<(), CouplingError> {
        Ok(self.axis.cam_mut().cam_in(params)?)
    }

    /// `MC_CamOut`.
    pub fn cam_out(&mut self, how: CamOut) {
        self.axis.cam_mut().cam_out(how);
    }

    /// `MC_GearIn`.
    ///
    /// # Errors
    /// As [`SlaveAxis::gear_in`].
    pub fn gear_in(&mut self, command: &GearIn) -> Result<(), CouplingError> {
        self.axis.gear_in(command)
    }

    /// `MC_GearInPos`.
    ///
    /// # Errors
    /// As [`SlaveAxis::gear_in_pos`].
    pub fn gear_in_pos(&mut self, command: &GearInPos) -> Result<(), CouplingError> {
        self.axis.gear_in_pos(command)
    }

    /// `MC_GearOut`.
    ///
    /// # Errors
    /// As [`SlaveAxis::gear_out`].
    pub fn gear_out(&mut self, command: &GearOut) -> Result<(), CouplingError> {
        self.axis.gear_out(command)
    }

    /// `MC_PhasingAbsolute` / `MC_PhasingRelative`.
    ///
    /// # Errors
    /// As [`SlaveAxis::phasing`].
    pub fn phasing(&mut self, command: &Phasing) -> Result<(), CouplingError> {
        self.axis.phasing(command)
    }

    /// `MC_MoveSuperimposed`.
    ///
    /// # Errors
    /// As [`SlaveAxis::move_superimposed`].
    pub fn move_superimposed(&mut self, command: &MoveSuperimposed) -> Result<(), CouplingError> {
        self.axis.move_superimposed(command)
    }

    /// `MC_HaltSuperimposed`.
    ///
    /// # Errors
    /// As [`SlaveAxis::halt_superimposed`].
    pub fn halt_superimposed(&mut self, deceleration: f64) -> Result<(), CouplingError> {
        self.axis.halt_superimposed(deceleration)
    }

    /// `MC_Stop` without a deceleration: the cam, the gear, the phase
    /// shift and the superimposed move hold where they are.
    pub fn stop(&mut self) {
        self.axis.cam_mut().stop();
        self.axis.stop_couplings();
    }

    /// `MC_Halt` of the cam at `deceleration` (see [`McCamAxis::halt`]).
    ///
    /// # Errors
    /// As [`McCamAxis::halt`].
    pub fn halt_cam(&mut self, deceleration: NonZeroU64) -> Result<(), CouplingError> {
        Ok(self.axis.cam_mut().halt(deceleration)?)
    }

    /// Declares the slave's position (nothing engaged or moving).
    ///
    /// # Errors
    /// As [`SlaveAxis::set_slave_position`].
    pub fn set_slave_position(&mut self, position: i64) -> Result<(), CouplingError> {
        self.axis.set_slave_position(position)
    }

    /// One cycle with the master at `master`, `dt_us` after the last.
    pub fn tick(&mut self, master: i64, dt_us: u32) -> SlaveStatus {
        self.tick_input(&SlaveInput {
            tick: TickInput::at(master, dt_us),
            latch: None,
        })
    }

    /// One cycle with every input (a touch-probe latch included).
    pub fn tick_input(&mut self, input: &SlaveInput) -> SlaveStatus {
        let axis = *self.axis.tick(input);
        let mut cam = self.axis.cam_status().copied().unwrap_or(CamStatus {
            in_sync: false,
            end_of_profile: false,
            busy: false,
            active: false,
            error: None,
            output: axis.cam,
        });
        // The cam's own pulse fields are not the axis': InSync counts the
        // axis' backlog.
        cam.in_sync = cam.output.following && axis.backlog == 0;
        SlaveStatus {
            cam,
            axis,
            in_sync: cam.in_sync,
        }
    }

    /// The slave axis (its cam, couplings and counts of commands).
    pub fn axis(&self) -> &SlaveAxis<McCamAxis<C>> {
        &self.axis
    }
}
