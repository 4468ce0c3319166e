//! The commands of an `ecam mc run` script, as parsed.

use core::num::NonZeroU64;
use std::path::PathBuf;

use ecam_core::PointTable;

use crate::{CamType, SingleTurn, UserUnit};

/// One parsed script command. Axis numbers are checked against the
/// script's axis count when parsed; tables are resolved (read, validated)
/// when parsed, so a running script never meets a bad table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Command {
    /// `Axes N`: the controller has N axes, numbered from 0 (the first
    /// command of a script, if present; without it there are 2).
    Axes(usize),
    /// `SetSingleTurn AXIS COUNTS` or `SetSingleTurn AXIS Off`.
    SetSingleTurn {
        /// The axis.
        axis: usize,
        /// Its single-turn encoder range, or `None` for off.
        turn: Option<SingleTurn>,
    },
    /// `SetUserUnit AXIS PULSES`.
    SetUserUnit {
        /// The axis.
        axis: usize,
        /// Pulses per user unit.
        unit: UserUnit,
    },
    /// `SetMaxMasterStep AXIS COUNTS` or `SetMaxMasterStep AXIS Off`.
    SetMaxMasterStep {
        /// The axis, as a master.
        axis: usize,
        /// The largest step per cycle a cam accepts from it, or `None`.
        step: Option<NonZeroU64>,
    },
    /// `SetCommandPosition AXIS POSITION`: sets the command position at
    /// once (ends a `MoveTo` on that axis).
    SetCommandPosition {
        /// The axis.
        axis: usize,
        /// The new command position.
        position: i64,
    },
    /// `MoveTo AXIS POSITION CYCLES`: a linear move over the next CYCLES
    /// cycles (0: at once).
    MoveTo {
        /// The axis.
        axis: usize,
        /// The target, unwrapped (on a single-turn axis, whole turns count).
        position: i64,
        /// Cycles the move takes.
        cycles: u32,
    },
    /// `ECAMTable NAME M S …` or `ECAMTableFile NAME PATH`: names a table
    /// for later `StartECAM` lines.
    ECamTable {
        /// The name.
        name: String,
        /// The table.
        table: PointTable,
    },
    /// `StartECAM MASTER SLAVE TYPE TABLE`.
    StartECam {
        /// The master axis.
        master: usize,
        /// The slave axis.
        slave: usize,
        /// Normal, Periodic or Repeat.
        cam_type: CamType,
        /// The table's name.
        table_name: String,
        /// The table as it was defined when this line was parsed.
        table: PointTable,
    },
    /// `StopECAM SLAVE`.
    StopECam {
        /// The slave axis of the E-CAM to stop.
        slave: usize,
    },
    /// `Tick N`: runs N control cycles.
    Tick(u64),
    /// `GetCommandPosition AXIS`.
    GetCommandPosition {
        /// The axis.
        axis: usize,
    },
    /// `GetSingleTurn AXIS`.
    GetSingleTurn {
        /// The axis.
        axis: usize,
    },
    /// `GetECAMStatus SLAVE`.
    GetECamStatus {
        /// The slave axis.
        slave: usize,
    },
    /// `Trace PATH [AXIS …]`: writes the command positions of the axes
    /// (all, if none are named) to a CSV file, one row per cycle.
    Trace {
        /// The file, relative to the script's directory.
        path: PathBuf,
        /// The axes, in column order.
        axes: Vec<usize>,
    },
    /// `Trace Off`: closes the trace file.
    TraceOff,
}

impl Command {
    /// The command's name as scripts spell it, e.g. `StartECAM`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Axes(_) => "Axes",
            Self::SetSingleTurn { .. } => "SetSingleTurn",
            Self::SetUserUnit { .. } => "SetUserUnit",
            Self::SetMaxMasterStep { .. } => "SetMaxMasterStep",
            Self::SetCommandPosition { .. } => "SetCommandPosition",
            Self::MoveTo { .. } => "MoveTo",
            Self::ECamTable { .. } => "ECAMTable",
            Self::StartECam { .. } => "StartECAM",
            Self::StopECam { .. } => "StopECAM",
            Self::Tick(_) => "Tick",
            Self::GetCommandPosition { .. } => "GetCommandPosition",
            Self::GetSingleTurn { .. } => "GetSingleTurn",
            Self::GetECamStatus { .. } => "GetECAMStatus",
            Self::Trace { .. } | Self::TraceOff => "Trace",
        }
    }
}
