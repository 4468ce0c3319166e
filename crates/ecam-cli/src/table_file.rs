//! Cam table files: CSV and JSON, chosen by extension.
//!
//! CSV has the header `master,slave,velocity,acceleration,jerk` (or the
//! minimal `master,slave`); reading needs only the `master` and `slave`
//! columns. JSON is one object:
//! `{"generator": "rotary-cut", "sync": {"low": 1425, "high": 1758},
//!   "points": [{"master": 0, "slave": 0, "velocity": …}, …]}` where
//! `generator` and `sync` are optional. Only JSON keeps the synchronised zone.
//!
//! A JSON file may also be `ecam_core`'s own format (`ecam_core::io`), tagged
//! by `kind`: besides point tables it stores evenly spaced tables and
//! segment profiles, which [`read`] returns as they are, exact.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, bail};
use ecam_core::{CamPoint, CamTable, Kinematics, PointTable, SegmentProfile, UniformTable};
use serde::{Deserialize, Serialize};

use crate::derivatives;

/// A table as stored in a file.
#[derive(Debug)]
pub struct TableFile {
    /// The validated points.
    pub table: PointTable,
    /// Master range of the synchronised zone, where known.
    pub sync: Option<(i64, i64)>,
    /// Which generator made it, where known.
    pub generator: Option<String>,
    /// Velocity, acceleration and jerk at each point when they are known
    /// exactly (from the generator's curve, or read from the file);
    /// otherwise they are estimated from the points.
    pub kinematics: Option<Vec<Kinematics>>,
}

impl TableFile {
    /// Velocity, acceleration and jerk at every point: the known ones, or
    /// finite-difference estimates.
    pub fn kinematics(&self) -> Vec<Kinematics> {
        match &self.kinematics {
            Some(k) if k.len() == self.table.points().len() => k.clone(),
            _ => derivatives::of_points(self.table.points()),
        }
    }
}

/// A table file of any kind `ecam table show | plot` take.
#[derive(Debug)]
pub enum AnyTable {
    /// A point table with what its file adds: CSV, this module's JSON, or
    /// `ecam_core`'s `{"kind": "points", ...}`.
    Points(TableFile),
    /// `ecam_core`'s evenly spaced table (document 002).
    Uniform(UniformTable),
    /// `ecam_core`'s segment profile: key points joined by motion laws.
    Profile(SegmentProfile),
}

impl AnyTable {
    /// The `kind` tag `ecam_core`'s JSON gives this table.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Points(_) => "points",
            Self::Uniform(_) => "uniform",
            Self::Profile(_) => "profile",
        }
    }
}

/// `path`'s extension in lower case (`T.CSV` and `t.csv` are the same format).
pub fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// File formats, chosen by extension.
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
    /// Extensions other than `csv` and `json`.
    pub fn of(path: &Path) -> anyhow::Result<Self> {
        match extension(path).as_deref() {
            Some("csv") => Ok(Self::Csv),
            Some("json") => Ok(Self::Json),
            _ => bail!("table file {} must end in .csv or .json", path.display()),
        }
    }
}

// Unknown keys are refused throughout: a misspelt `sync` would otherwise
// silently drop the shaded zone.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonSync {
    low: i64,
    high: i64,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonPoint {
    master: i64,
    slave: i64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    velocity: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    acceleration: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    jerk: Option<f64>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonTable {
    /// `ecam_core`'s tag: its `{"kind": "points", ...}` reads here too
    /// (only checked, hence never read).
    #[serde(default, rename = "kind", skip_serializing)]
    _kind: Option<PointsKind>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    generator: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    sync: Option<JsonSync>,
    points: Vec<JsonPoint>,
}

/// The only `kind` this module's JSON takes (other kinds go to `ecam_core`).
#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum PointsKind {
    Points,
}

/// Reads a CSV or JSON table file, of any kind.
///
/// # Errors
/// Unreadable file, missing columns, non-integer positions, or a table
/// `ecam_core` refuses (with its error code and section).
pub fn read(path: &Path) -> anyhow::Result<AnyTable> {
    let format = FileFormat::of(path)?;
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read table file {}", path.display()))?;
    let parsed = match format {
        FileFormat::Csv => parse_csv(&text).map(AnyTable::Points),
        FileFormat::Json => parse_json(&text),
    };
    parsed.with_context(|| format!("in table file {}", path.display()))
}

fn parse_csv(text: &str) -> anyhow::Result<TableFile> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let headers = reader
        .headers()
        .context("cannot read the CSV header")?
        .clone();
    let column = |name: &str| {
        headers
            .iter()
            .position(|h| h.eq_ignore_ascii_case(name))
            .with_context(|| {
                format!("the CSV header needs a `{name}` column (e.g. `master,slave`)")
            })
    };
    let (mi, si) = (column("master")?, column("slave")?);
    let derivative_columns = match (column("velocity"), column("acceleration"), column("jerk")) {
        (Ok(v), Ok(a), Ok(j)) => Some((v, a, j)),
        _ => None,
    };
    let mut kinematics = Vec::new();
    let mut points = Vec::new();
    for (row, record) in reader.records().enumerate() {
        let record = record.with_context(|| format!("bad CSV row {}", row + 1))?;
        let field = |i: usize, what: &str| -> anyhow::Result<i64> {
            let raw = record.get(i).unwrap_or("");
            parse_position(raw)
                .with_context(|| format!("row {}: {what} {raw:?} is not an integer", row + 1))
        };
        let point = CamPoint::new(field(mi, "master")?, field(si, "slave")?);
        if let Some((vi, ai, ji)) = derivative_columns {
            let real = |i: usize, what: &str| -> anyhow::Result<f64> {
                let raw = record.get(i).unwrap_or("");
                raw.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .with_context(|| format!("row {}: {what} {raw:?} is not a number", row + 1))
            };
            kinematics.push(Kinematics {
                s: point.slave as f64,
                v: real(vi, "velocity")?,
                a: real(ai, "acceleration")?,
                j: real(ji, "jerk")?,
            });
        }
        points.push(point);
    }
    Ok(TableFile {
        table: PointTable::new(points)?,
        sync: None,
        generator: None,
        kinematics: derivative_columns.map(|_| kinematics),
    })
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

fn parse_json(text: &str) -> anyhow::Result<AnyTable> {
    let json: JsonTable = match serde_json::from_str(text) {
        Ok(json) => json,
        Err(ours) => return other_kind(text, &ours),
    };
    let points = json
        .points
        .iter()
        .map(|p| CamPoint::new(p.master, p.slave))
        .collect();
    let kinematics = json
        .points
        .iter()
        .map(|p| {
            Some(Kinematics {
                s: p.slave as f64,
                v: p.velocity?,
                a: p.acceleration?,
                j: p.jerk?,
            })
        })
        .collect::<Option<Vec<_>>>();
    // As `--sync LOW:HIGH` is checked on the command line.
    if let Some(s) = &json.sync
        && s.low > s.high
    {
        bail!("sync zone low {} is above high {}", s.low, s.high);
    }
    Ok(AnyTable::Points(TableFile {
        table: PointTable::new(points)?,
        sync: json.sync.map(|s| (s.low, s.high)),
        generator: json.generator,
        kinematics,
    }))
}

/// A JSON file without this module's `points`: `ecam_core`'s own JSON,
/// which also stores evenly spaced tables and segment profiles.
fn other_kind(text: &str, ours: &serde_json::Error) -> anyhow::Result<AnyTable> {
    match ecam_core::io::from_json(text) {
        Ok(CamTable::Points(table)) => Ok(AnyTable::Points(TableFile {
            table,
            sync: None,
            generator: None,
            kinematics: None,
        })),
        Ok(CamTable::Uniform(table)) => Ok(AnyTable::Uniform(table)),
        Ok(CamTable::Profile(table)) => Ok(AnyTable::Profile(table)),
        // A `kind` key means the file is meant as `ecam_core`'s own JSON:
        // its validation error (code and section) says what to fix, while
        // ours would only complain about a missing `points` key.
        Err(core) if has_kind_key(text) => Err(anyhow::anyhow!("{core}")),
        Err(_) => Err(anyhow::anyhow!("not a table JSON object: {ours}")),
    }
}

fn has_kind_key(text: &str) -> bool {
    serde_json::from_str::<serde_json::Value>(text)
        .ok()
        .as_ref()
        .and_then(serde_json::Value::as_object)
        .is_some_and(|o| o.contains_key("kind"))
}

/// Reads any table kind `ecam_core` stores in JSON, or a point table from
/// CSV or this module's JSON: what a scenario's `file = ...` may name.
///
/// # Errors
/// As [`read`].
pub fn read_curve(path: &Path) -> anyhow::Result<Box<dyn ecam_core::CamCurve>> {
    Ok(match read(path)? {
        AnyTable::Points(file) => Box::new(file.table),
        AnyTable::Uniform(table) => Box::new(table),
        AnyTable::Profile(table) => Box::new(table),
    })
}

/// Which columns a CSV gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Columns {
    /// `master,slave`.
    Minimal,
    /// `master,slave,velocity,acceleration,jerk`.
    Full,
}

/// Writes `file` to `path` (format by extension), or as CSV to stdout when `path` is `None`.
///
/// # Errors
/// Bad extension or a failed write.
pub fn write(file: &TableFile, path: Option<&Path>, columns: Columns) -> anyhow::Result<()> {
    let text = match path.map(FileFormat::of).transpose()? {
        Some(FileFormat::Json) => to_json(file, columns)?,
        Some(FileFormat::Csv) | None => to_csv(file, columns),
    };
    match path {
        Some(path) => std::fs::write(path, text)
            .with_context(|| format!("cannot write table file {}", path.display())),
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(text.as_bytes())?;
            out.flush()?;
            Ok(())
        }
    }
}

/// The CSV text of a table.
pub fn to_csv(file: &TableFile, columns: Columns) -> String {
    let points = file.table.points();
    let mut out = String::new();
    match columns {
        Columns::Minimal => {
            out.push_str("master,slave\n");
            for p in points {
                out.push_str(&format!("{},{}\n", p.master, p.slave));
            }
        }
        Columns::Full => {
            out.push_str("master,slave,velocity,acceleration,jerk\n");
            for (p, k) in points.iter().zip(file.kinematics()) {
                // `+ 0.0` turns a negative zero into 0.
                out.push_str(&format!(
                    "{},{},{},{},{}\n",
                    p.master,
                    p.slave,
                    k.v + 0.0,
                    k.a + 0.0,
                    k.j + 0.0
                ));
            }
        }
    }
    out
}

fn to_json(file: &TableFile, columns: Columns) -> anyhow::Result<String> {
    let points = file.table.points();
    let kin = file.kinematics();
    let full = columns == Columns::Full;
    let json = JsonTable {
        _kind: None,
        generator: file.generator.clone(),
        sync: file.sync.map(|(low, high)| JsonSync { low, high }),
        points: points
            .iter()
            .zip(kin)
            .map(|(p, k)| JsonPoint {
                master: p.master,
                slave: p.slave,
                velocity: full.then_some(k.v),
                acceleration: full.then_some(k.a),
                jerk: full.then_some(k.j),
            })
            .collect(),
    };
    let mut text = serde_json::to_string_pretty(&json)?;
    text.push('\n');
    Ok(text)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn points(text: &str) -> TableFile {
        match parse_json(text).unwrap() {
            AnyTable::Points(file) => file,
            other => panic!("a {} table", other.kind()),
        }
    }

    #[test]
    fn a_bad_core_json_table_gets_the_core_error() {
        let e = parse_json(r#"{"kind": "uniform", "values": [0, 1], "cam_counts": 1}"#)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("6781"), "{e}");
        assert!(!e.contains("missing field"), "{e}");
        let e = parse_json(r#"{"pts": []}"#).err().unwrap().to_string();
        assert!(e.contains("`pts`"), "{e}");
        // A misspelt key is named, not silently dropped.
        let e = parse_json(r#"{"sycn": {"low": 0, "high": 5}, "points": [{"master": 0, "slave": 0}, {"master": 9, "slave": 1}]}"#)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("unknown field `sycn`"), "{e}");
        let e = parse_json(r#"{"sync": {"low": 5, "high": 1}, "points": [{"master": 0, "slave": 0}, {"master": 9, "slave": 1}]}"#)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("low 5 is above high 1"), "{e}");
        // ecam_core's own point JSON still reads.
        let t = points(
            r#"{"kind": "points", "points": [{"master": 0, "slave": 0}, {"master": 9, "slave": 1}]}"#,
        );
        assert_eq!(t.table.points().len(), 2);
    }

    fn sample() -> TableFile {
        TableFile {
            table: PointTable::from_pairs(&[(0, 0), (50, 100), (100, 200)]).unwrap(),
            sync: Some((10, 20)),
            generator: Some("test".into()),
            kinematics: None,
        }
    }

    #[test]
    fn csv_round_trip() {
        let text = to_csv(&sample(), Columns::Full);
        assert!(text.starts_with("master,slave,velocity,acceleration,jerk\n0,0,2,0,0\n"));
        let back = parse_csv(&text).unwrap();
        assert_eq!(back.table, sample().table);
        assert_eq!(back.kinematics.unwrap()[1].v, 2.0);
        let minimal = parse_csv("master,slave\n0,0\n10,5\n").unwrap();
        assert!(minimal.kinematics.is_none());
        assert_eq!(minimal.kinematics()[0].v, 0.5);
    }

    #[test]
    fn json_round_trip_keeps_sync() {
        let text = to_json(&sample(), Columns::Minimal).unwrap();
        let back = points(&text);
        assert_eq!(back.table, sample().table);
        assert_eq!(back.sync, Some((10, 20)));
        assert_eq!(back.generator.as_deref(), Some("test"));
    }

    #[test]
    fn csv_errors_name_the_problem() {
        let err = parse_csv("m,s\n0,0\n").unwrap_err();
        assert!(format!("{err:#}").contains("master"));
        let err = parse_csv("master,slave\n0,0\n1,x\n").unwrap_err();
        assert!(format!("{err:#}").contains("row 2"));
        let err = parse_csv("master,slave\n0,0\n0,1\n").unwrap_err();
        assert!(format!("{err:#}").contains("6782"));
    }

    #[test]
    fn core_json_tables_are_understood() {
        let points = r#"{"kind": "points", "points": [{"master": 0, "slave": 0}, {"master": 10, "slave": 5}]}"#;
        assert_eq!(super::tests::points(points).table.points().len(), 2);
        let uniform = r#"{"kind": "uniform", "values": [0, 100, 200], "cam_counts": 100}"#;
        match parse_json(uniform).unwrap() {
            AnyTable::Uniform(t) => assert_eq!(t.values(), [0, 100, 200]),
            other => panic!("a {} table", other.kind()),
        }
        let profile = ecam_core::io::to_json(&CamTable::Profile(
            SegmentProfile::new(
                CamPoint::new(0, 0),
                vec![ecam_core::Segment::new(
                    100,
                    50,
                    ecam_core::MotionLaw::Cycloid,
                )],
            )
            .unwrap(),
        ));
        let t = parse_json(&profile).unwrap();
        assert_eq!(t.kind(), "profile");
        assert!(parse_json("{}").is_err());
    }

    #[test]
    fn float_positions_must_be_whole() {
        assert_eq!(parse_position("1000.0"), Some(1000));
        assert_eq!(parse_position("-3"), Some(-3));
        assert_eq!(parse_position("1.5"), None);
    }
}
