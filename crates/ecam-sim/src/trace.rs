//! What the simulation loop reports at each tick, besides the engine's own
//! [`TickOutput`], and the trace CSV `ecam simulate --trace` writes of it.
//!
//! Header (a contract for scripts; columns may only be added at the end):
//! `t,master,slave,velocity,pulses,emitted,backlog,master_in_cycle,cycle,state,sync,flags`
//! - `t`: seconds since the start;
//! - `master`: the master as the cam receives it (the raw turn position on a
//!   single-turn master), `slave`: the commanded slave position;
//! - `velocity`: commanded slave velocity in pulses per second over the last tick;
//! - `pulses`: pulses emitted this tick (signed), `emitted`: their running sum,
//!   `backlog`: commanded minus emitted;
//! - `master_in_cycle`, `cycle`: the table input and the completed cycles;
//! - `state`: the engine state; `sync`: bit i set while sync window i is on;
//! - `flags`: `|`-separated: `delayed` (backlog), `engaged`, `cycle`,
//!   `finished`, `stopped`, `switched` (a queued table took over), `jump`
//!   (a periodic seam jump) (this tick's events), `fault`.

use core::fmt;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use ecam_engine::{AxisState, TickOutput};

/// One tick of a run: the trace CSV's first columns, and what a trace plot
/// draws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    /// Seconds since the start.
    pub t: f64,
    /// Master input of the tick (the raw turn position on a single-turn
    /// master).
    pub master: i64,
    /// Commanded slave position.
    pub slave: i64,
    /// Commanded slave velocity over the last tick, pulses per second (0 at
    /// tick 0, which has no interval before it).
    pub velocity: f64,
    /// Pulses this tick (signed).
    pub pulses: i64,
    /// Emitted position.
    pub emitted: i64,
    /// Commanded minus emitted.
    pub backlog: i64,
    /// Whether any sync window was on.
    pub in_sync: bool,
}

/// The engine state as a lower-case word, as the summary and the trace
/// write it.
pub fn state_name(state: AxisState) -> &'static str {
    match state {
        AxisState::Idle => "idle",
        AxisState::Armed => "armed",
        AxisState::Delaying => "delaying",
        AxisState::Running => "running",
        AxisState::Stopping => "stopping",
        AxisState::Finished => "finished",
        AxisState::Velocity => "velocity",
    }
}

/// The trace header line.
pub const HEADER: &str =
    "t,master,slave,velocity,pulses,emitted,backlog,master_in_cycle,cycle,state,sync,flags";

/// A trace file that cannot be created or written.
#[derive(Debug)]
pub struct TraceError {
    /// The file.
    pub path: PathBuf,
    /// Why.
    pub source: std::io::Error,
}

impl fmt::Display for TraceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "cannot write trace file {}: {}",
            self.path.display(),
            self.source
        )
    }
}

impl std::error::Error for TraceError {}

/// Writes trace rows to a CSV file.
pub struct TraceWriter {
    out: BufWriter<File>,
    path: PathBuf,
}

impl TraceWriter {
    /// Creates `path` and writes the header.
    ///
    /// # Errors
    /// The file cannot be created or written.
    pub fn create(path: &Path) -> Result<Self, TraceError> {
        let error = |source| TraceError {
            path: path.to_path_buf(),
            source,
        };
        let mut out = BufWriter::new(File::create(path).map_err(error)?);
        writeln!(out, "{HEADER}").map_err(error)?;
        Ok(Self {
            out,
            path: path.to_path_buf(),
        })
    }

    fn error(&self, source: std::io::Error) -> TraceError {
        TraceError {
            path: self.path.clone(),
            source,
        }
    }

    /// Appends one row.
    ///
    /// # Errors
    /// A failed write.
    pub fn write(&mut self, row: &Row, out: &TickOutput) -> Result<(), TraceError> {
        let written = writeln!(
            self.out,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            row.t,
            row.master,
            row.slave,
            row.velocity,
            row.pulses,
            row.emitted,
            row.backlog,
            out.master_in_cycle,
            out.cycle,
            state_name(out.state),
            out.sync,
            flags(out)
        );
        written.map_err(|e| self.error(e))
    }

    /// Flushes the file.
    ///
    /// # Errors
    /// A failed write.
    pub fn finish(mut self) -> Result<(), TraceError> {
        let flushed = self.out.flush();
        flushed.map_err(|e| self.error(e))
    }
}

fn flags(out: &TickOutput) -> String {
    let e = &out.events;
    let named = [
        (out.pulse_delayed, "delayed"),
        (e.engaged, "engaged"),
        (e.cycle_completed, "cycle"),
        (e.finished, "finished"),
        (e.stopped, "stopped"),
        (e.table_switched, "switched"),
        (e.seam_jump, "jump"),
        (out.fault.is_some(), "fault"),
    ];
    named
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, name)| *name)
        .collect::<Vec<_>>()
        .join("|")
}
