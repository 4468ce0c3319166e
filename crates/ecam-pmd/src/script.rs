//! The script language of `ecam pmd run`: one document-002 command per line.
//!
//! A line is read by the reader both script faces share
//! ([`ecam_core::script_line`]): a command name and its arguments separated
//! by blanks (or commas); `'` starts a comment, and so do the typographic
//! quotes `‘ ’` that document 002's listing uses; a line holding only `…`
//! or `...` is the document's elision and is skipped. Numbers are decimal
//! or `0x` hex, with an optional sign; a name defined by `Define NAME VALUE`
//! may stand for a number (document 002 writes `WriteBuffer 2
//! cam_table_0`). Command and parameter names ignore letter case.

use std::collections::HashMap;

use ecam_core::excerpt::excerpt;

use ecam_core::script_line::{NumberError, ScriptLine, parse_number};

use crate::CamParam;

/// One parsed command.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Command {
    /// `Axis N`: later commands go to axis N (from 0).
    Axis(i64),
    /// `Define NAME VALUE`: NAME stands for VALUE from here on.
    Define(String, i64),
    /// `SetBufferStart ID ADDRESS`.
    SetBufferStart(i64, i64),
    /// `SetBufferLength ID LENGTH`.
    SetBufferLength(i64, i64),
    /// `SetBufferWriteIndex ID INDEX`.
    SetBufferWriteIndex(i64, i64),
    /// `WriteBuffer ID VALUE`.
    WriteBuffer(i64, i64),
    /// `ReadBuffer ID INDEX` (prints the value).
    ReadBuffer(i64, i64),
    /// `SetProfileMode MODE` (0 Trapezoidal, 8 ElectronicCam).
    SetProfileMode(i64),
    /// `GetProfileMode`.
    GetProfileMode,
    /// `Update`.
    Update,
    /// `SetStopMode MODE` (0 none, 1 abrupt, 2 smooth).
    SetStopMode(i64),
    /// `SetCam PARAM VALUE`.
    SetCam(CamParam, i64),
    /// `GetCam PARAM`.
    GetCam(CamParam),
    /// `SetBreakpointValue ID VALUE`.
    SetBreakpointValue(i64, i64),
    /// `SetBreakpoint ID WORD`.
    SetBreakpoint(i64, i64),
    /// `SetEventAction EVENT ACTION`.
    SetEventAction(i64, i64),
    /// `ResetEventStatus MASK`.
    ResetEventStatus(i64),
    /// `GetCommandedPosition`.
    GetCommandedPosition,
    /// `GetActualPosition`.
    GetActualPosition,
    /// `GetActivityStatus`.
    GetActivityStatus,
    /// `GetEventStatus`.
    GetEventStatus,
    /// `SetActualPosition POSITION` (simulation).
    SetActualPosition(i64),
    /// `MoveTo AXIS POSITION TICKS` (simulation).
    MoveTo(i64, i64, i64),
    /// `Tick N`: run N cycles (simulation).
    Tick(u64),
}

/// A line that is not a command.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ParseError {
    /// No command of this name.
    UnknownCommand {
        /// The command name as written.
        cmd: String,
    },
    /// Too many or too few arguments.
    ArgumentCount {
        /// The command name as written.
        cmd: String,
        /// The arguments it takes, by name.
        usage: &'static [&'static str],
        /// How many were given.
        got: usize,
    },
    /// A number past the signed 64-bit range.
    NumberOutOfRange {
        /// The command name as written.
        cmd: String,
        /// The argument as written.
        word: String,
    },
    /// An argument that is neither a number nor a known name.
    NotANumber {
        /// The command name as written.
        cmd: String,
        /// The argument as written.
        word: String,
        /// The names the argument may take besides numbers.
        names: Names,
    },
    /// `Define` with a name that is not one.
    BadName {
        /// The command name as written.
        cmd: String,
        /// The name as written.
        name: String,
    },
    /// `Tick` with a cycle count outside 0 to the simulation limit.
    TickCount {
        /// The command name as written.
        cmd: String,
        /// The count given.
        count: i64,
    },
    /// `SetCam`/`GetCam` with a parameter document 002 does not have.
    UnknownCamParam {
        /// The command name as written.
        cmd: String,
        /// The parameter as written.
        word: String,
    },
    /// A `Tick` that takes the script's `Tick`s past the cycles one run
    /// may take ([`ecam_core::budget`]).
    TicksOverBudget {
        /// The command name as written.
        cmd: String,
        /// The `Tick`'s cycles.
        ticks: u64,
    },
}

impl ParseError {
    /// The command name as written.
    pub fn cmd(&self) -> &str {
        match self {
            Self::UnknownCommand { cmd }
            | Self::ArgumentCount { cmd, .. }
            | Self::NumberOutOfRange { cmd, .. }
            | Self::NotANumber { cmd, .. }
            | Self::BadName { cmd, .. }
            | Self::TickCount { cmd, .. }
            | Self::UnknownCamParam { cmd, .. }
            | Self::TicksOverBudget { cmd, .. } => cmd,
        }
    }
}

impl core::fmt::Display for ParseError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::UnknownCommand { cmd } => {
                write!(f, "unknown command '{cmd}'", cmd = excerpt(cmd))
            }
            Self::ArgumentCount { cmd, usage, got } => {
                let shape = if usage.is_empty() {
                    String::from("no arguments")
                } else {
                    usage.join(" ")
                };
                write!(
                    f,
                    "{cmd} takes {} argument{} ({shape}), got {got}",
                    usage.len(),
                    if usage.len() == 1 { "" } else { "s" },
                    cmd = excerpt(cmd)
                )
            }
            Self::NumberOutOfRange { cmd, word } => write!(
                f,
                "{cmd}: {word} is out of range: numbers must fit a signed 64-bit value (and the command's own range)",
                cmd = excerpt(cmd),
                word = excerpt(word)
            ),
            Self::NotANumber { cmd, word, names } => {
                write!(
                    f,
                    "{cmd}: '{word}' is not a number or a known name: ",
                    cmd = excerpt(cmd),
                    word = excerpt(word)
                )?;
                if names.is_empty() {
                    f.write_str(
                        "give a number (decimal or 0x hex) or a name set by `Define NAME VALUE`",
                    )
                } else {
                    let known: Vec<&str> = names.iter().map(|(n, _)| *n).collect();
                    write!(
                        f,
                        "give a number, one of {}, or a name set by `Define NAME VALUE`",
                        known.join(", ")
                    )
                }
            }
            Self::BadName { name, .. } => write!(
                f,
                "Define: '{name}' is not a name (letters, digits and _, not starting with a digit)",
                name = excerpt(name)
            ),
            Self::TickCount { count, .. } => write!(
                f,
                "Tick: {count} is out of range: the cycle count must be 0 to {}",
                ecam_core::limits::MAX_SIMULATED_TICKS
            ),
            Self::UnknownCamParam { cmd, word } => write!(
                f,
                "{cmd}: unknown cam parameter '{word}': use 0 CamBufferID, 1 CamCounts, 2 CamStartCount, 3 CamSource, 4 CamOutputOffset or 5 CamInputOffset",
                cmd = excerpt(cmd),
                word = excerpt(word)
            ),
            Self::TicksOverBudget { ticks, .. } => write!(
                f,
                "Tick {ticks}: the script's Ticks add up to more than the {} cycles one run may take",
                ecam_core::limits::MAX_SIMULATED_TICKS
            ),
        }
    }
}

impl std::error::Error for ParseError {}

/// Named values a command accepts besides numbers.
pub type Names = &'static [(&'static str, i64)];

const PROFILE_MODES: Names = &[("Trapezoidal", 0), ("ElectronicCam", 8)];
const STOP_MODES: Names = &[
    ("NoStop", 0),
    ("Abrupt", 1),
    ("AbruptStop", 1),
    ("Smooth", 2),
    ("SmoothStop", 2),
];
const EVENTS: Names = &[("Immediate", 0)];
const ACTIONS: Names = &[
    ("NoAction", 0),
    ("Update", 1),
    ("AbruptStop", 2),
    ("SmoothStop", 3),
    ("StartCam", 9),
];

/// Parses lines into commands, remembering `Define`d names and how many
/// cycles the script's `Tick`s take in all (one run's budget,
/// `ecam_core::budget`).
#[derive(Clone, Debug, Default)]
pub struct Parser {
    symbols: HashMap<String, i64>,
    budget: ecam_core::budget::Budget,
}

struct Args<'a> {
    cmd: &'a str,
    words: Vec<&'a str>,
    symbols: &'a HashMap<String, i64>,
}

impl Args<'_> {
    fn expect(&self, usage: &'static [&'static str]) -> Result<(), ParseError> {
        if self.words.len() == usage.len() {
            return Ok(());
        }
        Err(ParseError::ArgumentCount {
            cmd: self.cmd.to_owned(),
            usage,
            got: self.words.len(),
        })
    }

    fn value(&self, i: usize, names: Names) -> Result<i64, ParseError> {
        let word = self.words.get(i).copied().unwrap_or_default();
        let error = match parse_number(word) {
            Ok(n) => return Ok(n),
            Err(error) => error,
        };
        if let Some(&(_, v)) = names.iter().find(|(n, _)| n.eq_ignore_ascii_case(word)) {
            return Ok(v);
        }
        if let Some(&v) = self.symbols.get(word) {
            return Ok(v);
        }
        let (cmd, word) = (self.cmd.to_owned(), word.to_owned());
        // A number too big for any register ("Tick 18446744073709551615") is
        // still a number: say it is out of range, not that it is unknown.
        Err(match error {
            NumberError::OutOfRange => ParseError::NumberOutOfRange { cmd, word },
            NumberError::NotANumber => ParseError::NotANumber { cmd, word, names },
        })
    }

    fn number(&self, i: usize) -> Result<i64, ParseError> {
        self.value(i, &[])
    }
}

impl Parser {
    /// A parser with no names defined.
    pub fn new() -> Self {
        Self::default()
    }

    /// Defines `name` as `value` for later lines (also what `Define` does).
    pub fn define(&mut self, name: &str, value: i64) {
        self.symbols.insert(name.to_owned(), value);
    }

    /// Parses one line; `Ok(None)` for a blank, comment-only or elision line.
    ///
    /// # Errors
    /// Unknown command, wrong argument count, or an argument that is not a
    /// number or known name.
    pub fn parse_line(&mut self, line: &str) -> Result<Option<Command>, ParseError> {
        let Some(line) = ScriptLine::read(line) else {
            return Ok(None);
        };
        let cmd = line.command();
        let a = Args {
            cmd,
            words: line.args().to_vec(),
            symbols: &self.symbols,
        };
        let name = cmd.to_ascii_lowercase();
        let command = match name.as_str() {
            "axis" => {
                a.expect(&["N"])?;
                Command::Axis(a.number(0)?)
            }
            "define" => {
                a.expect(&["NAME", "VALUE"])?;
                let symbol = a.words.first().copied().unwrap_or_default();
                let valid = symbol
                    .chars()
                    .next()
                    .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                    && symbol
                        .chars()
                        .all(|c| c.is_ascii_alphanumeric() || c == '_');
                if !valid {
                    return Err(ParseError::BadName {
                        cmd: cmd.to_owned(),
                        name: symbol.to_owned(),
                    });
                }
                Command::Define(symbol.to_owned(), a.number(1)?)
            }
            "setbufferstart" => {
                a.expect(&["BUFFER", "ADDRESS"])?;
                Command::SetBufferStart(a.number(0)?, a.number(1)?)
            }
            "setbufferlength" => {
                a.expect(&["BUFFER", "LENGTH"])?;
                Command::SetBufferLength(a.number(0)?, a.number(1)?)
            }
            "setbufferwriteindex" => {
                a.expect(&["BUFFER", "INDEX"])?;
                Command::SetBufferWriteIndex(a.number(0)?, a.number(1)?)
            }
            "writebuffer" => {
                a.expect(&["BUFFER", "VALUE"])?;
                Command::WriteBuffer(a.number(0)?, a.number(1)?)
            }
            "readbuffer" => {
                a.expect(&["BUFFER", "INDEX"])?;
                Command::ReadBuffer(a.number(0)?, a.number(1)?)
            }
            "setprofilemode" => {
                a.expect(&["MODE"])?;
                Command::SetProfileMode(a.value(0, PROFILE_MODES)?)
            }
            "getprofilemode" => {
                a.expect(&[])?;
                Command::GetProfileMode
            }
            "update" => {
                a.expect(&[])?;
                Command::Update
            }
            "setstopmode" => {
                a.expect(&["MODE"])?;
                Command::SetStopMode(a.value(0, STOP_MODES)?)
            }
            "setcam" => {
                a.expect(&["PARAM", "VALUE"])?;
                Command::SetCam(Self::cam_param(&a)?, a.number(1)?)
            }
            "getcam" => {
                a.expect(&["PARAM"])?;
                Command::GetCam(Self::cam_param(&a)?)
            }
            "setbreakpointvalue" => {
                a.expect(&["ID", "VALUE"])?;
                Command::SetBreakpointValue(a.number(0)?, a.number(1)?)
            }
            "setbreakpoint" => {
                a.expect(&["ID", "WORD"])?;
                Command::SetBreakpoint(a.number(0)?, a.number(1)?)
            }
            "seteventaction" => {
                a.expect(&["EVENT", "ACTION"])?;
                Command::SetEventAction(a.value(0, EVENTS)?, a.value(1, ACTIONS)?)
            }
            "reseteventstatus" => {
                a.expect(&["MASK"])?;
                Command::ResetEventStatus(a.number(0)?)
            }
            "getcommandedposition" => {
                a.expect(&[])?;
                Command::GetCommandedPosition
            }
            "getactualposition" => {
                a.expect(&[])?;
                Command::GetActualPosition
            }
            "getactivitystatus" => {
                a.expect(&[])?;
                Command::GetActivityStatus
            }
            "geteventstatus" => {
                a.expect(&[])?;
                Command::GetEventStatus
            }
            "setactualposition" => {
                a.expect(&["POSITION"])?;
                Command::SetActualPosition(a.number(0)?)
            }
            "moveto" => {
                a.expect(&["AXIS", "POSITION", "TICKS"])?;
                Command::MoveTo(a.number(0)?, a.number(1)?, a.number(2)?)
            }
            "tick" => {
                a.expect(&["N"])?;
                let n = a.number(0)?;
                let limit = ecam_core::limits::MAX_SIMULATED_TICKS;
                let n = u64::try_from(n)
                    .ok()
                    .filter(|&n| n <= limit)
                    .ok_or_else(|| ParseError::TickCount {
                        cmd: cmd.to_owned(),
                        count: n,
                    })?;
                self.budget
                    .cycles(n)
                    .map_err(|_| ParseError::TicksOverBudget {
                        cmd: cmd.to_owned(),
                        ticks: n,
                    })?;
                Command::Tick(n)
            }
            _ => {
                return Err(ParseError::UnknownCommand {
                    cmd: cmd.to_owned(),
                });
            }
        };
        if let Command::Define(symbol, value) = &command {
            self.symbols.insert(symbol.clone(), *value);
        }
        Ok(Some(command))
    }

    fn cam_param(a: &Args<'_>) -> Result<CamParam, ParseError> {
        let word = a.words.first().copied().unwrap_or_default();
        CamParam::parse(word).ok_or_else(|| ParseError::UnknownCamParam {
            cmd: a.cmd.to_owned(),
            word: word.to_owned(),
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn document_lines_parse() {
        let mut p = Parser::new();
        assert_eq!(p.parse_line("‘ Use buffer 2 for cam table").unwrap(), None);
        assert_eq!(
            p.parse_line("SetBufferStart 2 0x1000 ").unwrap(),
            Some(Command::SetBufferStart(2, 0x1000))
        );
        assert_eq!(p.parse_line(" … ").unwrap(), None);
        assert_eq!(
            p.parse_line("SetCam CamSource 0x0001").unwrap(),
            Some(Command::SetCam(CamParam::CamSource, 1))
        );
        assert_eq!(
            p.parse_line("SetProfileMode 8 ' cam").unwrap(),
            Some(Command::SetProfileMode(8))
        );
        assert_eq!(
            p.parse_line("SetProfileMode ElectronicCam").unwrap(),
            Some(Command::SetProfileMode(8))
        );
    }

    #[test]
    fn messages_quote_a_short_excerpt_of_a_huge_word() {
        let mut p = Parser::new();
        let huge = "Q".repeat(100_000);
        let e = p.parse_line(&huge).unwrap_err().to_string();
        assert!(e.len() < 100, "{} bytes: {e}", e.len());
        assert!(e.contains("(100000 bytes)"), "{e}");
        let e = p
            .parse_line(&format!("Tick {huge}"))
            .unwrap_err()
            .to_string();
        assert!(e.len() < 300, "{} bytes: {e}", e.len());
    }

    #[test]
    fn a_scripts_ticks_share_one_budget() {
        let mut p = Parser::new();
        for _ in 0..4 {
            assert_eq!(
                p.parse_line("Tick 25000000").unwrap(),
                Some(Command::Tick(25_000_000))
            );
        }
        let e = p.parse_line("Tick 1").unwrap_err();
        assert!(
            e.to_string().contains("add up to more than the 100000000"),
            "{e}"
        );
        assert_eq!(p.parse_line("Tick 0").unwrap(), Some(Command::Tick(0)));
    }

    #[test]
    fn symbols_need_a_definition() {
        let mut p = Parser::new();
        let err = p.parse_line("WriteBuffer 2 cam_table_0").unwrap_err();
        assert!(err.to_string().contains("Define"), "{err}");
        p.parse_line("Define cam_table_0 -40").unwrap();
        assert_eq!(
            p.parse_line("WriteBuffer 2 cam_table_0").unwrap(),
            Some(Command::WriteBuffer(2, -40))
        );
    }

    #[test]
    fn bad_lines_say_why() {
        let mut p = Parser::new();
        let e = p.parse_line("SetCame CamCounts 3").unwrap_err();
        assert_eq!(e.to_string(), "unknown command 'SetCame'");
        let e = p.parse_line("SetCam CamCounts").unwrap_err();
        assert_eq!(
            e.to_string(),
            "SetCam takes 2 arguments (PARAM VALUE), got 1"
        );
        let e = p.parse_line("GetCam CamSpeed").unwrap_err();
        assert!(e.to_string().contains("unknown cam parameter"));
        assert!(p.parse_line("Tick -1").is_err());
        assert!(p.parse_line("Update now").is_err());
        assert!(p.parse_line("Define 9x 1").is_err());
        // Too big for 64 bits: a number out of range, not an unknown name.
        let e = p.parse_line("Tick 18446744073709551615").unwrap_err();
        assert!(e.to_string().contains("out of range"), "{e}");
        assert!(!e.to_string().contains("not a number"), "{e}");
        let e = p
            .parse_line("WriteBuffer 0 0x1FFFFFFFFFFFFFFFF")
            .unwrap_err();
        assert!(e.to_string().contains("out of range"), "{e}");
    }

    #[test]
    fn numbers_and_names() {
        let mut p = Parser::new();
        assert_eq!(
            p.parse_line("WriteBuffer 0 -0x10").unwrap(),
            Some(Command::WriteBuffer(0, -16))
        );
        let e = p.parse_line("WriteBuffer 0 1e3").unwrap_err();
        assert_eq!(
            e.to_string(),
            "WriteBuffer: '1e3' is not a number or a known name: give a number (decimal or 0x hex) or a name set by `Define NAME VALUE`"
        );
        let e = p.parse_line("SetStopMode Fast").unwrap_err();
        assert!(e.to_string().contains("one of NoStop, Abrupt"), "{e}");
        assert_eq!(e.cmd(), "SetStopMode");
    }
}
