//! CSV tables: one reader, one set of rules, for `ecam` and the library
//! (the rules: [`TableFile::from_csv`]).
//!
//! ```
//! use ecam_core::io::{from_csv, to_csv};
//! use ecam_core::PointTable;
//!
//! let table = from_csv("# exported\nmaster, slave\n0, 0\n100.0, 50\n")?;
//! assert_eq!(table, PointTable::from_pairs(&[(0, 0), (100, 50)])?);
//! assert_eq!(to_csv(&table), "master,slave\n0,0\n100,50\n");
//! assert_eq!(
//!     from_csv("master,slave\n0,0\n10,1.5\n").unwrap_err().to_string(),
//!     "line 3: slave `1.5` is not an integer"
//! );
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use core::fmt::Write as _;
use std::string::{String, ToString};
use std::vec::Vec;

use super::FormatError;
use super::table_file::{Columns, TableFile};
use crate::{CamCurve, CamPoint, Cursor, Kinematics, PointTable, TableError};

/// The header of a table with its derivatives.
const FULL_HEADER: &str = "master,slave,velocity,acceleration,jerk";

/// Writes `table` as `master,slave` lines under that header.
pub fn to_csv(table: &PointTable) -> String {
    let mut out = String::from("master,slave\n");
    for p in table.points() {
        // Writing to a String cannot fail.
        let _ = writeln!(out, "{},{}", p.master, p.slave);
    }
    out
}

/// Writes `curve` evaluated at each of `masters` with all derivatives:
/// header `master,slave,velocity,acceleration,jerk`, derivatives with
/// respect to the master in counts.
pub fn curve_to_csv(curve: &impl CamCurve, masters: impl IntoIterator<Item = i64>) -> String {
    let mut out = String::from(FULL_HEADER);
    out.push('\n');
    let mut cursor = Cursor::new();
    for m in masters {
        let k = curve.eval(m as f64, &mut cursor);
        let _ = writeln!(out, "{m},{},{},{},{}", k.s, k.v, k.a, k.j);
    }
    out
}

/// The csv crate's message without its own position (the caller names
/// the line): `found record with 3 fields, but the previous record has 2
/// fields`.
fn plain_csv_message(e: &csv::Error) -> String {
    match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => std::format!("{len} fields, but the header has {expected_len}"),
        _ => e.to_string(),
    }
}

/// Reads a point table from CSV text (the rules: [`TableFile::from_csv`]);
/// derivative columns are checked, then dropped.
///
/// # Errors
/// As [`TableFile::from_csv`].
pub fn from_csv(text: &str) -> Result<PointTable, FormatError> {
    TableFile::from_csv(text).map(|file| file.table)
}

impl TableFile {
    /// Reads CSV text, keeping the derivative columns when all three are
    /// present. The rules (the only CSV reader, for `ecam` and the library):
    ///
    /// Reading:
    /// - a header line naming the columns (any order, any case); `master` and
    ///   `slave` are required, `velocity,acceleration,jerk` are read when all
    ///   three are present, any other column is ignored;
    /// - one point per line, every line with as many fields as the header;
    /// - positions are whole numbers; a float with no fractional part (`1000.0`,
    ///   as spreadsheets write it) is accepted below 9·10¹⁵, where a float still
    ///   holds every integer;
    /// - derivatives are finite numbers;
    /// - spaces around fields, `#` comment lines and a UTF-8 byte-order mark are
    ///   accepted.
    ///
    /// Errors name the line of the file (counting from 1, header and
    /// comments included) and quote the value or, excerpted, the line.
    ///
    /// # Errors
    /// [`FormatError::MissingColumn`], [`FormatError::CsvHeader`],
    /// [`FormatError::CsvRow`], [`FormatError::NotAnInteger`] and
    /// [`FormatError::NotANumber`] naming the data row, or
    /// [`FormatError::Table`] when the points do not make a valid table.
    pub fn from_csv(text: &str) -> Result<Self, FormatError> {
        // The csv reader drops a UTF-8 byte-order mark before the header.
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        let headers = reader
            .headers()
            .map_err(|e| FormatError::CsvHeader {
                message: e.to_string(),
            })?
            .clone();
        let column = |name: &'static str| {
            headers
                .iter()
                .position(|h| h.eq_ignore_ascii_case(name))
                .ok_or(FormatError::MissingColumn { column: name })
        };
        let (mi, si) = (column("master")?, column("slave")?);
        let derivative_columns = match (column("velocity"), column("acceleration"), column("jerk"))
        {
            (Ok(v), Ok(a), Ok(j)) => Some((v, a, j)),
            _ => None,
        };
        let mut kinematics = Vec::new();
        let mut points = Vec::new();
        // The file line each point was read from, for the table checks.
        let mut lines = Vec::new();
        // The csv crate's line count skips comment lines, and a record's
        // position is where the reader went looking for it (before the
        // comment and blank lines it passed): count from its byte, then
        // pass those lines too.
        let line_at = |position: Option<&csv::Position>| {
            let byte = position.map_or(0, |p| usize::try_from(p.byte()).unwrap_or(usize::MAX));
            let before = text.get(..byte).unwrap_or(text);
            let first = before.bytes().filter(|&b| b == b'\n').count();
            let passed = text
                .lines()
                .skip(first)
                .take_while(|l| l.trim().is_empty() || l.trim_start().starts_with('#'))
                .count();
            (first + passed) as u64 + 1
        };
        let quoted = |line: u64| {
            let at = usize::try_from(line.saturating_sub(1)).unwrap_or(usize::MAX);
            crate::excerpt::excerpt(text.lines().nth(at).unwrap_or_default().trim()).to_string()
        };
        for record in reader.records() {
            let record = record.map_err(|e| {
                let line = line_at(e.position());
                FormatError::CsvRow {
                    line,
                    text: quoted(line),
                    message: plain_csv_message(&e),
                }
            })?;
            let line = line_at(record.position());
            let raw = |i: usize| record.get(i).unwrap_or("");
            let position = |i: usize, column: &'static str| {
                parse_position(raw(i)).ok_or_else(|| FormatError::NotAnInteger {
                    line,
                    column,
                    text: crate::excerpt::excerpt(raw(i)).to_string(),
                })
            };
            let point = CamPoint::new(position(mi, "master")?, position(si, "slave")?);
            if let Some((vi, ai, ji)) = derivative_columns {
                let real = |i: usize, column: &'static str| {
                    raw(i)
                        .parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| FormatError::NotANumber {
                            line,
                            column,
                            text: crate::excerpt::excerpt(raw(i)).to_string(),
                        })
                };
                kinematics.push(Kinematics {
                    s: point.slave as f64,
                    v: real(vi, "velocity")?,
                    a: real(ai, "acceleration")?,
                    j: real(ji, "jerk")?,
                });
            }
            points.push(point);
            lines.push(line);
        }
        let table = PointTable::new(points).map_err(|error| {
            // Name the line of the point the checks refused.
            let section = match error {
                TableError::MasterNotIncreasing { section }
                | TableError::ValueOutOfRange { section } => Some(section),
                _ => None,
            };
            match section.and_then(|k| lines.get(k)) {
                Some(&line) => FormatError::TableLine {
                    line,
                    text: quoted(line),
                    error,
                },
                None => FormatError::Table(error),
            }
        })?;
        Ok(Self {
            table,
            sync: None,
            generator: None,
            kinematics: derivative_columns.map(|_| kinematics),
            segments: None,
        })
    }

    /// The CSV text of this table: `master,slave` lines, or with
    /// [`Columns::Full`] also `velocity,acceleration,jerk` (the known ones,
    /// or estimates: see [`TableFile::kinematics`]).
    pub fn to_csv(&self, columns: Columns) -> String {
        match columns {
            Columns::Minimal => to_csv(&self.table),
            Columns::Full => {
                let mut out = String::from(FULL_HEADER);
                out.push('\n');
                for (p, k) in self.table.points().iter().zip(self.kinematics()) {
                    // `+ 0.0` turns a negative zero into 0.
                    let _ = writeln!(
                        out,
                        "{},{},{},{},{}",
                        p.master,
                        p.slave,
                        k.v + 0.0,
                        k.a + 0.0,
                        k.j + 0.0
                    );
                }
                out
            }
        }
    }
}

/// Integer positions; a float with no fractional part (e.g. `1000.0`) is accepted.
fn parse_position(raw: &str) -> Option<i64> {
    if let Ok(v) = raw.parse::<i64>() {
        return Some(v);
    }
    let f: f64 = raw.parse().ok()?;
    // Beyond 2^53 a float no longer holds every integer.
    (f.fract() == 0.0 && f.abs() < 9.0e15).then_some(f as i64)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn sample() -> TableFile {
        TableFile {
            table: PointTable::from_pairs(&[(0, 0), (50, 100), (100, 200)]).unwrap(),
            sync: Some((10, 20)),
            generator: Some("test".into()),
            kinematics: None,
            segments: None,
        }
    }

    #[test]
    fn csv_round_trip() {
        let text = sample().to_csv(Columns::Full);
        assert!(text.starts_with("master,slave,velocity,acceleration,jerk\n0,0,2,0,0\n"));
        let back = TableFile::from_csv(&text).unwrap();
        assert_eq!(back.table, sample().table);
        assert_eq!(back.kinematics.unwrap()[1].v, 2.0);
        let minimal = TableFile::from_csv("master,slave\n0,0\n10,5\n").unwrap();
        assert!(minimal.kinematics.is_none());
        assert_eq!(minimal.kinematics()[0].v, 0.5);
        assert_eq!(
            sample().to_csv(Columns::Minimal),
            "master,slave\n0,0\n50,100\n100,200\n"
        );
    }

    #[test]
    fn csv_errors_name_the_problem() {
        let err = TableFile::from_csv("m,s\n0,0\n").unwrap_err();
        assert!(err.to_string().contains("master"));
        let err = TableFile::from_csv("master,slave\n0,0\n1,x\n").unwrap_err();
        assert!(err.to_string().contains("line 3: slave `x`"));
        let err = TableFile::from_csv("master,slave\n0,0\n0,1\n").unwrap_err();
        assert!(err.to_string().contains("6782"));
    }

    #[test]
    fn columns_are_found_by_name() {
        let t = from_csv("\u{feff}Slave,note,MASTER\n0,a,0\n5,b,10\n").unwrap();
        assert_eq!(t, PointTable::from_pairs(&[(0, 0), (10, 5)]).unwrap());
    }

    #[test]
    fn float_positions_must_be_whole() {
        assert_eq!(parse_position("1000.0"), Some(1000));
        assert_eq!(parse_position("-3"), Some(-3));
        assert_eq!(parse_position("1.5"), None);
        assert_eq!(parse_position("1e16"), None);
    }
}
