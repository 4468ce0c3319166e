//! The script language of `ecam mc run`: document 001's motion controller
//! without Rust.
//!
//! One command per line, arguments separated by blanks (or commas); `'`
//! starts a comment; command names and the words `Off`, `Normal`,
//! `Periodic`, `Repeat` ignore letter case. Axes are numbered from 0.
//! Every `Get…` command gives a [`Report`], printed as one JSON object per
//! line. The whole language, with its output and errors, is in `docs/mc.md`
//! ("Scripts").
//!
//! A script is parsed whole before anything runs ([`Script::read`]): every
//! argument is checked, every axis number bounded, every table read and
//! validated, so a bad line stops it at once with `FILE:LINE: message`.
//! Running ([`ScriptRunner::run`]) stops at the first command the
//! controller refuses; that command changed nothing.
//!
//! ```
//! use ecam_mc::script::{Script, ScriptRunner};
//!
//! let text = "
//! ' Document 001: Repeat type, continuous at the seam.
//! ECAMTable doc 0 500, 10000 1500, 20000 1000, 30000 2000
//! StartECAM 0 1 Repeat doc
//! MoveTo 0 40000 400    ' master 0 -> 40000 over 400 cycles
//! Tick 400
//! GetCommandPosition 1
//! ";
//! let script = Script::parse(text, "repeat.mc")?;
//! let mut runner = ScriptRunner::default();
//! let mut lines = Vec::new();
//! runner.run(&script, |report| lines.push(report.to_json()))?;
//! assert_eq!(lines, [r#"{"cmd":"GetCommandPosition","axis":1,"value":3000}"#]);
//!
//! // A bad line names its place; nothing ran.
//! let err = Script::parse("Tick 10\nStartECAM 0 1 Repeat nowhere", "bad.mc").unwrap_err();
//! assert!(err.to_string().starts_with("bad.mc:2: StartECAM: no E-CAM table named 'nowhere'"));
//! # Ok::<(), ecam_mc::script::ScriptError>(())
//! ```
//!
//! For a file, [`run_file`] collects the reports and [`run_file_with`]
//! hands each one over as it is made (what `ecam mc run` prints).

mod command;
mod error;
mod line_error;
mod linear_move;
mod parse;
mod report;
mod runner;
mod trace;

use std::path::Path;

pub use command::Command;
pub use error::{Problem, ScriptError};
pub use line_error::LineError;
pub use parse::{DEFAULT_AXES, Line, MAX_AXES, Script};
pub use report::Report;
pub use runner::ScriptRunner;

/// Reads, parses and runs the script at `path`, handing each report to
/// `on_report` as it is made: what `ecam mc run SCRIPT` does, printing
/// [`Report::to_json`] lines.
///
/// ```
/// use std::io::Write;
///
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/mc/single_turn_start.mc");
/// let mut out = Vec::new(); // `std::io::stdout().lock()` in `ecam mc run`
/// let mut written = Ok(());
/// let result = ecam_mc::script::run_file_with(path, |report| {
///     if written.is_ok() {
///         written = writeln!(out, "{report}");
///     }
/// });
/// result?; // on error: `SCRIPT:LINE: message`
/// written?;
/// let text = String::from_utf8(out)?;
/// assert_eq!(
///     text.lines().next(),
///     Some(r#"{"cmd":"GetCommandPosition","axis":1,"value":-2000}"#)
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// The script cannot be read, a line is not a valid command (nothing ran),
/// or a command was refused (the run ended there; earlier reports were
/// handed over).
pub fn run_file_with(
    path: impl AsRef<Path>,
    on_report: impl FnMut(&Report),
) -> Result<(), ScriptError> {
    let script = Script::read(path)?;
    ScriptRunner::new(script.axis_count()).run(&script, on_report)
}

/// Reads, parses and runs the script at `path`; gives every report.
///
/// # Errors
/// As [`run_file_with`]; the reports made before a refused command are
/// dropped (use [`run_file_with`] to keep them).
pub fn run_file(path: impl AsRef<Path>) -> Result<Vec<Report>, ScriptError> {
    let mut reports = Vec::new();
    run_file_with(path, |report| reports.push(report.clone()))?;
    Ok(reports)
}
