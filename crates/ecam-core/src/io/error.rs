//! What can go wrong reading a table file.

use std::string::String;

use crate::TableError;

/// A table file that could not be read.
#[derive(Clone, Debug, PartialEq)]
pub enum FormatError {
    /// A CSV line is malformed (`line` counts from 1, the header included).
    Csv {
        /// Line number in the file.
        line: u64,
        /// What is wrong with it.
        message: String,
    },
    /// The JSON text is malformed or does not describe a table.
    Json {
        /// The parser's message, with line and column.
        message: String,
    },
    /// The file was read but the table it holds is invalid.
    Table(TableError),
}

impl core::fmt::Display for FormatError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Csv { line, message } => write!(f, "CSV line {line}: {message}"),
            Self::Json { message } => write!(f, "JSON: {message}"),
            Self::Table(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for FormatError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Table(e) => Some(e),
            _ => None,
        }
    }
}

impl From<TableError> for FormatError {
    fn from(e: TableError) -> Self {
        Self::Table(e)
    }
}
