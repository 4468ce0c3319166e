//! A table as stored in a file: its points, and what a file adds to them
//! (the synchronised zone, the generator's name, exact derivatives).
//!
//! CSV (see [`TableFile::from_csv`]) keeps the points and, optionally, the
//! derivatives. JSON is one object:
//! `{"generator": "rotary-cut", "sync": {"low": 1425, "high": 1758},
//!   "points": [{"master": 0, "slave": 0, "velocity": …}, …]}` where
//! `generator`, `sync` and the derivative keys are optional. Only JSON keeps
//! the synchronised zone.
//!
//! A JSON text may also be `ecam_core`'s own format ([`from_json`](super::from_json)),
//! tagged by `kind`: besides point tables it stores evenly spaced tables and
//! segment profiles, which [`AnyTable::from_json`] returns as they are, exact.
//!
//! ```
//! use ecam_core::io::{AnyTable, Columns, TableFile};
//!
//! let text = r#"{"sync": {"low": 0, "high": 10}, "points": [{"master": 0, "slave": 0}, {"master": 20, "slave": 10}]}"#;
//! let AnyTable::Points(file) = AnyTable::from_json(text)? else { unreachable!() };
//! assert_eq!(file.sync, Some((0, 10)));
//! assert_eq!(file.kinematics()[0].v, 0.5); // estimated from the points
//! assert_eq!(file.to_csv(Columns::Minimal), "master,slave\n0,0\n20,10\n");
//! # Ok::<(), ecam_core::io::FormatError>(())
//! ```

use std::boxed::Box;
use std::string::{String, ToString};
use std::vec::Vec;

use serde::{Deserialize, Serialize};

use super::FormatError;
use crate::segments::SegmentCam;
use crate::table::derivatives;
use crate::{CamCurve, CamPoint, CamTable, Kinematics, PointTable, SegmentProfile, UniformTable};

/// A point table with what its file adds.
#[derive(Clone, Debug, PartialEq)]
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
    /// The segment cam the table was sampled from (`ecam table gen
    /// segments`), where known: JSON keeps it as `"segments": {"start",
    /// "segments"}`, so its continuity and peaks can be reported exactly.
    pub segments: Option<Box<SegmentCam>>,
}

impl TableFile {
    /// Velocity, acceleration and jerk at every point: the known ones, or
    /// finite-difference estimates ([`derivatives::of_points`]).
    pub fn kinematics(&self) -> Vec<Kinematics> {
        match &self.kinematics {
            Some(k) if k.len() == self.table.points().len() => k.clone(),
            _ => derivatives::of_points(self.table.points()),
        }
    }

    /// The JSON text of this table (pretty-printed, ending in a newline),
    /// with the derivatives when `columns` is [`Columns::Full`].
    pub fn to_json(&self, columns: Columns) -> String {
        let full = columns == Columns::Full;
        let json = JsonTable {
            _kind: None,
            generator: self.generator.clone(),
            sync: self.sync.map(|(low, high)| JsonSync { low, high }),
            segments: self.segments.clone(),
            points: self
                .table
                .points()
                .iter()
                .zip(self.kinematics())
                .map(|(p, k)| JsonPoint {
                    master: p.master,
                    slave: p.slave,
                    velocity: full.then_some(k.v),
                    acceleration: full.then_some(k.a),
                    jerk: full.then_some(k.j),
                })
                .collect(),
        };
        // Integers, floats (non-finite ones become `null`) and strings
        // always serialise; fall back to an empty object rather than panic.
        let mut text = serde_json::to_string_pretty(&json).unwrap_or_else(|_| "{}".to_string());
        text.push('\n');
        text
    }
}

/// Which columns (CSV) or keys (JSON) a written table gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Columns {
    /// `master,slave`.
    Minimal,
    /// `master,slave,velocity,acceleration,jerk`.
    Full,
}

/// A table file of any kind: what `ecam table show | plot` take.
#[derive(Clone, Debug, PartialEq)]
pub enum AnyTable {
    /// A point table with what its file adds: CSV, a table file's JSON, or
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

    /// The cam itself, of whichever kind.
    pub fn into_curve(self) -> Box<dyn CamCurve> {
        match self {
            Self::Points(file) => Box::new(file.table),
            Self::Uniform(table) => Box::new(table),
            Self::Profile(table) => Box::new(table),
        }
    }

    /// Reads a table file's JSON object, or `ecam_core`'s JSON of any kind.
    ///
    /// # Errors
    /// [`FormatError::Json`] with the error code and section for a text with
    /// a `kind` key that `ecam_core` refuses; [`FormatError::NotATable`]
    /// for other malformed JSON (an unknown key is named, never dropped);
    /// [`FormatError::SyncZone`] or [`FormatError::Table`] for an invalid
    /// zone or table.
    pub fn from_json(text: &str) -> Result<Self, FormatError> {
        // A syntax error is reported as one, not as whichever shape the
        // broken text failed to match first.
        if let Err(e) = serde_json::from_str::<serde::de::IgnoredAny>(text) {
            return Err(FormatError::Json {
                message: super::error::plain_json_message(&e),
            });
        }
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
            return Err(FormatError::SyncZone {
                low: s.low,
                high: s.high,
            });
        }
        Ok(Self::Points(TableFile {
            table: PointTable::new(points)?,
            sync: json.sync.map(|s| (s.low, s.high)),
            generator: json.generator,
            kinematics,
            segments: json.segments,
        }))
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
    #[serde(default, skip_serializing_if = "Option::is_none")]
    segments: Option<Box<SegmentCam>>,
    points: Vec<JsonPoint>,
}

/// The only `kind` a table file's JSON takes (other kinds are `ecam_core`'s
/// tagged JSON).
#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum PointsKind {
    Points,
}

/// A JSON text without a table file's `points`: `ecam_core`'s own JSON,
/// which also stores evenly spaced tables and segment profiles.
fn other_kind(text: &str, ours: &serde_json::Error) -> Result<AnyTable, FormatError> {
    match super::from_json(text) {
        Ok(CamTable::Points(table)) => Ok(AnyTable::Points(TableFile {
            table,
            sync: None,
            generator: None,
            kinematics: None,
            segments: None,
        })),
        Ok(CamTable::Uniform(table)) => Ok(AnyTable::Uniform(table)),
        Ok(CamTable::Profile(table)) => Ok(AnyTable::Profile(table)),
        // A `kind` key means the text is meant as `ecam_core`'s own JSON:
        // its validation error (code and section) says what to fix, while
        // ours would only complain about a missing `points` key.
        Err(core) if has_kind_key(text) => Err(core),
        Err(_) => Err(FormatError::NotATable {
            message: super::error::plain_json_message(ours),
        }),
    }
}

fn has_kind_key(text: &str) -> bool {
    serde_json::from_str::<serde_json::Value>(text)
        .ok()
        .as_ref()
        .and_then(serde_json::Value::as_object)
        .is_some_and(|o| o.contains_key("kind"))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn points(text: &str) -> TableFile {
        match AnyTable::from_json(text).unwrap() {
            AnyTable::Points(file) => file,
            other => panic!("a {} table", other.kind()),
        }
    }

    fn error(text: &str) -> String {
        AnyTable::from_json(text).err().unwrap().to_string()
    }

    #[test]
    fn a_bad_core_json_table_gets_the_core_error() {
        let e = error(r#"{"kind": "uniform", "values": [0, 1], "cam_counts": 1}"#);
        assert!(e.contains("6781"), "{e}");
        assert!(!e.contains("missing field"), "{e}");
        let e = error(r#"{"pts": []}"#);
        assert!(e.contains("`pts`"), "{e}");
        // A misspelt key is named, not silently dropped.
        let e = error(
            r#"{"sycn": {"low": 0, "high": 5}, "points": [{"master": 0, "slave": 0}, {"master": 9, "slave": 1}]}"#,
        );
        assert!(e.contains("unknown field `sycn`"), "{e}");
        let e = error(
            r#"{"sync": {"low": 5, "high": 1}, "points": [{"master": 0, "slave": 0}, {"master": 9, "slave": 1}]}"#,
        );
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
            segments: None,
        }
    }

    #[test]
    fn json_round_trip_keeps_sync() {
        let back = points(&sample().to_json(Columns::Minimal));
        assert_eq!(back.table, sample().table);
        assert_eq!(back.sync, Some((10, 20)));
        assert_eq!(back.generator.as_deref(), Some("test"));
        let full = points(&sample().to_json(Columns::Full));
        assert_eq!(full.kinematics.unwrap()[1].v, 2.0);
    }

    #[test]
    fn core_json_tables_are_understood() {
        let points = r#"{"kind": "points", "points": [{"master": 0, "slave": 0}, {"master": 10, "slave": 5}]}"#;
        assert_eq!(super::tests::points(points).table.points().len(), 2);
        let uniform = r#"{"kind": "uniform", "values": [0, 100, 200], "cam_counts": 100}"#;
        match AnyTable::from_json(uniform).unwrap() {
            AnyTable::Uniform(t) => assert_eq!(t.values(), [0, 100, 200]),
            other => panic!("a {} table", other.kind()),
        }
        let profile = super::super::to_json(&CamTable::Profile(
            SegmentProfile::new(
                CamPoint::new(0, 0),
                std::vec![crate::Segment::new(100, 50, crate::MotionLaw::Cycloid)],
            )
            .unwrap(),
        ));
        let t = AnyTable::from_json(&profile).unwrap();
        assert_eq!(t.kind(), "profile");
        assert_eq!(t.into_curve().stroke(), 50);
        assert!(AnyTable::from_json("{}").is_err());
    }
}
