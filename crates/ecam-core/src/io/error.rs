//! What can go wrong reading a table file: [`FormatError`] for its text,
//! [`FileError`] for the file around it.
//!
//! The messages are what `ecam` prints (a [`FileError`] followed by its
//! source, `: `-separated), so each names what to fix.

use std::fmt;
use std::format;
use std::path::PathBuf;
use std::string::{String, ToString};

use crate::TableError;

/// Table text that could not be read.
#[derive(Clone, Debug, PartialEq)]
pub enum FormatError {
    /// The CSV header line cannot be read.
    CsvHeader {
        /// The CSV parser's message.
        message: String,
    },
    /// The CSV header lacks a column every table needs.
    MissingColumn {
        /// `master` or `slave`.
        column: &'static str,
    },
    /// A CSV row is malformed (e.g. its field count differs from the header's).
    CsvRow {
        /// Line of the file, counting from 1 (header and comments counted).
        line: u64,
        /// The line, excerpted.
        text: String,
        /// The CSV parser's message.
        message: String,
    },
    /// A position is not a whole number of counts or pulses.
    NotAnInteger {
        /// Line of the file, counting from 1.
        line: u64,
        /// `master` or `slave`.
        column: &'static str,
        /// The text found.
        text: String,
    },
    /// A derivative column holds something other than a finite number.
    NotANumber {
        /// Line of the file, counting from 1.
        line: u64,
        /// `velocity`, `acceleration` or `jerk`.
        column: &'static str,
        /// The text found.
        text: String,
    },
    /// `ecam_core`'s JSON (tagged by `kind`) is malformed or does not
    /// describe a valid table.
    Json {
        /// The parser's message, with line and column (and, for a table
        /// its constructor refuses, the error code and section).
        message: String,
    },
    /// A JSON text that is neither a table file's object nor `ecam_core`'s
    /// tagged JSON.
    NotATable {
        /// The table-file parser's message, with line and column.
        message: String,
    },
    /// A synchronised zone whose low end is above its high end.
    SyncZone {
        /// Low end (master counts).
        low: i64,
        /// High end (master counts).
        high: i64,
    },
    /// A CSV table whose point on `line` the table checks refuse (a master
    /// not above the one before, a value out of range).
    TableLine {
        /// Line of the file, counting from 1.
        line: u64,
        /// The line, excerpted.
        text: String,
        /// What the table checks say (with the PLC's error code).
        error: TableError,
    },
    /// The text was read but the table it holds is invalid.
    Table(TableError),
}

impl fmt::Display for FormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::CsvHeader { message } => write!(f, "cannot read the CSV header: {message}"),
            Self::MissingColumn { column } => write!(
                f,
                "the CSV header needs a `{column}` column (e.g. `master,slave`)"
            ),
            Self::CsvRow {
                line,
                text,
                message,
            } => write!(f, "line {line}: `{text}`: {message}"),
            Self::NotAnInteger { line, column, text } => {
                write!(f, "line {line}: {column} `{text}` is not an integer")
            }
            Self::NotANumber { line, column, text } => {
                write!(f, "line {line}: {column} `{text}` is not a number")
            }
            Self::TableLine { line, text, error } => {
                write!(f, "line {line}: `{text}`: {error}")
            }
            Self::Json { message } => write!(f, "JSON: {message}"),
            Self::NotATable { message } => write!(f, "not a table JSON object: {message}"),
            Self::SyncZone { low, high } => {
                write!(f, "sync zone low {low} is above high {high}")
            }
            Self::Table(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for FormatError {
    // `Table` shows the table error itself (it has no source of its own):
    // naming it again as the source would print it twice in a chain.
}

impl From<TableError> for FormatError {
    fn from(e: TableError) -> Self {
        Self::Table(e)
    }
}

/// A table file that could not be read or written.
#[derive(Debug)]
pub enum FileError {
    /// The path's extension names no table format.
    Extension {
        /// The path given.
        path: PathBuf,
    },
    /// The file cannot be read.
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file was read but its text is not a valid table.
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong with the text.
        source: FormatError,
    },
    /// The file cannot be written.
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Extension { path } => {
                write!(f, "table file {} must end in .csv or .json", path.display())
            }
            Self::Read { path, .. } => write!(f, "cannot read table file {}", path.display()),
            Self::Format { path, .. } => write!(f, "in table file {}", path.display()),
            Self::Write { path, .. } => write!(f, "cannot write table file {}", path.display()),
        }
    }
}

impl std::error::Error for FileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Extension { .. } => None,
            Self::Read { source, .. } | Self::Write { source, .. } => Some(source),
            Self::Format { source, .. } => Some(source),
        }
    }
}

/// A serde_json error in the words of the file's author: Rust type names
/// (`i64`, `f64`, `u16`…) become what they mean.
pub(crate) fn plain_json_message(e: &serde_json::Error) -> String {
    plain_serde_message(&e.to_string())
}

/// Why `text` is not JSON, in the words of its author rather than the
/// parser's: where it stops being JSON (line and column) and whether it
/// ended too early. For HTTP request bodies and other JSON a user types.
pub fn json_syntax_message(e: &serde_json::Error) -> String {
    let at = format!("line {}, column {}", e.line(), e.column());
    match e.classify() {
        serde_json::error::Category::Eof => format!("it ends before the JSON is complete ({at})"),
        serde_json::error::Category::Syntax => format!("it stops being JSON at {at}"),
        serde_json::error::Category::Io => format!("it cannot be read ({at})"),
        serde_json::error::Category::Data => plain_json_message(e),
    }
}

/// A serde message (JSON, TOML, parameter maps) in the words of the input's
/// author: `expected i64` becomes `expected a whole number`, and so on for
/// the other Rust number types.
pub fn plain_serde_message(message: &str) -> String {
    // serde and TOML quote the input (a value, a whole line): cut it.
    let mut text = crate::excerpt::cut_quotes(message);
    for (rust, plain) in [
        ("expected i64", "expected a whole number"),
        ("expected i32", "expected a whole number"),
        ("expected i16", "expected a whole number"),
        ("expected u64", "expected a whole number, 0 or more"),
        ("expected u32", "expected a whole number, 0 or more"),
        ("expected u16", "expected a whole number, 0 or more"),
        ("expected usize", "expected a whole number, 0 or more"),
        ("expected f64", "expected a number"),
        ("expected f32", "expected a number"),
    ] {
        text = text.replace(rust, plain);
    }
    text
}
