//! Why a script did not run to its end.

use core::fmt;
use std::path::PathBuf;

/// A script that could not be read, a line that is not a command, or a
/// command the controller refused. Printed as `FILE:LINE: message` (or
/// `FILE: message` when no line is at fault).
///
/// A parse error stops the script before anything runs; a refused command
/// changes nothing and ends the run at that line (what earlier lines
/// printed stands).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScriptError {
    /// The script file (as given).
    pub path: PathBuf,
    /// The line at fault, counting from 1; `None` when the file itself
    /// could not be read.
    pub line: Option<usize>,
    /// What is wrong, in words.
    pub message: String,
}

impl ScriptError {
    pub(crate) fn at(path: &std::path::Path, line: usize, message: String) -> Self {
        Self {
            path: path.to_path_buf(),
            line: Some(line),
            message,
        }
    }
}

impl fmt::Display for ScriptError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{line}: {}", self.path.display(), self.message),
            None => write!(f, "{}: {}", self.path.display(), self.message),
        }
    }
}

impl std::error::Error for ScriptError {}
