//! PLCopen function-block behaviour for the couplings of a slave axis
//! ([`crate::plcopen_slave::McSlaveAxis`]): `Execute` acts on its rising
//! edge; `Done`, `Error`/`ErrorID` and `CommandAborted` latch until the
//! next rising edge (PLCopen Part 1). `MC_DigitalCamSwitch` is an
//! `Enable` block.
//!
//! Call each block once per cycle after
//! [`crate::plcopen_slave::McSlaveAxis::tick`], with that cycle's status.

use ecam_core::CamCurve;

use crate::plcopen_slave::{McSlaveAxis, SlaveStatus};
use crate::{
    CamSwitch, CouplingError, DigitalCamSwitch, GearIn, GearInPos, GearState, MoveSuperimposed,
    Phasing,
};

/// The latching every execute block shares: which command is this
/// block's, whether another took over, the error.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Latch {
    execute: bool,
    command: Option<u64>,
    aborted: bool,
    error: Option<CouplingError>,
}

impl Latch {
    /// Takes `execute`; `true` on its rising edge (the outputs cleared).
    fn edge(&mut self, execute: bool) -> bool {
        let rising = execute && !self.execute;
        self.execute = execute;
        if rising {
            self.aborted = false;
            self.error = None;
            self.command = None;
        }
        rising
    }

    /// What issuing the command gave: the coupling's command count after
    /// it, or the refusal.
    fn issued(&mut self, result: Result<u64, CouplingError>) {
        match result {
            Ok(id) => self.command = Some(id),
            Err(e) => self.error = Some(e),
        }
    }

    /// Follows the coupling's command count: another command took over.
    fn follow(&mut self, count: u64) {
        if let Some(id) = self.command
            && count != id
        {
            self.aborted = true;
            self.command = None;
        }
    }

    fn mine(&self) -> bool {
        self.command.is_some()
    }
}

/// `MC_GearIn` outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GearInOutputs {
    /// `InGear`: the gear runs at the ratio.
    pub in_gear: bool,
    /// `Busy`: the command is not finished.
    pub busy: bool,
    /// `Active`: the command has control of the gear.
    pub active: bool,
    /// `CommandAborted`: another gear command took over.
    pub command_aborted: bool,
    /// `Error`.
    pub error: bool,
    /// `ErrorID`.
    pub error_id: Option<CouplingError>,
}

/// `MC_GearIn` as a function block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GearInBlock {
    latch: Latch,
}

impl GearInBlock {
    /// One call with this cycle's `status`.
    pub fn call<C: CamCurve>(
        &mut self,
        axis: &mut McSlaveAxis<C>,
        execute: bool,
        command: &GearIn,
        status: &SlaveStatus,
    ) -> GearInOutputs {
        if self.latch.edge(execute) {
            let issued = axis.gear_in(command).map(|()| axis.axis().commands().gear);
            self.latch.issued(issued);
        }
        self.latch.follow(axis.axis().commands().gear);
        gear_outputs(&self.latch, status)
    }
}

fn gear_outputs(latch: &Latch, status: &SlaveStatus) -> GearInOutputs {
    let mine = latch.mine();
    let state = status.axis.gear.state;
    GearInOutputs {
        in_gear: mine && state == GearState::InGear,
        busy: mine,
        active: mine && state != GearState::Waiting,
        command_aborted: latch.aborted,
        error: latch.error.is_some(),
        error_id: latch.error,
    }
}

/// `MC_GearInPos` outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GearInPosOutputs {
    /// `StartSync`: the approach to the sync point runs.
    pub start_sync: bool,
    /// `InSync`: in gear through the sync point.
    pub in_sync: bool,
    /// `Busy`, `Active`, `CommandAborted`, `Error`, `ErrorID` as for `MC_GearIn`.
    pub common: GearInOutputs,
}

/// `MC_GearInPos` as a function block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GearInPosBlock {
    latch: Latch,
}

impl GearInPosBlock {
    /// One call with this cycle's `status`.
    pub fn call<C: CamCurve>(
        &mut self,
        axis: &mut McSlaveAxis<C>,
        execute: bool,
        command: &GearInPos,
        status: &SlaveStatus,
    ) -> GearInPosOutputs {
        if self.latch.edge(execute) {
            let issued = axis
                .gear_in_pos(command)
                .map(|()| axis.axis().commands().gear);
            self.latch.issued(issued);
        }
        self.latch.follow(axis.axis().commands().gear);
        let common = gear_outputs(&self.latch, status);
        GearInPosOutputs {
            start_sync: self.latch.mine() && status.axis.gear.state == GearState::Syncing,
            in_sync: common.in_gear,
            common,
        }
    }
}

/// `MC_Phasing` outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhasingOutputs {
    /// `Done`: the shift is reached.
    pub done: bool,
    /// `Busy`.
    pub busy: bool,
    /// `Active`.
    pub active: bool,
    /// `CommandAborted`.
    pub command_aborted: bool,
    /// `Error`.
    pub error: bool,
    /// `ErrorID`.
    pub error_id: Option<CouplingError>,
    /// `AbsolutePhaseShift` (master counts).
    pub absolute_phase_shift: f64,
    /// `CoveredPhaseShift` (master counts).
    pub covered_phase_shift: f64,
}

/// `MC_PhasingAbsolute` / `MC_PhasingRelative` as a function block (the
/// mode is in [`Phasing::mode`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PhasingBlock {
    latch: Latch,
    done: bool,
}

impl PhasingBlock {
    /// One call with this cycle's `status`.
    pub fn call<C: CamCurve>(
        &mut self,
        axis: &mut McSlaveAxis<C>,
        execute: bool,
        command: &Phasing,
        status: &SlaveStatus,
    ) -> PhasingOutputs {
        if execute && !self.latch.execute {
            self.done = false;
        }
        if self.latch.edge(execute) {
            let issued = axis
                .phasing(command)
                .map(|()| axis.axis().commands().phasing);
            self.latch.issued(issued);
        }
        self.latch.follow(axis.axis().commands().phasing);
        let p = status.axis.phasing;
        if self.latch.mine() && p.done && !p.active {
            // Done latches; the command is no longer in charge.
            self.done = true;
            self.latch.command = None;
        }
        let mine = self.latch.mine();
        PhasingOutputs {
            done: self.done,
            busy: mine,
            active: mine && p.active,
            command_aborted: self.latch.aborted,
            error: self.latch.error.is_some(),
            error_id: self.latch.error,
            absolute_phase_shift: p.shift,
            covered_phase_shift: p.covered,
        }
    }
}

/// `MC_MoveSuperimposed` outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MoveSuperimposedOutputs {
    /// `Done`.
    pub done: bool,
    /// `Busy`.
    pub busy: bool,
    /// `Active`.
    pub active: bool,
    /// `CommandAborted`.
    pub command_aborted: bool,
    /// `Error`.
    pub error: bool,
    /// `ErrorID`.
    pub error_id: Option<CouplingError>,
    /// `CoveredDistance` (pulses).
    pub covered_distance: i64,
}

/// `MC_MoveSuperimposed` as a function block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MoveSuperimposedBlock {
    latch: Latch,
    done: bool,
}

impl MoveSuperimposedBlock {
    /// One call with this cycle's `status`.
    pub fn call<C: CamCurve>(
        &mut self,
        axis: &mut McSlaveAxis<C>,
        execute: bool,
        command: &MoveSuperimposed,
        status: &SlaveStatus,
    ) -> MoveSuperimposedOutputs {
        if execute && !self.latch.execute {
            self.done = false;
        }
        if self.latch.edge(execute) {
            let issued = axis
                .move_superimposed(command)
                .map(|()| axis.axis().commands().superimposed);
            self.latch.issued(issued);
        }
        self.latch.follow(axis.axis().commands().superimposed);
        let s = status.axis.superimposed;
        if self.latch.mine() && s.done && !s.active {
            self.done = true;
            self.latch.command = None;
        }
        let mine = self.latch.mine();
        MoveSuperimposedOutputs {
            done: self.done,
            busy: mine,
            active: mine && s.active,
            command_aborted: self.latch.aborted,
            error: self.latch.error.is_some(),
            error_id: self.latch.error,
            covered_distance: s.covered,
        }
    }
}

/// `MC_DigitalCamSwitch` outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DigitalCamSwitchOutputs {
    /// `InOperation`: enabled and the switches accepted.
    pub in_operation: bool,
    /// `Busy`: enabled.
    pub busy: bool,
    /// `Error`.
    pub error: bool,
    /// `ErrorID`.
    pub error_id: Option<CouplingError>,
    /// `Outputs`: bit `i` for track `i`.
    pub outputs: u32,
}

/// `MC_DigitalCamSwitch` as a function block: `Enable` level, the cams
/// (`Switches`) handed in every call, the position of the axis it watches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DigitalCamSwitchBlock {
    group: DigitalCamSwitch,
}

impl DigitalCamSwitchBlock {
    /// A block over a cam-switch group (its modulo and track options).
    pub const fn new(group: DigitalCamSwitch) -> Self {
        Self { group }
    }

    /// One call: while `enable`, the tracks at `position` (`dt_us` after the
    /// last call), masked by `enable_mask`; disabled, all off.
    pub fn call(
        &mut self,
        enable: bool,
        switches: &[CamSwitch],
        position: i64,
        dt_us: u32,
        enable_mask: u32,
    ) -> DigitalCamSwitchOutputs {
        if !enable {
            return DigitalCamSwitchOutputs::default();
        }
        if let Err(e) = DigitalCamSwitch::check(switches) {
            return DigitalCamSwitchOutputs {
                busy: true,
                error: true,
                error_id: Some(e),
                ..DigitalCamSwitchOutputs::default()
            };
        }
        DigitalCamSwitchOutputs {
            in_operation: true,
            busy: true,
            error: false,
            error_id: None,
            outputs: self.group.tick(switches, position, dt_us, enable_mask),
        }
    }
}
