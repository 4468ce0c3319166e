//! File formats for cam tables (`std` feature): CSV and JSON.

mod csv_format;
mod error;
mod json;

pub use csv_format::{curve_to_csv, from_csv, to_csv};
pub use error::FormatError;
pub use json::{from_json, to_json};
