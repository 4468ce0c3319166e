//! File formats for cam tables (`std` feature): CSV and JSON, and table
//! files on disk chosen by extension.
//!
//! - [`to_csv`], [`from_csv`], [`curve_to_csv`]: point tables as CSV (the
//!   one CSV reader and its rules: [`TableFile::from_csv`]);
//! - [`to_json`], [`from_json`]: any [`crate::CamTable`] as JSON tagged by
//!   `kind`;
//! - [`TableFile`], [`AnyTable`]: a table with what its file adds (the
//!   synchronised zone, the generator, exact derivatives);
//! - [`read()`], [`write()`], [`FileFormat`]: files, by extension.

mod csv_format;
mod error;
mod files;
mod json;
mod table_file;

pub use csv_format::{curve_to_csv, from_csv, to_csv};
pub use error::{FileError, FormatError, json_syntax_message, plain_serde_message};
pub use files::{FileFormat, extension, read, write};
pub use json::{from_json, to_json};
pub use table_file::{AnyTable, Columns, TableFile};
