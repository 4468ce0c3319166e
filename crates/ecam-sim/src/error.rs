//! Why a scenario cannot be simulated: the file cannot be read, a key is
//! wrong, the settings contradict each other, or the engine refuses the
//! cam. Each message names the key and says everything, causes included
//! (no `source`), so a front end prints it as it is.

use core::fmt;
use std::path::PathBuf;

use ecam_design::TableSourceError;
use ecam_engine::{CouplingError, EngineError};

use crate::couplings_error::CouplingsError;

/// A scenario file that does not describe a run.
#[derive(Debug)]
pub enum ScenarioError {
    /// The file cannot be read.
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The scenario in `path` is wrong.
    In {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        error: Box<ScenarioError>,
    },
    /// TOML syntax, an unknown key, or a value of the wrong kind.
    Toml(toml::de::Error),
    /// A `[table]` (`place` = `[table]`, `[[switch]] N table`) that gives no cam.
    Table {
        /// Which table.
        place: String,
        /// Why (boxed: a file error carries its excerpt and path).
        error: Box<TableSourceError>,
    },
    /// A duration or time outside 0 to a year.
    Seconds {
        /// The key.
        what: String,
        /// The value given.
        seconds: f64,
    },
    /// A key that must be at least 1.
    AtLeastOne {
        /// The key, with its section.
        key: String,
        /// What follows the 1: ` count` for master distances, a note, or
        /// nothing.
        unit: &'static str,
    },
    /// `[master] moves[i]` target past ±4.5e15 counts.
    TargetRange {
        /// The move.
        index: usize,
        /// The target given.
        target: f64,
    },
    /// `[master] moves[i]` target with a fraction.
    TargetFraction {
        /// The move.
        index: usize,
        /// The target given.
        target: f64,
    },
    /// The moves together last longer than 2^64 µs.
    MovesTooLong,
    /// Neither moves nor a duration.
    NothingToSimulate,
    /// More ticks than [`ecam_core::limits::MAX_SIMULATED_TICKS`].
    TooManyTicks {
        /// The ticks the scenario runs.
        ticks: u64,
        /// Its tick.
        tick_us: u32,
    },
    /// `[start] input[i]` that goes off before it goes on.
    InputOrder {
        /// The input span.
        index: usize,
    },
    /// A stop or switch (`what`) without exactly one trigger.
    Trigger {
        /// `[stop]` or `[[switch]] N`.
        what: String,
    },
    /// `[[switch]] N` with `mode = "position"` and no position.
    SwitchPositionMissing {
        /// `[[switch]] N`.
        what: String,
    },
    /// `[[switch]] N` with a position but another mode.
    SwitchPositionUnused {
        /// `[[switch]] N`.
        what: String,
    },
    /// More than 4 `[[sync]]` windows.
    TooManySyncWindows {
        /// How many were given.
        got: usize,
    },
    /// A `[[sync]]` window whose low end is above its high end.
    SyncOrder {
        /// The low end.
        low: i64,
        /// The high end.
        high: i64,
    },
    /// `[cam] max_interval_us` without `master_filter = "interpolate"`.
    IntervalNeedsInterpolate,
    /// A `[cam]` key the cam's kind never reads.
    UnusedCamKey {
        /// The key.
        key: &'static str,
        /// The kind that reads it.
        applies_to: &'static str,
        /// The cam's kind.
        kind: &'static str,
    },
    /// A `[start]` key the start's mode never reads.
    UnusedStartKey {
        /// The key.
        key: &'static str,
        /// The modes that read it, quoted.
        modes: &'static str,
        /// The start's mode.
        mode: &'static str,
    },
    /// `[start] input` without an edge to wait for.
    UnusedInput {
        /// The start's mode.
        mode: &'static str,
    },
    /// `master_value`/`slave_value` the alignment never reads.
    UnusedAlignValue {
        /// The key.
        key: &'static str,
        /// The alignments that read it.
        aligns: &'static str,
    },
    /// A start setting without the key it needs.
    StartNeeds {
        /// The setting (`mode = "after-delay"`, `this master_align`).
        setting: &'static str,
        /// The key and its value, as it should be written.
        needs: &'static str,
    },
    /// A zoom the engine refuses.
    Zoom {
        /// `master_zoom` or `slave_zoom`.
        what: &'static str,
        /// The numerator given.
        num: u16,
        /// The denominator given.
        den: u16,
        /// Why.
        error: EngineError,
    },
    /// A coupling section (`[modulo]`, `[registration]`, `[[plcopen]]`...).
    Couplings(CouplingsError),
}

impl From<CouplingsError> for ScenarioError {
    fn from(e: CouplingsError) -> Self {
        Self::Couplings(e)
    }
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read { path, source } => {
                write!(f, "cannot read scenario {}: {source}", path.display())
            }
            Self::In { path, error } => write!(f, "in scenario {}: {error}", path.display()),
            // TOML quotes the input (a whole line): cut it, in plain words.
            Self::Toml(e) => f.write_str(&ecam_core::io::plain_serde_message(&e.to_string())),
            Self::Table { place, error } => write!(f, "in {place}: {error}"),
            Self::Seconds { what, seconds } => write!(
                f,
                "{what} = {seconds:?} s: must be between 0 and 3.2e7 seconds"
            ),
            Self::AtLeastOne { key, unit } => write!(f, "{key} must be at least 1{unit}"),
            Self::TargetRange { index, target } => write!(
                f,
                "[master] moves[{index}] target {target:?} is out of range: at most ±4.5e15 counts"
            ),
            Self::TargetFraction { index, target } => write!(
                f,
                "[master] moves[{index}] target {target} must be a whole number of counts"
            ),
            Self::MovesTooLong => f.write_str("[master] moves last too long"),
            Self::NothingToSimulate => {
                f.write_str("nothing to simulate: give [master] moves or duration_s")
            }
            Self::TooManyTicks { ticks, tick_us } => write!(
                f,
                "the scenario runs {ticks} ticks of {tick_us} us; the limit is {}: shorten duration_s or the moves, or lengthen tick_us",
                ecam_core::limits::MAX_SIMULATED_TICKS
            ),
            Self::InputOrder { index } => write!(
                f,
                "[start] input[{index}]: the input must go off after it goes on"
            ),
            Self::Trigger { what } => write!(
                f,
                "{what} needs exactly one of at_s, master_at_least, master_at_most"
            ),
            Self::SwitchPositionMissing { what } => {
                write!(f, "{what}: mode = \"position\" needs position = MASTER")
            }
            Self::SwitchPositionUnused { what } => {
                write!(f, "{what}: position is read only with mode = \"position\"")
            }
            Self::TooManySyncWindows { got } => {
                write!(f, "at most 4 [[sync]] windows, got {got}")
            }
            Self::SyncOrder { low, high } => {
                write!(f, "[[sync]] low {low} is above high {high}")
            }
            Self::IntervalNeedsInterpolate => {
                f.write_str("[cam] max_interval_us needs master_filter = \"interpolate\"")
            }
            Self::UnusedCamKey {
                key,
                applies_to,
                kind,
            } => write!(
                f,
                "[cam] {key} only applies to kind = \"{applies_to}\" (this cam is \"{kind}\")"
            ),
            Self::UnusedStartKey { key, modes, mode } => write!(
                f,
                "[start] {key} only applies to mode = {modes} (this start is mode = \"{mode}\")"
            ),
            Self::UnusedInput { mode } => write!(
                f,
                "[start] input is only read by mode = \"rising-edge\" or with after_edge = true (this start is mode = \"{mode}\")"
            ),
            Self::UnusedAlignValue { key, aligns } => {
                write!(f, "[start] {key} only applies to {aligns}")
            }
            Self::StartNeeds { setting, needs } => {
                write!(f, "[start] {setting} needs {needs}")
            }
            Self::Zoom {
                what,
                num,
                den,
                error,
            } => write!(f, "[cam] {what} = [{num}, {den}]: {error}"),
            Self::Couplings(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for ScenarioError {}

/// A run that could not go on: the engine refused the scenario's cam or a
/// step of it, or the caller's `record` failed (`E`, its error).
#[derive(Debug)]
pub enum SimulateError<E> {
    /// The engine refuses the cam or configuration (a slave axis' couplings
    /// included).
    Refused {
        /// Why.
        error: CouplingError,
        /// The table's first and last master.
        master_range: (i64, i64),
        /// `[cam] single_turn`, if set.
        single_turn: Option<u64>,
    },
    /// The start slave position cannot be set.
    SlaveStart(CouplingError),
    /// The cam cannot be armed.
    Arm(EngineError),
    /// The engine refuses the table of `[[switch]] N`.
    Switch {
        /// N, counting from 1.
        number: usize,
        /// Why.
        error: EngineError,
        /// The new table's first and last master.
        master_range: (i64, i64),
    },
    /// The engine refuses `[[plcopen]] N`'s block.
    Step {
        /// N, counting from 1.
        number: usize,
        /// The block's PLCopen name.
        block: &'static str,
        /// Why.
        error: CouplingError,
    },
    /// [`crate::simulate_couplings`] on a scenario without couplings.
    NoCouplings,
    /// The caller's `record` failed; the run stopped there.
    Record(E),
}

impl<E: fmt::Display> fmt::Display for SimulateError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Refused {
                error,
                master_range: (first, last),
                single_turn,
            } => {
                // Name the numbers the engine compared, so the user sees what to change.
                write!(
                    f,
                    "the engine refuses the scenario: {error} (table master {first} .. {last}"
                )?;
                if let Some(turn) = single_turn {
                    write!(f, ", single_turn = {turn}")?;
                }
                f.write_str(")")
            }
            Self::SlaveStart(e) => write!(f, "cannot set the start slave position: {e}"),
            Self::Arm(e) => write!(f, "cannot arm the cam: {e}"),
            Self::Switch {
                number,
                error,
                master_range: (first, last),
            } => write!(
                f,
                "[[switch]] {number}: the engine refuses the table: {error} (table master {first} .. {last})"
            ),
            Self::Step {
                number,
                block,
                error,
            } => write!(f, "[[plcopen]] {number} {block}: refused: {error}"),
            Self::NoCouplings => {
                f.write_str("the scenario has no couplings: run it with `simulate`")
            }
            // The alternate form keeps the causes of an error that has them
            // (an `anyhow::Error` of the caller).
            Self::Record(e) => write!(f, "{e:#}"),
        }
    }
}

impl<E: fmt::Debug + fmt::Display> std::error::Error for SimulateError<E> {}
