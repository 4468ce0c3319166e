//! The script language of `ecam pmd run`: one document-002 command per line.
//!
//! A line holds a command name and its arguments separated by blanks (or
//! commas). `'` starts a comment, and so do the typographic quotes `‘ ’`
//! that document 002's listing uses. A line holding only `…` or `...` is the
//! document's elision and is skipped. Numbers are decimal or `0x` hex, with
//! an optional sign; a name defined by `Define NAME VALUE` may stand for a
//! number (document 002 writes `WriteBuffer 2 cam_table_0`). Command and
//! parameter names ignore letter case.

use std::collections::HashMap;

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
pub struct ParseError {
    /// The command name as written (empty if the line had none).
    pub cmd: String,
    /// What is wrong, in words.
    pub message: String,
}

impl core::fmt::Display for ParseError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ParseError {}

/// Named values a command accepts besides numbers.
type Names = &'static [(&'static str, i64)];

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

/// Removes the comment from a line: `'`, `‘` or `’` to the end.
pub fn strip_comment(line: &str) -> &str {
    line.find(['\'', '‘', '’'])
        .map_or(line, |i| line.get(..i).unwrap_or(line))
}

/// Parses a number: decimal or `0x` hex, optional sign.
pub fn parse_number(text: &str) -> Option<i64> {
    let (negative, digits) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text.strip_prefix('+').unwrap_or(text)),
    };
    let magnitude = match digits
        .strip_prefix("0x")
        .or_else(|| digits.strip_prefix("0X"))
    {
        Some(hex) => i128::from_str_radix(hex, 16).ok()?,
        None if digits.bytes().all(|b| b.is_ascii_digit()) => digits.parse::<i128>().ok()?,
        None => return None,
    };
    i64::try_from(if negative { -magnitude } else { magnitude }).ok()
}

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
    fn error(&self, message: String) -> ParseError {
        ParseError {
            cmd: self.cmd.to_owned(),
            message,
        }
    }

    fn expect(&self, usage: &[&str]) -> Result<(), ParseError> {
        if self.words.len() == usage.len() {
            return Ok(());
        }
        let shape = if usage.is_empty() {
            String::from("no arguments")
        } else {
            usage.join(" ")
        };
        Err(self.error(format!(
            "{} takes {} argument{} ({shape}), got {}",
            self.cmd,
            usage.len(),
            if usage.len() == 1 { "" } else { "s" },
            self.words.len()
        )))
    }

    fn value(&self, i: usize, names: Names) -> Result<i64, ParseError> {
        let word = self.words.get(i).copied().unwrap_or_default();
        if let Some(n) = parse_number(word) {
            return Ok(n);
        }
        if let Some(&(_, v)) = names.iter().find(|(n, _)| n.eq_ignore_ascii_case(word)) {
            return Ok(v);
        }
        if let Some(&v) = self.symbols.get(word) {
            return Ok(v);
        }
        // A number too big for any register ("Tick 18446744073709551615") is
        // still a number: say it is out of range, not that it is unknown.
        let digits = word.trim_start_matches(['-', '+']);
        let hex = digits
            .strip_prefix("0x")
            .or_else(|| digits.strip_prefix("0X"));
        let numeric = match hex {
            Some(h) => !h.is_empty() && h.bytes().all(|b| b.is_ascii_hexdigit()),
            None => !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()),
        };
        if numeric {
            return Err(self.error(format!(
                "{}: {word} is out of range: numbers must fit a signed 64-bit value (and the command's own range)",
                self.cmd
            )));
        }
        let known: Vec<&str> = names.iter().map(|(n, _)| *n).collect();
        let hint = if known.is_empty() {
            String::from("give a number (decimal or 0x hex) or a name set by `Define NAME VALUE`")
        } else {
            format!(
                "give a number, one of {}, or a name set by `Define NAME VALUE`",
                known.join(", ")
            )
        };
        Err(self.error(format!(
            "{}: '{word}' is not a number or a known name: {hint}",
            self.cmd
        )))
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
        // A byte-order mark may open a script saved by a Windows editor.
        let code = strip_comment(line.trim_start_matches('\u{feff}')).trim();
        if code.is_empty() || code == "…" || code == "..." {
            return Ok(None);
        }
        let mut words = code
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|w| !w.is_empty());
        let cmd = words.next().unwrap_or_default();
        let a = Args {
            cmd,
            words: words.collect(),
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
                    return Err(a.error(format!(
                        "Define: '{symbol}' is not a name (letters, digits and _, not starting with a digit)"
                    )));
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
                    .ok_or_else(|| {
                        a.error(format!(
                            "Tick: {n} is out of range: the cycle count must be 0 to {limit}"
                        ))
                    })?;
                self.budget.cycles(n).map_err(|_| {
                    a.error(format!(
                        "Tick {n}: the script's Ticks add up to more than the {limit} cycles one run may take"
                    ))
                })?;
                Command::Tick(n)
            }
            _ => {
                return Err(a.error(format!(
                    "unknown command '{cmd}'",
                    cmd = ecam_core::excerpt::excerpt(cmd)
                )));
            }
        };
        if let Command::Define(symbol, value) = &command {
            self.symbols.insert(symbol.clone(), *value);
        }
        Ok(Some(command))
    }

    fn cam_param(a: &Args<'_>) -> Result<CamParam, ParseError> {
        let word = a.words.first().copied().unwrap_or_default();
        CamParam::parse(word).ok_or_else(|| {
            a.error(format!(
                "{}: unknown cam parameter '{word}': use 0 CamBufferID, 1 CamCounts, 2 CamStartCount, 3 CamSource, 4 CamOutputOffset or 5 CamInputOffset",
                a.cmd
            ))
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
            e.message.contains("add up to more than the 100000000"),
            "{e}"
        );
        assert_eq!(p.parse_line("Tick 0").unwrap(), Some(Command::Tick(0)));
    }

    #[test]
    fn symbols_need_a_definition() {
        let mut p = Parser::new();
        let err = p.parse_line("WriteBuffer 2 cam_table_0").unwrap_err();
        assert!(err.message.contains("Define"), "{err}");
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
        assert_eq!(e.message, "unknown command 'SetCame'");
        let e = p.parse_line("SetCam CamCounts").unwrap_err();
        assert_eq!(e.message, "SetCam takes 2 arguments (PARAM VALUE), got 1");
        let e = p.parse_line("GetCam CamSpeed").unwrap_err();
        assert!(e.message.contains("unknown cam parameter"));
        assert!(p.parse_line("Tick -1").is_err());
        assert!(p.parse_line("Update now").is_err());
        assert!(p.parse_line("Define 9x 1").is_err());
        // Too big for 64 bits: a number out of range, not an unknown name.
        let e = p.parse_line("Tick 18446744073709551615").unwrap_err();
        assert!(e.message.contains("out of range"), "{e}");
        assert!(!e.message.contains("not a number"), "{e}");
        let e = p
            .parse_line("WriteBuffer 0 0x1FFFFFFFFFFFFFFFF")
            .unwrap_err();
        assert!(e.message.contains("out of range"), "{e}");
    }

    #[test]
    fn numbers() {
        assert_eq!(parse_number("-0x10"), Some(-16));
        assert_eq!(parse_number("+7"), Some(7));
        assert_eq!(parse_number("1e3"), None);
        assert_eq!(parse_number("99999999999999999999"), None);
        assert_eq!(parse_number("-9223372036854775808"), Some(i64::MIN));
    }
}
