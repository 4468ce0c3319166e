//! The designer page's table endpoints: reading a table file the user
//! uploads, checking a point table the user edits, writing a table as a
//! file, and the limits and option names the page's forms offer. JSON in,
//! JSON out, no sockets (`ecam serve` routes them).
//!
//! The page keeps no copy of these facts: the file formats are
//! [`ecam_core::io`]'s, the checks the core's (with their error codes), the
//! impulses [`ecam_core::table::steps`]', the rounding note
//! [`TableReport::note`](crate::TableReport::note)'s.

use ecam_core::generator::key_points::{CurveType, MAX_KEY_POINTS};
use ecam_core::io::{AnyTable, Columns, FileFormat, TableFile};
use ecam_core::table::steps::Steps;
use ecam_core::table::{Summary, derivatives};
use ecam_core::{Kinematics, PointTable, register_image};
use serde_json::{Value, json};

use crate::designer::MAX_LAW_POINTS;

/// `GET /api/limits`: what the page's forms may hold and the names they
/// offer: points of a DECAM table (2 to 512), key points (at most 10) and
/// their curves, law samples.
pub fn limits_json() -> Value {
    json!({
        "table_points": {"min": 2, "max": register_image::MAX_SECTIONS},
        "key_points": MAX_KEY_POINTS,
        "key_curves": CurveType::ALL.map(CurveType::name),
        "law_points": MAX_LAW_POINTS,
    })
}

/// The `[[master, slave], ...]` pairs of `body["points"]`.
fn pairs(body: &Value) -> Result<Vec<(i64, i64)>, String> {
    let points = body
        .get("points")
        .and_then(Value::as_array)
        .ok_or("the body needs \"points\": [[master, slave], ...]")?;
    points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let pair = p.as_array().filter(|a| a.len() == 2);
            let whole = |k: usize| pair.and_then(|a| a.get(k)).and_then(Value::as_i64);
            match (whole(0), whole(1)) {
                (Some(m), Some(s)) => Ok((m, s)),
                _ => Err(format!(
                    "point {}: `{}`: master and slave are whole numbers",
                    i + 1,
                    ecam_core::excerpt::excerpt(&p.to_string())
                )),
            }
        })
        .collect()
}

/// `POST /api/table/check` `{"points": [[0, 0], [1000, 500], ...]}`: the
/// point table the page edits, checked as a DECAM block takes it, with
/// what the page draws: each section's velocity, the velocity steps at its
/// points (acceleration impulses), the summary.
///
/// # Errors
/// A body without points, a point that is not two whole numbers, a table
/// the core refuses (6782 with the point, 6783), more points than a DECAM
/// block holds.
pub fn table_check_json(body: &Value) -> Result<Value, String> {
    let pairs = pairs(body)?;
    let max = register_image::MAX_SECTIONS;
    if pairs.len() > max {
        return Err(format!(
            "a DECAM table holds 2 to {max} points, not {}",
            pairs.len()
        ));
    }
    let table = PointTable::from_pairs(&pairs).map_err(|e| e.to_string())?;
    let points = table.points();
    let x: Vec<f64> = points.iter().map(|p| p.master as f64).collect();
    let s: Vec<f64> = points.iter().map(|p| p.slave as f64).collect();
    Ok(json!({
        "points": points.len(),
        "master": points.iter().map(|p| p.master).collect::<Vec<_>>(),
        "slave": points.iter().map(|p| p.slave).collect::<Vec<_>>(),
        "velocity": derivatives::forward(&x, &s),
        "steps": Steps::of(&table),
        "summary": Summary::of(&table),
    }))
}

/// `POST /api/table/read` `{"name": "t.csv", "text": "master,slave\n..."}`:
/// a table file the user uploads, read as `ecam table show` reads it (CSV or
/// JSON by the name's extension), as `{"points": [[m, s], ...],
/// "generator", "sync"}`.
///
/// # Errors
/// A name that is not `.csv`/`.json`, or the reader's error naming the
/// file, the line and the value; a table of another kind than points.
pub fn table_read_json(body: &Value) -> Result<Value, String> {
    let name = body
        .get("name")
        .and_then(Value::as_str)
        .ok_or("the body needs \"name\" (the file's name) and \"text\"")?;
    let text = body
        .get("text")
        .and_then(Value::as_str)
        .ok_or("the body needs \"text\", the file's contents")?;
    let read = match FileFormat::of(std::path::Path::new(name)).map_err(|e| e.to_string())? {
        FileFormat::Csv => TableFile::from_csv(text).map(AnyTable::Points),
        FileFormat::Json => AnyTable::from_json(text),
    };
    match read.map_err(|e| format!("{name}: {e}"))? {
        AnyTable::Points(file) => Ok(json!({
            "points": file.table.points().iter().map(|p| [p.master, p.slave]).collect::<Vec<_>>(),
            "generator": file.generator,
            "sync": file.sync,
        })),
        other => Err(format!(
            "{name} holds a {} table; the designer edits point tables (`ecam table show` reads it)",
            other.kind()
        )),
    }
}

/// `POST /api/table/convert` `{"format": "csv" | "json", "generator",
/// "sync": [lo, hi], "points": [[m, s], ...], "velocity": [...],
/// "acceleration": [...], "jerk": [...], "segments": {"start", "segments"}}`:
/// the table as `ecam table gen -o`
/// writes it, `{"text": "..."}` (the derivative columns as given, else
/// estimated from the points).
///
/// # Errors
/// An unknown format, bad points, derivative columns of another length.
pub fn table_convert_json(body: &Value) -> Result<Value, String> {
    let table = PointTable::from_pairs(&pairs(body)?).map_err(|e| e.to_string())?;
    let column = |key: &str| -> Option<Vec<f64>> {
        body.get(key)?
            .as_array()?
            .iter()
            .map(Value::as_f64)
            .collect()
    };
    let n = table.points().len();
    let kinematics = match (column("velocity"), column("acceleration"), column("jerk")) {
        (Some(v), Some(a), Some(j)) if v.len() == n && a.len() == n && j.len() == n => Some(
            table
                .points()
                .iter()
                .zip(v.iter().zip(a.iter().zip(&j)))
                .map(|(p, (&v, (&a, &j)))| Kinematics {
                    s: p.slave as f64,
                    v,
                    a,
                    j,
                })
                .collect(),
        ),
        (None, None, None) => None,
        _ => {
            return Err(format!(
                "velocity, acceleration and jerk need {n} numbers each"
            ));
        }
    };
    let sync = body
        .get("sync")
        .and_then(Value::as_array)
        .and_then(|a| Some((a.first()?.as_i64()?, a.get(1)?.as_i64()?)));
    let file = TableFile {
        table,
        sync,
        generator: body
            .get("generator")
            .and_then(Value::as_str)
            .map(str::to_string),
        kinematics,
        // A segment cam's own description (`{"start", "segments"}`), kept
        // in the file as `ecam table gen segments` keeps it.
        segments: match body.get("segments") {
            None | Some(Value::Null) => None,
            Some(cam) => Some(Box::new(
                serde_json::from_value(cam.clone()).map_err(|e| format!("\"segments\": {e}"))?,
            )),
        },
    };
    let text = match body.get("format").and_then(Value::as_str) {
        Some("csv") => file.to_csv(Columns::Full),
        Some("json") => file.to_json(Columns::Full),
        _ => return Err("\"format\" is \"csv\" or \"json\"".into()),
    };
    Ok(json!({ "text": text }))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn a_point_table_is_checked_with_its_impulses() {
        let v =
            table_check_json(&json!({"points": [[0, 0], [10, 10], [40, 100], [50, 100]]})).unwrap();
        assert_eq!(v["velocity"], json!([1.0, 3.0, 0.0, 0.0]));
        let steps: Vec<f64> = v["steps"]["velocity"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["size"].as_f64().unwrap())
            .collect();
        assert_eq!(steps, [2.0, -3.0, 1.0]);
        let e = table_check_json(&json!({"points": [[0, 0], [10, 10], [5, 1]]})).unwrap_err();
        assert!(e.contains("6782"), "{e}");
        let many: Vec<[i64; 2]> = (0..513).map(|i| [i, 0]).collect();
        assert!(
            table_check_json(&json!({ "points": many }))
                .unwrap_err()
                .contains("512")
        );
    }

    #[test]
    fn files_read_back_as_they_are_written() {
        let written = table_convert_json(&json!({
            "format": "csv", "points": [[0, 0], [100, 50]], "generator": "t"
        }))
        .unwrap();
        let text = written["text"].as_str().unwrap();
        assert!(
            text.starts_with("master,slave,velocity,acceleration,jerk\n"),
            "{text}"
        );
        let read = table_read_json(&json!({"name": "t.csv", "text": text})).unwrap();
        assert_eq!(read["points"], json!([[0, 0], [100, 50]]));
        let e = table_read_json(&json!({"name": "t.csv", "text": "master,slave\n0,0\n# x\n1,y\n"}))
            .unwrap_err();
        assert!(e.contains("t.csv: line 4: slave `y`"), "{e}");
    }
}
