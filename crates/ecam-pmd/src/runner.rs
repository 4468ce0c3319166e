//! Runs a command script against a [`MotionProcessor`] and collects what it prints.

use crate::script::{Command, Parser};
use crate::{MotionProcessor, PmdError};

/// One line of output: the answer to a `Get…` command, or why a line failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Report {
    /// A value read by a `Get…` (or `ReadBuffer`) command.
    Value {
        /// The command name, e.g. `GetCam`.
        cmd: &'static str,
        /// The axis it was directed to.
        axis: u8,
        /// `GetCam`'s parameter name.
        param: Option<&'static str>,
        /// The value.
        value: i64,
    },
    /// A line that was refused or not understood; it changed nothing.
    Error {
        /// Line number (from 1).
        line: usize,
        /// The command name as written.
        cmd: String,
        /// The axis commands were directed to at that line.
        axis: u8,
        /// Why.
        message: String,
    },
}

impl Report {
    /// The report as one JSON object, keys in the order of the `ecam pmd run`
    /// contract, e.g. `{"cmd":"GetCam","axis":0,"param":"CamOutputOffset","value":-12}`.
    pub fn to_json(&self) -> String {
        let text = |s: &str| serde_json::Value::from(s).to_string();
        match self {
            Self::Value {
                cmd,
                axis,
                param: Some(param),
                value,
            } => {
                format!(
                    r#"{{"cmd":{},"axis":{axis},"param":{},"value":{value}}}"#,
                    text(cmd),
                    text(param)
                )
            }
            Self::Value {
                cmd,
                axis,
                param: None,
                value,
            } => {
                format!(r#"{{"cmd":{},"axis":{axis},"value":{value}}}"#, text(cmd))
            }
            Self::Error {
                line,
                cmd,
                axis,
                message,
            } => format!(
                r#"{{"cmd":{},"axis":{axis},"line":{line},"error":{}}}"#,
                text(cmd),
                text(message)
            ),
        }
    }
}

/// Executes script lines one by one: the processor, the current axis, the
/// defined names.
#[derive(Debug, Default)]
pub struct ScriptRunner {
    processor: MotionProcessor,
    axis: u8,
    parser: Parser,
}

impl ScriptRunner {
    /// A runner on a default (four-axis) processor, commands going to axis 0.
    pub fn new() -> Self {
        Self::default()
    }

    /// A runner on `processor`.
    pub fn with_processor(processor: MotionProcessor) -> Self {
        Self {
            processor,
            axis: 0,
            parser: Parser::new(),
        }
    }

    /// Defines `name` for the script (as `Define NAME VALUE` would).
    pub fn define(&mut self, name: &str, value: i64) {
        self.parser.define(name, value);
    }

    /// The processor.
    pub fn processor(&self) -> &MotionProcessor {
        &self.processor
    }

    /// Runs a whole script; a failing line reports and the script goes on.
    pub fn run_script(&mut self, text: &str) -> Vec<Report> {
        text.lines()
            .enumerate()
            .filter_map(|(i, line)| self.run_line(i.saturating_add(1), line))
            .collect()
    }

    /// Runs one line numbered `line`; gives its report, if it makes one.
    pub fn run_line(&mut self, line: usize, text: &str) -> Option<Report> {
        let command = match self.parser.parse_line(text) {
            Ok(Some(command)) => command,
            Ok(None) => return None,
            Err(e) => {
                return Some(Report::Error {
                    line,
                    cmd: e.cmd().to_owned(),
                    axis: self.axis,
                    message: e.to_string(),
                });
            }
        };
        let name = command_name(&command);
        match self.execute(command) {
            Ok(report) => report,
            Err(e) => Some(Report::Error {
                line,
                cmd: name.to_owned(),
                axis: self.axis,
                message: e.to_string(),
            }),
        }
    }

    fn value(&self, cmd: &'static str, value: i64) -> Option<Report> {
        Some(Report::Value {
            cmd,
            axis: self.axis,
            param: None,
            value,
        })
    }

    fn execute(&mut self, command: Command) -> Result<Option<Report>, PmdError> {
        let p = &mut self.processor;
        let axis = self.axis;
        match command {
            Command::Axis(n) => self.axis = p.check_axis(n)?,
            Command::Define(..) => {}
            Command::SetBufferStart(id, v) => p.set_buffer_start(id, v)?,
            Command::SetBufferLength(id, v) => p.set_buffer_length(id, v)?,
            Command::SetBufferWriteIndex(id, v) => p.set_buffer_write_index(id, v)?,
            Command::WriteBuffer(id, v) => p.write_buffer(id, v)?,
            Command::ReadBuffer(id, i) => {
                let v = p.read_buffer(id, i)?;
                return Ok(self.value("ReadBuffer", v));
            }
            Command::SetProfileMode(m) => p.set_profile_mode(axis, m)?,
            Command::GetProfileMode => {
                let m = p.profile_mode(axis)?.code();
                return Ok(self.value("GetProfileMode", m));
            }
            Command::Update => p.update(axis)?,
            Command::SetStopMode(m) => p.set_stop_mode(axis, m)?,
            Command::SetCam(param, v) => p.set_cam(axis, param, v)?,
            Command::GetCam(param) => {
                let value = p.get_cam(axis, param)?;
                return Ok(Some(Report::Value {
                    cmd: "GetCam",
                    axis,
                    param: Some(param.name()),
                    value,
                }));
            }
            Command::SetBreakpointValue(id, v) => p.set_breakpoint_value(axis, id, v)?,
            Command::SetBreakpoint(id, w) => p.set_breakpoint(axis, id, w)?,
            Command::SetEventAction(e, a) => p.set_event_action(axis, e, a)?,
            Command::ResetEventStatus(m) => p.reset_event_status(axis, m)?,
            Command::GetCommandedPosition => {
                let v = p.commanded_position(axis)?;
                return Ok(self.value("GetCommandedPosition", v));
            }
            Command::GetActualPosition => {
                let v = p.actual_position(axis)?;
                return Ok(self.value("GetActualPosition", v));
            }
            Command::GetActivityStatus => {
                let v = p.activity_status(axis)?;
                return Ok(self.value("GetActivityStatus", i64::from(v)));
            }
            Command::GetEventStatus => {
                let v = p.event_status(axis)?;
                return Ok(self.value("GetEventStatus", i64::from(v)));
            }
            Command::SetActualPosition(v) => p.set_actual_position(axis, v)?,
            Command::MoveTo(a, v, t) => {
                let a = p.check_axis(a)?;
                p.move_to(a, v, t)?;
            }
            Command::Tick(n) => p.run(n),
        }
        Ok(None)
    }
}

/// The document's spelling of a command's name.
fn command_name(command: &Command) -> &'static str {
    match command {
        Command::Axis(_) => "Axis",
        Command::Define(..) => "Define",
        Command::SetBufferStart(..) => "SetBufferStart",
        Command::SetBufferLength(..) => "SetBufferLength",
        Command::SetBufferWriteIndex(..) => "SetBufferWriteIndex",
        Command::WriteBuffer(..) => "WriteBuffer",
        Command::ReadBuffer(..) => "ReadBuffer",
        Command::SetProfileMode(_) => "SetProfileMode",
        Command::GetProfileMode => "GetProfileMode",
        Command::Update => "Update",
        Command::SetStopMode(_) => "SetStopMode",
        Command::SetCam(..) => "SetCam",
        Command::GetCam(_) => "GetCam",
        Command::SetBreakpointValue(..) => "SetBreakpointValue",
        Command::SetBreakpoint(..) => "SetBreakpoint",
        Command::SetEventAction(..) => "SetEventAction",
        Command::ResetEventStatus(_) => "ResetEventStatus",
        Command::GetCommandedPosition => "GetCommandedPosition",
        Command::GetActualPosition => "GetActualPosition",
        Command::GetActivityStatus => "GetActivityStatus",
        Command::GetEventStatus => "GetEventStatus",
        Command::SetActualPosition(_) => "SetActualPosition",
        Command::MoveTo(..) => "MoveTo",
        Command::Tick(_) => "Tick",
    }
}
