//! Reading a script: lines into [`Command`]s, every argument checked and
//! every table resolved before anything runs.

use core::num::NonZeroU64;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use ecam_core::PointTable;
use ecam_core::io::AnyTable;
use ecam_core::script_line::{NumberError, ScriptLine, parse_number};

use super::{Command, LineError, Problem, ScriptError};
use crate::{CamType, SingleTurn, UserUnit};

/// Axes of a script without an `Axes` line: document 001's master (0) and
/// slave (1).
pub const DEFAULT_AXES: usize = 2;

/// The most axes `Axes N` creates.
pub const MAX_AXES: usize = 256;

/// One command and the line it came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Line {
    /// Line number in the script, counting from 1.
    pub number: usize,
    /// The command.
    pub command: Command,
}

/// A parsed script: its commands, checked and with their tables read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Script {
    path: PathBuf,
    axis_count: usize,
    lines: Vec<Line>,
}

impl Script {
    /// Reads and parses the script file at `path`; table files and trace
    /// files it names are relative to its directory.
    ///
    /// # Errors
    /// The file cannot be read, or a line is not a valid command (the first
    /// such line, as `FILE:LINE: message`).
    pub fn read(path: impl AsRef<Path>) -> Result<Self, ScriptError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| ScriptError {
            path: path.to_path_buf(),
            line: None,
            problem: Problem::Read(e.to_string()),
        })?;
        Self::parse(&text, path)
    }

    /// Parses script `text`; `path` names it in messages and its directory
    /// is where relative table and trace paths start.
    ///
    /// # Errors
    /// The first line that is not a valid command.
    pub fn parse(text: &str, path: impl AsRef<Path>) -> Result<Self, ScriptError> {
        let path = path.as_ref();
        let mut parser = Parser {
            base_dir: path.parent().unwrap_or(Path::new("")),
            axis_count: DEFAULT_AXES,
            tables: BTreeMap::new(),
            budget: ecam_core::budget::Budget::per_run(),
        };
        let mut lines: Vec<Line> = Vec::new();
        for (index, text) in text.lines().enumerate() {
            let number = index.saturating_add(1);
            let first = lines.is_empty();
            let command = parser
                .parse_line(text, first)
                .map_err(|error| ScriptError::at(path, number, Problem::Line(error)))?;
            if let Some(command) = command {
                lines.push(Line { number, command });
            }
        }
        Ok(Self {
            path: path.to_path_buf(),
            axis_count: parser.axis_count,
            lines,
        })
    }

    /// The script's path, as given.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// How many axes the script works on (`Axes N`, or [`DEFAULT_AXES`]).
    pub fn axis_count(&self) -> usize {
        self.axis_count
    }

    /// The commands, in order.
    pub fn lines(&self) -> &[Line] {
        &self.lines
    }
}

struct Parser<'a> {
    base_dir: &'a Path,
    axis_count: usize,
    tables: BTreeMap<String, PointTable>,
    /// The cycles of the script's `Tick`s in all: one run's budget.
    budget: ecam_core::budget::Budget,
}

/// One line's command word and arguments.
struct Args<'a> {
    cmd: &'a str,
    words: Vec<&'a str>,
}

impl Args<'_> {
    fn expect(&self, usage: &'static [&'static str]) -> Result<(), LineError> {
        if self.words.len() == usage.len() {
            return Ok(());
        }
        Err(self.wrong_count(usage))
    }

    fn wrong_count(&self, usage: &'static [&'static str]) -> LineError {
        LineError::ArgumentCount {
            cmd: self.cmd.to_owned(),
            usage,
            got: self.words.len(),
        }
    }

    fn word(&self, i: usize) -> &str {
        self.words.get(i).copied().unwrap_or_default()
    }

    fn is_off(&self, i: usize) -> bool {
        self.word(i).eq_ignore_ascii_case("off")
    }

    /// A whole number (decimal or `0x` hex); `what` names it in messages.
    fn integer(&self, i: usize, what: &'static str) -> Result<i64, LineError> {
        let word = self.word(i);
        let (cmd, word_owned) = (self.cmd.to_owned(), word.to_owned());
        parse_number(word).map_err(|e| match e {
            NumberError::OutOfRange => LineError::NumberOutOfRange {
                cmd,
                what,
                word: word_owned,
            },
            NumberError::NotANumber => LineError::NotWhole {
                cmd,
                what,
                word: word_owned,
            },
        })
    }

    /// A number from `min` up to `max`, with the range in the message.
    fn bounded(&self, i: usize, what: &'static str, min: i64, max: i64) -> Result<i64, LineError> {
        let n = self.integer(i, what)?;
        if (min..=max).contains(&n) {
            Ok(n)
        } else {
            Err(LineError::OutOfRange {
                cmd: self.cmd.to_owned(),
                what,
                value: n,
                min,
                max,
            })
        }
    }

    /// A count of at least 1, or `Off`.
    fn count_or_off(&self, i: usize, what: &'static str) -> Result<Option<NonZeroU64>, LineError> {
        if self.is_off(i) {
            return Ok(None);
        }
        let n = self.integer(i, what)?;
        u64::try_from(n)
            .ok()
            .and_then(NonZeroU64::new)
            .map(Some)
            .ok_or_else(|| LineError::CountOrOff {
                cmd: self.cmd.to_owned(),
                what,
                value: n,
            })
    }
}

impl Parser<'_> {
    fn axis(&self, a: &Args<'_>, i: usize, what: &'static str) -> Result<usize, LineError> {
        let n = a.integer(i, what)?;
        match usize::try_from(n) {
            Ok(axis) if axis < self.axis_count => Ok(axis),
            _ => Err(LineError::NoSuchAxis {
                cmd: a.cmd.to_owned(),
                axis: n,
                count: self.axis_count,
            }),
        }
    }

    fn table_name(a: &Args<'_>) -> Result<String, LineError> {
        let name = a.word(0);
        let valid = name
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if valid {
            Ok(name.to_owned())
        } else {
            Err(LineError::TableName {
                cmd: a.cmd.to_owned(),
                name: name.to_owned(),
            })
        }
    }

    fn inline_table(a: &Args<'_>) -> Result<PointTable, LineError> {
        let values = a.words.get(1..).unwrap_or_default();
        if values.is_empty() || values.len() % 2 != 0 {
            return Err(LineError::Pairs {
                cmd: a.cmd.to_owned(),
                got: values.len(),
            });
        }
        let mut pairs = Vec::with_capacity(values.len() / 2);
        for i in (1..a.words.len()).step_by(2) {
            let master = a.integer(i, "master position")?;
            let slave = a.integer(i.saturating_add(1), "slave position")?;
            pairs.push((master, slave));
        }
        PointTable::from_pairs(&pairs).map_err(|error| LineError::Table {
            cmd: a.cmd.to_owned(),
            error,
        })
    }

    fn file_table(&self, cmd: &str, file: &str) -> Result<PointTable, LineError> {
        let path = self.base_dir.join(file);
        match ecam_core::io::read(&path) {
            Ok(AnyTable::Points(file)) => Ok(file.table),
            Ok(other) => Err(LineError::NotPoints {
                cmd: cmd.to_owned(),
                path,
                kind: other.kind(),
            }),
            Err(e) => {
                let mut reason = e.to_string();
                let mut source = std::error::Error::source(&e);
                while let Some(s) = source {
                    reason.push_str(&format!(": {s}"));
                    source = s.source();
                }
                Err(LineError::TableFile {
                    cmd: cmd.to_owned(),
                    reason,
                })
            }
        }
    }

    /// Parses one line; `Ok(None)` for a blank or comment-only line.
    /// `first` says no command came before.
    fn parse_line(&mut self, line: &str, first: bool) -> Result<Option<Command>, LineError> {
        let Some(line) = ScriptLine::read(line) else {
            return Ok(None);
        };
        let cmd = line.command();
        let a = Args {
            cmd,
            words: line.args().to_vec(),
        };
        let command = match cmd.to_ascii_lowercase().as_str() {
            "axes" => {
                a.expect(&["N"])?;
                if !first {
                    return Err(LineError::AxesNotFirst);
                }
                let n = a.bounded(0, "the axis count", 1, MAX_AXES as i64)?;
                let n = usize::try_from(n).unwrap_or(DEFAULT_AXES);
                self.axis_count = n;
                Command::Axes(n)
            }
            "setsingleturn" => {
                a.expect(&["AXIS", "COUNTS|Off"])?;
                let axis = self.axis(&a, 0, "axis")?;
                let turn = a
                    .count_or_off(1, "the single-turn encoder range")?
                    .map(|counts| SingleTurn::new(counts.get()))
                    .transpose()
                    .map_err(|error| LineError::Refused {
                        cmd: cmd.to_owned(),
                        error,
                    })?;
                Command::SetSingleTurn { axis, turn }
            }
            "setuserunit" => {
                a.expect(&["AXIS", "PULSES"])?;
                let axis = self.axis(&a, 0, "axis")?;
                let pulses = a.integer(1, "pulses per user unit")?;
                let unit = u64::try_from(pulses)
                    .ok()
                    .and_then(|p| UserUnit::new(p).ok())
                    .ok_or_else(|| LineError::UserUnit {
                        cmd: cmd.to_owned(),
                        pulses,
                    })?;
                Command::SetUserUnit { axis, unit }
            }
            "setmaxmasterstep" => {
                a.expect(&["AXIS", "COUNTS|Off"])?;
                let axis = self.axis(&a, 0, "axis")?;
                let step = a.count_or_off(1, "the largest master step")?;
                Command::SetMaxMasterStep { axis, step }
            }
            "setcommandposition" => {
                a.expect(&["AXIS", "POSITION"])?;
                Command::SetCommandPosition {
                    axis: self.axis(&a, 0, "axis")?,
                    position: a.integer(1, "position")?,
                }
            }
            "moveto" => {
                a.expect(&["AXIS", "POSITION", "CYCLES"])?;
                let axis = self.axis(&a, 0, "axis")?;
                let position = a.integer(1, "position")?;
                let cycles = a.bounded(2, "the cycle count", 0, i64::from(u32::MAX))?;
                Command::MoveTo {
                    axis,
                    position,
                    cycles: u32::try_from(cycles).unwrap_or(u32::MAX),
                }
            }
            "ecamtable" => {
                if a.words.is_empty() {
                    return Err(a.wrong_count(&["NAME MASTER SLAVE MASTER SLAVE …"]));
                }
                let name = Self::table_name(&a)?;
                let table = Self::inline_table(&a)?;
                self.tables.insert(name.clone(), table.clone());
                Command::ECamTable { name, table }
            }
            "ecamtablefile" => {
                // The path is the rest of the line: it may hold blanks and commas.
                let rest = line.rest();
                let (name_word, file) = rest
                    .split_once(char::is_whitespace)
                    .map_or((rest, ""), |(n, f)| (n, f.trim()));
                let named = Args {
                    cmd,
                    words: vec![name_word],
                };
                if name_word.is_empty() || file.is_empty() {
                    return Err(LineError::TableFileArgs {
                        cmd: cmd.to_owned(),
                    });
                }
                let name = Self::table_name(&named)?;
                let table = self.file_table(cmd, file)?;
                self.tables.insert(name.clone(), table.clone());
                Command::ECamTable { name, table }
            }
            "startecam" => {
                a.expect(&["MASTER", "SLAVE", "Normal|Periodic|Repeat", "TABLE"])?;
                let master = self.axis(&a, 0, "master axis")?;
                let slave = self.axis(&a, 1, "slave axis")?;
                if master == slave {
                    return Err(LineError::OwnMaster {
                        cmd: cmd.to_owned(),
                        axis: master,
                    });
                }
                let cam_type = match a.word(2).to_ascii_lowercase().as_str() {
                    "normal" => CamType::Normal,
                    "periodic" => CamType::Periodic,
                    "repeat" => CamType::Repeat,
                    other => {
                        return Err(LineError::CamType {
                            cmd: cmd.to_owned(),
                            word: other.to_owned(),
                        });
                    }
                };
                let table_name = a.word(3).to_owned();
                let table = self.tables.get(&table_name).cloned().ok_or_else(|| {
                    LineError::NoSuchTable {
                        cmd: cmd.to_owned(),
                        name: table_name.clone(),
                        known: self.tables.keys().cloned().collect(),
                    }
                })?;
                Command::StartECam {
                    master,
                    slave,
                    cam_type,
                    table_name,
                    table,
                }
            }
            "stopecam" => {
                a.expect(&["SLAVE"])?;
                Command::StopECam {
                    slave: self.axis(&a, 0, "slave axis")?,
                }
            }
            "tick" => {
                a.expect(&["N"])?;
                let limit = ecam_core::limits::MAX_SIMULATED_TICKS as i64;
                let n = a.bounded(0, "the cycle count", 0, limit)?;
                let n = u64::try_from(n).unwrap_or_default();
                self.budget
                    .cycles(n)
                    .map_err(|_| LineError::TicksOverBudget { ticks: n, limit })?;
                Command::Tick(n)
            }
            "getcommandposition" => {
                a.expect(&["AXIS"])?;
                Command::GetCommandPosition {
                    axis: self.axis(&a, 0, "axis")?,
                }
            }
            "getsingleturn" => {
                a.expect(&["AXIS"])?;
                Command::GetSingleTurn {
                    axis: self.axis(&a, 0, "axis")?,
                }
            }
            "getecamstatus" => {
                a.expect(&["SLAVE"])?;
                Command::GetECamStatus {
                    slave: self.axis(&a, 0, "slave axis")?,
                }
            }
            "trace" => {
                if a.words.is_empty() {
                    return Err(a.wrong_count(&["PATH [AXIS …] or Off"]));
                }
                if a.words.len() == 1 && a.is_off(0) {
                    Command::TraceOff
                } else {
                    let axes = (1..a.words.len())
                        .map(|i| self.axis(&a, i, "axis"))
                        .collect::<Result<Vec<_>, _>>()?;
                    Command::Trace {
                        path: self.base_dir.join(a.word(0)),
                        axes,
                    }
                }
            }
            _ => {
                return Err(LineError::UnknownCommand {
                    cmd: cmd.to_owned(),
                });
            }
        };
        Ok(Some(command))
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Script, ScriptError> {
        Script::parse(text, "t.mc")
    }

    fn only(text: &str) -> Command {
        let script = parse(text).unwrap();
        script.lines().first().unwrap().command.clone()
    }

    fn error(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    #[test]
    fn messages_quote_a_short_excerpt_of_a_huge_line() {
        let huge = "Q".repeat(100_000);
        let e = error(&format!("{huge} 1"));
        assert!(e.len() < 120, "{} bytes: {e}", e.len());
        assert!(e.starts_with("t.mc:1: unknown command 'QQ"), "{e}");
        assert!(e.contains("(100000 bytes)"), "{e}");
        let e = error(&format!("Axes 2\nECAMTable 9{huge} 0 0 10 10"));
        assert!(e.len() < 250, "{} bytes: {e}", e.len());
        assert!(e.starts_with("t.mc:2: ECAMTable:"), "{e}");
    }

    #[test]
    fn commands_parse() {
        assert_eq!(
            only("setsingleturn 0 30000 ' master"),
            Command::SetSingleTurn {
                axis: 0,
                turn: Some(SingleTurn::new(30000).unwrap())
            }
        );
        assert_eq!(
            only("SetSingleTurn 0 Off"),
            Command::SetSingleTurn {
                axis: 0,
                turn: None
            }
        );
        assert_eq!(
            only("MoveTo 0 -75000 750"),
            Command::MoveTo {
                axis: 0,
                position: -75000,
                cycles: 750
            }
        );
        let script =
            parse("ECAMTable doc 0 500, 10000,1500 20000 1000\nStartECAM 0 1 repeat doc").unwrap();
        let Command::StartECam {
            cam_type, table, ..
        } = &script.lines()[1].command
        else {
            panic!("{script:?}");
        };
        assert_eq!(*cam_type, CamType::Repeat);
        assert_eq!(table.points().len(), 3);
        assert_eq!(only("Trace Off"), Command::TraceOff);
        assert_eq!(
            only("Trace out.csv 1"),
            Command::Trace {
                path: PathBuf::from("out.csv"),
                axes: vec![1]
            }
        );
    }

    #[test]
    fn lines_read_as_in_motion_processor_scripts() {
        // The shared reader: hex numbers, typographic-quote comments and the
        // listings' elision, which this face did not take before.
        assert_eq!(
            only("…\nMoveTo 0, -0x10 0X2 ‘ a comment"),
            Command::MoveTo {
                axis: 0,
                position: -16,
                cycles: 2
            }
        );
        assert!(error("MoveTo 0 0x 1").contains("position '0x' is not a whole number"));
        assert!(error("MoveTo 0 0x8000000000000000 1").contains("out of range (a signed 64-bit"));
    }

    #[test]
    fn axes_come_first_and_bound_the_axis_numbers() {
        assert_eq!(
            parse("Axes 4\nGetCommandPosition 3").unwrap().axis_count(),
            4
        );
        assert_eq!(
            error("GetCommandPosition 2"),
            "t.mc:1: GetCommandPosition: no axis 2: axes are numbered 0 to 1 (`Axes N` as the first command sets how many)"
        );
        assert!(error("Tick 1\nAxes 4").starts_with("t.mc:2: Axes must be"));
        assert!(error("Axes 0").contains("out of range: 1 to 256"));
    }

    #[test]
    fn bad_lines_say_why() {
        assert_eq!(error("\n\nFoo 1"), "t.mc:3: unknown command 'Foo'");
        assert_eq!(error("Tick"), "t.mc:1: Tick takes N, got 0 arguments");
        assert_eq!(
            error("Tick -1"),
            "t.mc:1: Tick: the cycle count -1 is out of range: 0 to 100000000"
        );
        assert!(error("Tick 99999999999999999999").contains("out of range"));
        assert!(error("SetCommandPosition 0 1.5").contains("'1.5' is not a whole number"));
        assert!(error("SetSingleTurn 0 0").contains("at least 1 (or Off)"));
        assert!(error("SetUserUnit 1 0").contains("at least 1 pulse"));
        assert!(error("MoveTo 0 5 4294967296").contains("out of range"));
        assert!(error("ECAMTable t 0 0 10").contains("MASTER SLAVE pairs"));
        assert!(error("ECAMTable 9t 0 0 10 1").contains("not a table name"));
        assert!(error("ECAMTable t 10 0 0 1").starts_with("t.mc:1: ECAMTable: "));
        assert!(error("StartECAM 0 1 Repeat t").contains("no table is defined yet"));
        assert!(error("ECAMTable a 0 0 1 1\nStartECAM 0 1 Repeat b").contains("defined so far: a"));
        assert!(
            error("ECAMTable a 0 0 1 1\nStartECAM 0 1 Cyclic a").contains("unknown E-CAM type")
        );
        assert!(error("ECAMTable a 0 0 1 1\nStartECAM 1 1 Normal a").contains("its own master"));
        assert!(error("ECAMTableFile t no-such-file.csv").contains("cannot read table file"));
        assert!(error("ECAMTableFile t table.txt").contains(".csv or .json"));
    }
}
