//! Table files on disk: the format chosen by the extension.
//!
//! `.csv` ([`TableFile::from_csv`]) or `.json` ([`AnyTable::from_json`]), in
//! any case (`T.CSV` is CSV).
//!
//! ```
//! use std::path::Path;
//! use ecam_core::io::{FileFormat, extension};
//!
//! assert_eq!(FileFormat::of(Path::new("cam.JSON"))?, FileFormat::Json);
//! assert_eq!(extension(Path::new("plot.SVG")).as_deref(), Some("svg"));
//! assert!(FileFormat::of(Path::new("cam.txt")).is_err());
//! # Ok::<(), ecam_core::io::FileError>(())
//! ```

use std::path::Path;
use std::string::String;

use super::{AnyTable, Columns, FileError, TableFile};

/// `path`'s extension in lower case (`T.CSV` and `t.csv` are the same format).
pub fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// Table file formats, chosen by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileFormat {
    /// Comma-separated values.
    Csv,
    /// JSON object.
    Json,
}

impl FileFormat {
    /// The format for `path`'s extension.
    ///
    /// # Errors
    /// [`FileError::Extension`] for extensions other than `csv` and `json`.
    pub fn of(path: &Path) -> Result<Self, FileError> {
        match extension(path).as_deref() {
            Some("csv") => Ok(Self::Csv),
            Some("json") => Ok(Self::Json),
            _ => Err(FileError::Extension {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// Reads a CSV or JSON table file, of any kind.
///
/// # Errors
/// A bad extension, an unreadable file, or text that is not a valid table
/// ([`FileError::Format`], whose source says what is wrong).
pub fn read(path: &Path) -> Result<AnyTable, FileError> {
    let format = FileFormat::of(path)?;
    let read_error = |source| FileError::Read {
        path: path.to_path_buf(),
        source,
    };
    // Bounded work: the size is checked before anything is read.
    let limit = crate::limits::MAX_TABLE_FILE_BYTES;
    let size = std::fs::metadata(path).map_err(read_error)?.len();
    if size > limit {
        return Err(read_error(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            std::format!("the file is {size} bytes; table files are limited to {limit} bytes"),
        )));
    }
    let text = std::fs::read_to_string(path).map_err(read_error)?;
    let parsed = match format {
        FileFormat::Csv => TableFile::from_csv(&text).map(AnyTable::Points),
        FileFormat::Json => AnyTable::from_json(&text),
    };
    parsed.map_err(|source| FileError::Format {
        path: path.to_path_buf(),
        source,
    })
}

/// Writes `file` to `path`, CSV or JSON by its extension.
///
/// # Errors
/// A bad extension or a failed write.
pub fn write(file: &TableFile, path: &Path, columns: Columns) -> Result<(), FileError> {
    let text = match FileFormat::of(path)? {
        FileFormat::Csv => file.to_csv(columns),
        FileFormat::Json => file.to_json(columns),
    };
    std::fs::write(path, text).map_err(|source| FileError::Write {
        path: path.to_path_buf(),
        source,
    })
}
