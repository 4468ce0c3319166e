//! Running a parsed script against a [`MotionController`] in simulated time.

use core::fmt;

use super::linear_move::LinearMove;
use super::trace::{Trace, TraceError};
use super::{Command, DEFAULT_AXES, Problem, Report, Script, ScriptError};
use crate::{ECamData, McError, MotionController, SingleTurn};

/// Why a command was refused; it changed nothing.
#[derive(Debug)]
enum Refusal {
    /// The controller refused.
    Controller(McError),
    /// A position was set or a move started on an E-CAM's slave.
    Follows { axis: usize },
    /// An E-CAM was started on an axis a `MoveTo` is driving.
    Moving { axis: usize },
    /// `StopECAM` on an axis no E-CAM drives.
    NoECam { axis: usize },
    /// The trace file could not be written.
    Trace(TraceError),
}

impl fmt::Display for Refusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Controller(e) => write!(f, "{e}"),
            Self::Follows { axis } => write!(
                f,
                "axis {axis} follows an E-CAM: `StopECAM {axis}` before setting or moving it"
            ),
            Self::Moving { axis } => write!(
                f,
                "axis {axis} is moving (MoveTo): let the move end, or `SetCommandPosition` it, before it follows an E-CAM"
            ),
            Self::NoECam { axis } => write!(f, "no E-CAM drives axis {axis}"),
            Self::Trace(e) => write!(f, "{e}"),
        }
    }
}

impl From<McError> for Refusal {
    fn from(e: McError) -> Self {
        Self::Controller(e)
    }
}

impl From<TraceError> for Refusal {
    fn from(e: TraceError) -> Self {
        Self::Trace(e)
    }
}

/// What the script last commanded an axis, in unwrapped counts, and the
/// move under way.
#[derive(Clone, Copy, Debug, Default)]
struct Drive {
    /// The last position `SetCommandPosition` or `MoveTo` gave the axis,
    /// before a single-turn axis wraps it.
    commanded: i64,
    moving: Option<LinearMove>,
}

impl Drive {
    fn at(position: i64) -> Self {
        Self {
            commanded: position,
            moving: None,
        }
    }

    /// Where a new move starts: the position last commanded, whole turns
    /// included, if the axis is still there (`now` is its wrap); else (an
    /// E-CAM moved it, or nothing commanded it yet) its position `now`.
    fn unwrapped(&self, now: i64, turn: Option<SingleTurn>) -> i64 {
        let wrapped = turn.map_or(self.commanded, |t| t.wrap(self.commanded));
        if wrapped == now { self.commanded } else { now }
    }
}

/// Executes scripts: a [`MotionController`], the `MoveTo`s under way, the
/// open trace and the cycle count.
///
/// Each cycle of `Tick N`: every `MoveTo` advances its axis, then every
/// running E-CAM reads its master and commands its slave
/// ([`MotionController::tick`]), then the trace gets a row.
#[derive(Debug)]
pub struct ScriptRunner {
    controller: MotionController,
    drives: Vec<Drive>,
    trace: Option<Trace>,
    cycles: u64,
}

impl Default for ScriptRunner {
    fn default() -> Self {
        Self::new(DEFAULT_AXES)
    }
}

impl ScriptRunner {
    /// A runner on a controller with `axis_count` axes (a script's `Axes N`
    /// replaces it with N fresh axes).
    pub fn new(axis_count: usize) -> Self {
        Self {
            controller: MotionController::new(axis_count),
            drives: vec![Drive::default(); axis_count],
            trace: None,
            cycles: 0,
        }
    }

    /// The controller, as the commands so far left it.
    pub fn controller(&self) -> &MotionController {
        &self.controller
    }

    /// Control cycles run so far.
    pub fn cycles(&self) -> u64 {
        self.cycles
    }

    /// Runs `script`, handing each report to `on_report` as it is made.
    /// The trace, if one is open, is closed at the end.
    ///
    /// # Errors
    /// The first refused command, as `FILE:LINE: message`: it changed
    /// nothing and the run ends there.
    pub fn run(
        &mut self,
        script: &Script,
        mut on_report: impl FnMut(&Report),
    ) -> Result<(), ScriptError> {
        let mut result = Ok(());
        for line in script.lines() {
            match self.execute(&line.command) {
                Ok(Some(report)) => on_report(&report),
                Ok(None) => {}
                Err(refusal) => {
                    result = Err(ScriptError::at(
                        script.path(),
                        line.number,
                        Problem::Refused {
                            command: line.command.name(),
                            reason: refusal.to_string(),
                        },
                    ));
                    break;
                }
            }
        }
        let closed = self.close_trace().map_err(|e| ScriptError {
            path: script.path().to_path_buf(),
            line: None,
            problem: Problem::Trace(e.to_string()),
        });
        result.and(closed)
    }

    fn close_trace(&mut self) -> Result<(), TraceError> {
        self.trace.take().map_or(Ok(()), Trace::finish)
    }

    /// Refuses to set or move an E-CAM's slave.
    fn free(&self, axis: usize) -> Result<(), Refusal> {
        self.controller.position(axis)?;
        if self.controller.ecam_running(axis) {
            return Err(Refusal::Follows { axis });
        }
        Ok(())
    }

    fn drive(&mut self, axis: usize) -> Result<&mut Drive, Refusal> {
        let count = self.drives.len();
        self.drives
            .get_mut(axis)
            .ok_or(Refusal::Controller(McError::NoSuchAxis { axis, count }))
    }

    fn execute(&mut self, command: &Command) -> Result<Option<Report>, Refusal> {
        let mc = &mut self.controller;
        match command {
            Command::Axes(n) => {
                self.close_trace()?;
                *self = Self::new(*n);
            }
            Command::SetSingleTurn { axis, turn } => mc.set_single_turn(*axis, *turn)?,
            Command::SetUserUnit { axis, unit } => mc.set_user_unit(*axis, *unit)?,
            Command::SetMaxMasterStep { axis, step } => mc.set_max_master_step(*axis, *step)?,
            Command::SetCommandPosition { axis, position } => {
                self.free(*axis)?;
                self.controller.set_position(*axis, *position)?;
                *self.drive(*axis)? = Drive::at(*position);
            }
            Command::MoveTo {
                axis,
                position,
                cycles,
            } => {
                self.free(*axis)?;
                if *cycles == 0 {
                    self.controller.set_position(*axis, *position)?;
                    *self.drive(*axis)? = Drive::at(*position);
                } else {
                    let now = self.controller.position(*axis)?;
                    let turn = self.controller.single_turn(*axis)?;
                    let drive = self.drive(*axis)?;
                    let from = drive.unwrapped(now, turn);
                    *drive = Drive {
                        commanded: from,
                        moving: Some(LinearMove::new(from, *position, *cycles)),
                    };
                }
            }
            Command::ECamTable { .. } => {}
            Command::StartECam {
                master,
                slave,
                cam_type,
                table,
                ..
            } => {
                if self.drive(*slave)?.moving.is_some() {
                    return Err(Refusal::Moving { axis: *slave });
                }
                self.controller.start_ecam(ECamData {
                    master_axis: *master,
                    slave_axis: *slave,
                    cam_type: *cam_type,
                    table: table.clone(),
                })?;
            }
            Command::StopECam { slave } => {
                mc.position(*slave)?;
                if !mc.stop_ecam(*slave) {
                    return Err(Refusal::NoECam { axis: *slave });
                }
            }
            Command::Tick(n) => {
                for _ in 0..*n {
                    self.cycle()?;
                }
            }
            Command::GetCommandPosition { axis } => {
                return Ok(Some(Report::Value {
                    cmd: "GetCommandPosition",
                    axis: *axis,
                    value: mc.position(*axis)?,
                }));
            }
            Command::GetSingleTurn { axis } => {
                let counts = mc.single_turn(*axis)?.map_or(0, |t| t.counts().get());
                return Ok(Some(Report::Value {
                    cmd: "GetSingleTurn",
                    axis: *axis,
                    value: i64::try_from(counts).unwrap_or(i64::MAX),
                }));
            }
            Command::GetECamStatus { slave } => {
                return Ok(Some(Report::ECamStatus {
                    axis: *slave,
                    running: mc.ecam_running(*slave),
                    fault: mc.fault(*slave)?,
                }));
            }
            Command::Trace { path, axes } => {
                let axes = if axes.is_empty() {
                    (0..mc.axis_count()).collect()
                } else {
                    axes.clone()
                };
                for &axis in &axes {
                    mc.position(axis)?;
                }
                // Flushed, not closed: if the new file cannot be made, the
                // old trace goes on (a refused command changes nothing).
                if let Some(open) = &mut self.trace {
                    open.flush()?;
                }
                let trace = Trace::create(path, axes, &self.controller, self.cycles)?;
                if let Some(old) = self.trace.replace(trace) {
                    old.finish()?;
                }
            }
            Command::TraceOff => self.close_trace()?,
        }
        Ok(None)
    }

    /// One control cycle: moves, then cams, then the trace row.
    fn cycle(&mut self) -> Result<(), Refusal> {
        for (axis, drive) in self.drives.iter_mut().enumerate() {
            if let Some(m) = &mut drive.moving {
                let (position, arrived) = m.step();
                // StartECAM refuses a moving slave, so this axis is free.
                self.controller.set_position(axis, position)?;
                drive.commanded = position;
                if arrived {
                    drive.moving = None;
                }
            }
        }
        self.controller.tick();
        self.cycles = self.cycles.saturating_add(1);
        if let Some(trace) = &mut self.trace {
            trace.row(&self.controller, self.cycles)?;
        }
        Ok(())
    }
}
