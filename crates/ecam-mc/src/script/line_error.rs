//! Why a script line is not a command: one variant per rule of the script
//! language (`docs/mc.md`, "Scripts"), each naming the command as written.

use core::fmt;
use std::path::PathBuf;

use ecam_core::TableError;
use ecam_core::excerpt::excerpt;

use crate::McError;

/// A line that is not a valid command.
#[derive(Clone, Debug, PartialEq)]
pub enum LineError {
    /// No command of this name.
    UnknownCommand {
        /// The command as written.
        cmd: String,
    },
    /// Too many or too few arguments.
    ArgumentCount {
        /// The command as written.
        cmd: String,
        /// The arguments it takes, by name.
        usage: &'static [&'static str],
        /// How many were given.
        got: usize,
    },
    /// `Axes` after another command.
    AxesNotFirst,
    /// A whole number past the signed 64-bit range.
    NumberOutOfRange {
        /// The command as written.
        cmd: String,
        /// What the argument is.
        what: &'static str,
        /// The argument as written.
        word: String,
    },
    /// An argument that is not a whole number.
    NotWhole {
        /// The command as written.
        cmd: String,
        /// What the argument is.
        what: &'static str,
        /// The argument as written.
        word: String,
    },
    /// A number outside the command's own range.
    OutOfRange {
        /// The command as written.
        cmd: String,
        /// What the argument is.
        what: &'static str,
        /// The value given.
        value: i64,
        /// The smallest value allowed.
        min: i64,
        /// The largest value allowed.
        max: i64,
    },
    /// A count below 1 where a count or `Off` is expected.
    CountOrOff {
        /// The command as written.
        cmd: String,
        /// What the argument is.
        what: &'static str,
        /// The value given.
        value: i64,
    },
    /// An axis number past the script's axes.
    NoSuchAxis {
        /// The command as written.
        cmd: String,
        /// The axis given.
        axis: i64,
        /// How many axes the script has.
        count: usize,
    },
    /// The controller refuses the value (a single-turn range).
    Refused {
        /// The command as written.
        cmd: String,
        /// Why.
        error: McError,
    },
    /// A user unit of less than 1 pulse.
    UserUnit {
        /// The command as written.
        cmd: String,
        /// The pulses given.
        pulses: i64,
    },
    /// A table name that is not one.
    TableName {
        /// The command as written.
        cmd: String,
        /// The name as written.
        name: String,
    },
    /// An inline table whose numbers do not pair up.
    Pairs {
        /// The command as written.
        cmd: String,
        /// How many numbers were given.
        got: usize,
    },
    /// A table the point-table checks refuse.
    Table {
        /// The command as written.
        cmd: String,
        /// Why.
        error: TableError,
    },
    /// `ECAMTableFile` without a name or a path.
    TableFileArgs {
        /// The command as written.
        cmd: String,
    },
    /// A table file that cannot be read; `reason` is the reader's message
    /// and its causes.
    TableFile {
        /// The command as written.
        cmd: String,
        /// The reader's message.
        reason: String,
    },
    /// A table file that holds no point table.
    NotPoints {
        /// The command as written.
        cmd: String,
        /// The file.
        path: PathBuf,
        /// The kind of table it holds.
        kind: &'static str,
    },
    /// An E-CAM whose master is its slave.
    OwnMaster {
        /// The command as written.
        cmd: String,
        /// The axis.
        axis: usize,
    },
    /// An E-CAM type other than Normal, Periodic and Repeat.
    CamType {
        /// The command as written.
        cmd: String,
        /// The type, in lower case.
        word: String,
    },
    /// A table name no earlier line defines.
    NoSuchTable {
        /// The command as written.
        cmd: String,
        /// The name asked for.
        name: String,
        /// The names defined so far.
        known: Vec<String>,
    },
    /// A `Tick` that takes the script's `Tick`s past the cycles one run
    /// may take ([`ecam_core::budget`]).
    TicksOverBudget {
        /// The `Tick`'s cycles.
        ticks: u64,
        /// The cycles one run may take.
        limit: i64,
    },
}

impl fmt::Display for LineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        match self {
            Self::UnknownCommand { cmd } => {
                write!(f, "unknown command '{cmd}'", cmd = excerpt(cmd))
            }
            Self::ArgumentCount { cmd, usage, got } => {
                let shape = if usage.is_empty() {
                    "no arguments".to_owned()
                } else {
                    usage.join(" ")
                };
                write!(
                    f,
                    "{cmd} takes {shape}, got {got} argument{}",
                    plural(*got),
                    cmd = excerpt(cmd)
                )
            }
            Self::AxesNotFirst => f.write_str(
                "Axes must be the script's first command: it creates the axes the others use",
            ),
            Self::NumberOutOfRange { cmd, what, word } => write!(
                f,
                "{cmd}: {what} {word} is out of range (a signed 64-bit number)",
                cmd = excerpt(cmd),
                word = excerpt(word)
            ),
            Self::NotWhole { cmd, what, word } => {
                write!(
                    f,
                    "{cmd}: {what} '{word}' is not a whole number",
                    cmd = excerpt(cmd),
                    word = excerpt(word)
                )
            }
            Self::OutOfRange {
                cmd,
                what,
                value,
                min,
                max,
            } => write!(
                f,
                "{cmd}: {what} {value} is out of range: {min} to {max}",
                cmd = excerpt(cmd)
            ),
            Self::CountOrOff { cmd, what, value } => {
                write!(
                    f,
                    "{cmd}: {what} must be at least 1 (or Off), got {value}",
                    cmd = excerpt(cmd)
                )
            }
            Self::NoSuchAxis { cmd, axis, count } => write!(
                f,
                "{cmd}: no axis {axis}: axes are numbered 0 to {} (`Axes N` as the first command sets how many)",
                count.saturating_sub(1),
                cmd = excerpt(cmd)
            ),
            Self::Refused { cmd, error } => write!(f, "{cmd}: {error}", cmd = excerpt(cmd)),
            Self::UserUnit { cmd, pulses } => {
                write!(
                    f,
                    "{cmd}: a user unit must be at least 1 pulse, got {pulses}",
                    cmd = excerpt(cmd)
                )
            }
            Self::TableName { cmd, name } => write!(
                f,
                "{cmd}: '{name}' is not a table name (letters, digits, _ and -, starting with a letter or _)",
                cmd = excerpt(cmd),
                name = excerpt(name)
            ),
            Self::Pairs { cmd, got } => write!(
                f,
                "{cmd}: give the points as MASTER SLAVE pairs after the name, got {got} number{}",
                plural(*got),
                cmd = excerpt(cmd)
            ),
            Self::Table { cmd, error } => write!(f, "{cmd}: {error}", cmd = excerpt(cmd)),
            Self::TableFileArgs { cmd } => write!(f, "{cmd} takes NAME PATH", cmd = excerpt(cmd)),
            Self::TableFile { cmd, reason } => write!(f, "{cmd}: {reason}", cmd = excerpt(cmd)),
            Self::NotPoints { cmd, path, kind } => write!(
                f,
                "{cmd}: {} holds a {kind} table; an E-CAM table is (master, slave) points: CSV, or JSON of kind points",
                path.display(),
                cmd = excerpt(cmd)
            ),
            Self::OwnMaster { cmd, axis } => {
                write!(
                    f,
                    "{cmd}: axis {axis} cannot be its own master",
                    cmd = excerpt(cmd)
                )
            }
            Self::CamType { cmd, word } => write!(
                f,
                "{cmd}: unknown E-CAM type '{word}': use Normal, Periodic or Repeat",
                cmd = excerpt(cmd),
                word = excerpt(word)
            ),
            Self::NoSuchTable { cmd, name, known } => {
                write!(
                    f,
                    "{cmd}: no E-CAM table named '{name}' (",
                    cmd = excerpt(cmd),
                    name = excerpt(name)
                )?;
                if known.is_empty() {
                    f.write_str("no table is defined yet: define one with ECAMTable or ECAMTableFile above this line")?;
                } else {
                    write!(f, "defined so far: {}", known.join(", "))?;
                }
                f.write_str(")")
            }
            Self::TicksOverBudget { ticks, limit } => write!(
                f,
                "Tick {ticks}: the script's Ticks add up to more than the {limit} cycles one run may take"
            ),
        }
    }
}

impl std::error::Error for LineError {}
