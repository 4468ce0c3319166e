//! The per-tick trace of `ecam simulate --trace`.
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

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use anyhow::Context;
use ecam_engine::TickOutput;
use ecam_sim::{Row, state_name};

/// The trace header line.
pub const HEADER: &str =
    "t,master,slave,velocity,pulses,emitted,backlog,master_in_cycle,cycle,state,sync,flags";

/// Writes trace rows to a CSV file.
pub struct TraceWriter {
    out: BufWriter<File>,
}

impl TraceWriter {
    /// Creates `path` and writes the header.
    ///
    /// # Errors
    /// The file cannot be created or written.
    pub fn create(path: &Path) -> anyhow::Result<Self> {
        let file = File::create(path)
            .with_context(|| format!("cannot create trace file {}", path.display()))?;
        let mut out = BufWriter::new(file);
        writeln!(out, "{HEADER}")?;
        Ok(Self { out })
    }

    /// Appends one row.
    ///
    /// # Errors
    /// A failed write.
    pub fn write(&mut self, row: &Row, out: &TickOutput) -> anyhow::Result<()> {
        writeln!(
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
        )?;
        Ok(())
    }

    /// Flushes the file.
    ///
    /// # Errors
    /// A failed write.
    pub fn finish(mut self) -> anyhow::Result<()> {
        self.out.flush()?;
        Ok(())
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
