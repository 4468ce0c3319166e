//! JSON tables: a [`CamTable`] tagged by `kind` (see its documentation).

use std::string::{String, ToString};

use super::FormatError;
use crate::CamTable;

/// Writes `table` as pretty-printed JSON.
pub fn to_json(table: &CamTable) -> String {
    // Serialising plain integers, floats-free structs and strings cannot fail;
    // fall back to an empty object rather than panic.
    serde_json::to_string_pretty(table).unwrap_or_else(|_| "{}".to_string())
}

/// Reads a table written by [`to_json`] (or by hand). The table is validated
/// as its constructor would.
///
/// # Errors
/// [`FormatError::Json`] for malformed JSON, an unknown `kind`, or a table
/// its constructor refuses (the message carries the error code and section).
pub fn from_json(text: &str) -> Result<CamTable, FormatError> {
    serde_json::from_str(text).map_err(|e| FormatError::Json {
        message: super::error::plain_json_message(&e),
    })
}
