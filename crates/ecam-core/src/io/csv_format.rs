//! CSV tables: a `master,slave` header, one point per line; further columns
//! (`velocity,acceleration,jerk`, as [`curve_to_csv`] writes them) are
//! ignored on reading.

use core::fmt::Write as _;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use super::FormatError;
use crate::{CamCurve, CamPoint, Cursor, PointTable};

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
    let mut out = String::from("master,slave,velocity,acceleration,jerk\n");
    let mut cursor = Cursor::new();
    for m in masters {
        let k = curve.eval(m as f64, &mut cursor);
        let _ = writeln!(out, "{m},{},{},{},{}", k.s, k.v, k.a, k.j);
    }
    out
}

/// A whole number of counts or pulses: `12`, or `12.0` as spreadsheets write it.
fn whole(text: &str) -> Option<i64> {
    if let Ok(v) = text.parse::<i64>() {
        return Some(v);
    }
    let f = text.parse::<f64>().ok()?;
    // ±2^63 are exact in f64; i64 holds [-2^63, 2^63).
    const LIMIT: f64 = 9_223_372_036_854_775_808.0;
    let fits = f.fract() == 0.0 && (-LIMIT..LIMIT).contains(&f);
    fits.then_some(f as i64)
}

/// Reads a point table from CSV text with a `master,slave` header.
///
/// # Errors
/// [`FormatError::Csv`] with the line number for a missing header, a
/// missing column or a value that is not a whole number;
/// [`FormatError::Table`] when the points do not make a valid table.
pub fn from_csv(text: &str) -> Result<PointTable, FormatError> {
    // Spreadsheets on Windows start UTF-8 files with a byte-order mark.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let header_ok = match reader.headers() {
        Ok(h) => {
            h.get(0).is_some_and(|c| c.eq_ignore_ascii_case("master"))
                && h.get(1).is_some_and(|c| c.eq_ignore_ascii_case("slave"))
        }
        Err(_) => false,
    };
    if !header_ok {
        return Err(FormatError::Csv {
            line: 1,
            message: "the first line must be the header `master,slave`".to_string(),
        });
    }
    let mut points = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| FormatError::Csv {
            line: e.position().map_or(0, |p| p.line()),
            message: e.to_string(),
        })?;
        let line = record.position().map_or(0, |p| p.line());
        let field = |i: usize, name: &str| -> Result<i64, FormatError> {
            let text = record.get(i).unwrap_or("");
            whole(text).ok_or_else(|| FormatError::Csv {
                line,
                message: format!("{name} `{text}` is not a whole number"),
            })
        };
        points.push(CamPoint::new(field(0, "master")?, field(1, "slave")?));
    }
    Ok(PointTable::new(points)?)
}
