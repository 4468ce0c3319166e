//! Checking a cam against its drive ([`ecam_core::drive_check`]) from the
//! front ends: a drive file's TOML, a table file of any kind, the
//! designer's JSON.

use ecam_core::drive_check::{self, Drive, DriveReport, Motion};
use ecam_core::io::AnyTable;
use ecam_core::segments::SegmentCam;
use serde_json::{Value, json};

use crate::error::DriveFileError;

/// Samples per segment of an exact cam for the drive check: the RMS
/// integral by trapezoids is then within about 10⁻⁶ of the exact one.
const SAMPLES_PER_SEGMENT: usize = 2000;

/// Reads a drive file (`[mechanics]`, `[limits]`, see `docs/design.md`).
///
/// # Errors
/// TOML syntax, unknown or missing keys, values out of range.
pub fn read_drive(text: &str) -> Result<Drive, DriveFileError> {
    let drive: Drive = toml::from_str(text)
        .map_err(|e| DriveFileError::Keys(ecam_core::io::plain_serde_message(&e.to_string())))?;
    drive.validate()?;
    Ok(drive)
}

/// The motion of a segment cam: its exact samples, both ends of each segment.
pub fn motion_of_cam(cam: &SegmentCam) -> Motion {
    Motion::from_samples(cam.sample_segments(SAMPLES_PER_SEGMENT))
}

/// The motion the drive follows for a table file: a segment cam's exact
/// samples when the file keeps one (`ecam table gen segments -o F.json`) or
/// is a profile, else the derivatives at the points (a generator's design
/// columns, or the estimates from the points: see `docs/cli.md`).
///
/// # Errors
/// An evenly spaced table (the check takes tables with known points or
/// laws); a profile that is not a valid segment cam.
pub fn motion_of(table: &AnyTable) -> Result<Motion, DriveFileError> {
    Ok(match table {
        AnyTable::Points(file) => match &file.segments {
            Some(cam) => motion_of_cam(cam),
            None => Motion::from_samples(
                file.table
                    .points()
                    .iter()
                    .zip(file.kinematics())
                    .map(|(p, k)| (p.master as f64, k))
                    .collect(),
            ),
        },
        AnyTable::Profile(profile) => {
            motion_of_cam(&SegmentCam::try_from(profile).map_err(DriveFileError::Profile)?)
        }
        AnyTable::Uniform(_) => return Err(DriveFileError::Uniform),
    })
}

/// `table` checked against the drive file `drive_text`, at `master_hz`
/// (counts/s) when given.
///
/// # Errors
/// A bad drive file or a table the check does not take.
pub fn check_table(
    table: &AnyTable,
    drive_text: &str,
    master_hz: Option<f64>,
) -> Result<DriveReport, DriveFileError> {
    let drive = read_drive(drive_text)?;
    let motion = motion_of(table)?;
    Ok(drive_check::check(&motion, &drive, master_hz)?)
}

/// The designer's drive check: `{"generator": "segments", "params": {...},
/// "drive": {"mechanics": {...}, "limits": {...}}, "master_speed": 1000}` →
/// the [`DriveReport`] as JSON (∞ as `null`).
///
/// # Errors
/// A body of the wrong shape, a design the generator refuses, a bad drive.
pub fn drive_check_json(body: &Value) -> Result<Value, String> {
    let run = || -> Result<Value, String> {
        let name = body
            .get("generator")
            .and_then(Value::as_str)
            .ok_or("the body needs \"generator\" and \"params\", as POST /api/table/gen")?;
        let params = body.get("params").cloned().unwrap_or_else(|| json!({}));
        let drive: Drive = serde_json::from_value(
            body.get("drive")
                .cloned()
                .ok_or("the body needs \"drive\": {\"mechanics\": {...}, \"limits\": {...}}")?,
        )
        .map_err(|e| {
            format!(
                "drive: {}",
                ecam_core::io::plain_serde_message(&e.to_string())
            )
        })?;
        let master_hz = match body.get("master_speed") {
            None | Some(Value::Null) => None,
            Some(v) => Some(
                v.as_f64()
                    .ok_or("master_speed must be a number (counts/s)")?,
            ),
        };
        let g = crate::generate::from_json(name, params).map_err(|e| e.to_string())?;
        let motion = match &g.segments {
            Some(cam) => motion_of_cam(cam),
            None => match &g.exact {
                Some(ecam_core::generator::ExactCurve::Design(design)) => {
                    Motion::from_samples(design.sample_pieces(SAMPLES_PER_SEGMENT))
                }
                _ => motion_of(&AnyTable::Points(ecam_core::io::TableFile {
                    table: g.table.clone(),
                    sync: None,
                    generator: None,
                    kinematics: g.kinematics.clone(),
                    segments: None,
                }))
                .map_err(|e| e.to_string())?,
            },
        };
        let report = drive_check::check(&motion, &drive, master_hz).map_err(|e| e.to_string())?;
        serde_json::to_value(report).map_err(|e| e.to_string())
    };
    run()
}
