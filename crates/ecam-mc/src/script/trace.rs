//! `Trace`: the command positions of chosen axes, one CSV row per cycle.

use std::fs::File;
use std::io::{BufWriter, Write as _};
use std::path::{Path, PathBuf};

use crate::{McError, MotionController};

/// An open trace file.
#[derive(Debug)]
pub(crate) struct Trace {
    path: PathBuf,
    axes: Vec<usize>,
    out: BufWriter<File>,
}

/// Why a trace could not be written.
#[derive(Debug)]
pub(crate) enum TraceError {
    /// The file could not be created or written.
    Io(PathBuf, std::io::Error),
    /// An axis went missing (cannot happen with a parsed script).
    Axis(McError),
}

impl core::fmt::Display for TraceError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Io(path, e) => write!(f, "cannot write trace file {}: {e}", path.display()),
            Self::Axis(e) => write!(f, "trace: {e}"),
        }
    }
}

impl Trace {
    /// Creates (or replaces) `path` and writes the header and the row of
    /// the current positions at `cycle`.
    pub(crate) fn create(
        path: &Path,
        axes: Vec<usize>,
        controller: &MotionController,
        cycle: u64,
    ) -> Result<Self, TraceError> {
        let io = |e| TraceError::Io(path.to_path_buf(), e);
        let file = File::create(path).map_err(io)?;
        let mut trace = Self {
            path: path.to_path_buf(),
            axes,
            out: BufWriter::new(file),
        };
        let mut header = String::from("cycle");
        for axis in &trace.axes {
            header.push_str(&format!(",axis{axis}"));
        }
        writeln!(trace.out, "{header}").map_err(io)?;
        trace.row(controller, cycle)?;
        Ok(trace)
    }

    /// Writes the row for `cycle`.
    pub(crate) fn row(
        &mut self,
        controller: &MotionController,
        cycle: u64,
    ) -> Result<(), TraceError> {
        let mut row = cycle.to_string();
        for &axis in &self.axes {
            let position = controller.position(axis).map_err(TraceError::Axis)?;
            row.push_str(&format!(",{position}"));
        }
        writeln!(self.out, "{row}").map_err(|e| TraceError::Io(self.path.clone(), e))
    }

    /// Writes out what is buffered.
    pub(crate) fn flush(&mut self) -> Result<(), TraceError> {
        self.out
            .flush()
            .map_err(|e| TraceError::Io(self.path.clone(), e))
    }

    /// Flushes and closes the file.
    pub(crate) fn finish(mut self) -> Result<(), TraceError> {
        self.flush()
    }
}
