//! Fuzzing harnesses (`std` feature): one function per reader a user can
//! feed, shared by the cargo-fuzz targets in `fuzz/` and by the stable
//! property tests in `tests/it/fuzz.rs`, so both exercise the same code.
//!
//! Each takes arbitrary bytes and must return without panicking, whatever
//! the bytes; a panic is a bug in the reader.

use crate::io::{self, AnyTable, Columns, TableFile};
use crate::{CamCurve, Cursor};

/// Feeds `data` to the CSV table reader ([`TableFile::from_csv`]); a table
/// it accepts is evaluated, written back and read again.
pub fn table_csv(data: &[u8]) {
    let Ok(text) = core::str::from_utf8(data) else {
        return;
    };
    if let Ok(file) = TableFile::from_csv(text) {
        exercise_file(&file);
    }
}

/// Feeds `data` to the JSON table readers ([`AnyTable::from_json`], as
/// [`io::read`] does for any table kind, and [`io::from_json`]); a table
/// they accept is evaluated and written back.
pub fn table_json(data: &[u8]) {
    let Ok(text) = core::str::from_utf8(data) else {
        return;
    };
    if let Ok(table) = AnyTable::from_json(text) {
        if let AnyTable::Points(file) = &table {
            exercise_file(file);
        }
        let _ = table.kind();
        exercise_curve(&*table.into_curve());
    }
    if let Ok(table) = io::from_json(text) {
        let written = io::to_json(&table);
        // What was written must read back.
        assert!(
            io::from_json(&written).is_ok(),
            "written table does not read back: {written}"
        );
    }
}

/// Writes `file` both ways and reads the text back; evaluates its curve.
fn exercise_file(file: &TableFile) {
    let _ = file.kinematics();
    for columns in [Columns::Minimal, Columns::Full] {
        let csv = file.to_csv(columns);
        assert!(
            TableFile::from_csv(&csv).is_ok(),
            "written CSV does not read back: {csv}"
        );
        let json = file.to_json(columns);
        assert!(
            AnyTable::from_json(&json).is_ok(),
            "written JSON does not read back: {json}"
        );
    }
    exercise_curve(&file.table);
}

/// Evaluates `curve` at its ends, inside and outside its cycle.
fn exercise_curve(curve: &dyn CamCurve) {
    let first = curve.master_first() as f64;
    let last = curve.master_last() as f64;
    let mut cursor = Cursor::default();
    for master in [
        first - 1.0,
        first,
        first + (last - first) / 3.0,
        (first + last) / 2.0,
        last,
        last + 1.0,
    ] {
        let _ = curve.eval(master, &mut cursor);
        let _ = curve.position(master, &mut cursor);
    }
    let _ = (curve.master_span(), curve.stroke(), curve.segment_count());
}
