//! Why a script did not run to its end.

use core::fmt;
use std::path::PathBuf;

use super::LineError;

/// A script that could not be read, a line that is not a command, or a
/// command the controller refused. Printed as `FILE:LINE: message` (or
/// `FILE: message` when no line is at fault).
///
/// A parse error stops the script before anything runs; a refused command
/// changes nothing and ends the run at that line (what earlier lines
/// printed stands).
#[derive(Clone, Debug, PartialEq)]
pub struct ScriptError {
    /// The script file (as given).
    pub path: PathBuf,
    /// The line at fault, counting from 1; `None` when the file itself
    /// could not be read or the trace could not be closed.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: Problem,
}

/// What stopped a script.
#[derive(Clone, Debug, PartialEq)]
pub enum Problem {
    /// The script file cannot be read (the system's reason).
    Read(String),
    /// A line is not a valid command; nothing ran.
    Line(LineError),
    /// The controller refused a command; it changed nothing and the run
    /// ended there.
    Refused {
        /// The command's name.
        command: &'static str,
        /// Why it was refused.
        reason: String,
    },
    /// The trace file could not be written at the end of the run.
    Trace(String),
}

impl ScriptError {
    pub(crate) fn at(path: &std::path::Path, line: usize, problem: Problem) -> Self {
        Self {
            path: path.to_path_buf(),
            line: Some(line),
            problem,
        }
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read(reason) => write!(f, "cannot read the script: {reason}"),
            Self::Line(error) => write!(f, "{error}"),
            Self::Refused { command, reason } => write!(f, "{command}: {reason}"),
            Self::Trace(reason) => f.write_str(reason),
        }
    }
}

impl fmt::Display for ScriptError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{line}: {}", self.path.display(), self.problem),
            None => write!(f, "{}: {}", self.path.display(), self.problem),
        }
    }
}

impl std::error::Error for ScriptError {}
