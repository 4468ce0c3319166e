//! The parameter block shared by ECAMTBX K100 (rotary cut) and K101 (flying
//! saw): the manual gives both the same P1–P7 table, so both generators take
//! this one struct and share the checks that do not depend on the geometry.

use super::accel_curve::AccelCurve;
use super::placement::CamPlacement;
use crate::TableError;

/// Fewest points (`P7`). The K100/K101 parameter table gives no range; the
/// manual's cam datasheet (document 003, "Resolution") allows 10 to 512
/// points in a table, the same as the key-point generator's total, so both
/// generators take that one range. (A geometry that still needed more
/// sections than the points give would be a section-count error, 6783.)
pub const MIN_RESOLUTION: u16 = 10;
/// Most points (`P7`).
pub const MAX_RESOLUTION: u16 = 512;
/// What the 6781 message says of a resolution outside
/// [`MIN_RESOLUTION`]..=[`MAX_RESOLUTION`] (a unit test keeps them in step).
pub const RESOLUTION_RANGE: &str = "must be between 10 and 512";

/// ECAMTBX K100/K101 parameters. `Default` holds the manual's defaults (3000,
/// 1000, 300, 5/3); it gives none for `P5`–`P7`, so the max ratio is 10× the
/// sync ratio (the demo's rule, [`CutParams::default_max_ratio`]), the
/// curves are code 0, leftCAM and 100 points.
///
/// The serde form uses the keys of [`schema::ROTARY_CUT`](super::schema::ROTARY_CUT)
/// (`master`, `slave`, `sync`, `ratio`, `max_ratio`, `accel`, `placement`,
/// `resolution`); what it leaves out keeps the default, and a missing
/// `max_ratio` follows the sync ratio it was given.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(from = "CutForm")]
pub struct CutParams {
    /// `P1`: master (feed) counts of the table: the cut length for a rotary
    /// cut, the counts of one stroke for a flying saw.
    #[serde(rename = "master")]
    pub master_length: i64,
    /// `P2`: slave pulses of the table: knife pulses per revolution for a
    /// rotary cut; the stroke for a flying saw (negative for its return table).
    #[serde(rename = "slave")]
    pub slave_length: i64,
    /// `P3`: sync length in slave pulses.
    #[serde(rename = "sync")]
    pub sync_length: i64,
    /// `P4`: slave pulses per master pulse in the sync zone.
    #[serde(rename = "ratio")]
    pub sync_ratio: f64,
    /// `P5`: highest ratio allowed anywhere.
    pub max_ratio: f64,
    /// `P6` low word.
    #[serde(rename = "accel")]
    pub accel_curve: AccelCurve,
    /// `P6` high word (for a flying saw without the `H1000` flag: the sign of `P2` decides).
    pub placement: CamPlacement,
    /// `P7`: points in the table, [`MIN_RESOLUTION`] to [`MAX_RESOLUTION`].
    pub resolution: u16,
}

/// [`CutParams`] as written: `max_ratio` may be left to the rule.
#[derive(serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
struct CutForm {
    master: i64,
    slave: i64,
    sync: i64,
    ratio: f64,
    max_ratio: Option<f64>,
    accel: AccelCurve,
    placement: CamPlacement,
    resolution: u16,
}

impl Default for CutForm {
    fn default() -> Self {
        let d = CutParams::default();
        Self {
            master: d.master_length,
            slave: d.slave_length,
            sync: d.sync_length,
            ratio: d.sync_ratio,
            max_ratio: None,
            accel: d.accel_curve,
            placement: d.placement,
            resolution: d.resolution,
        }
    }
}

impl From<CutForm> for CutParams {
    fn from(form: CutForm) -> Self {
        Self {
            master_length: form.master,
            slave_length: form.slave,
            sync_length: form.sync,
            sync_ratio: form.ratio,
            max_ratio: form
                .max_ratio
                .unwrap_or_else(|| Self::default_max_ratio(form.ratio)),
            accel_curve: form.accel,
            placement: form.placement,
            resolution: form.resolution,
        }
    }
}

/// Sync ratio of the manual's register table (`P4`).
const DEFAULT_SYNC_RATIO: f64 = 5.0 / 3.0;

impl Default for CutParams {
    fn default() -> Self {
        Self {
            master_length: 3000,
            slave_length: 1000,
            sync_length: 300,
            sync_ratio: DEFAULT_SYNC_RATIO,
            max_ratio: Self::default_max_ratio(DEFAULT_SYNC_RATIO),
            accel_curve: AccelCurve::Uniform,
            placement: CamPlacement::LeftCam,
            resolution: 100,
        }
    }
}

impl CutParams {
    /// `P5` when none is given: ten times the sync ratio `P4` (the manual's
    /// demo's rule; the register table gives no default).
    ///
    /// ```
    /// use ecam_core::generator::CutParams;
    ///
    /// assert_eq!(CutParams::default_max_ratio(2.0), 20.0);
    /// ```
    pub fn default_max_ratio(sync_ratio: f64) -> f64 {
        10.0 * sync_ratio
    }

    /// Checks `P1`, `P4`, `P5` and `P7`, which mean the same for both
    /// generators (`P2`, `P3` and `P6` are checked by each generator).
    pub(crate) fn check_common(&self) -> Result<(), TableError> {
        let bad = |name, reason| Err(TableError::Parameter { name, reason });
        if !(1..=i64::from(i32::MAX)).contains(&self.master_length) {
            return bad(
                "master length (P1)",
                "must be between 1 and 2147483647 pulses",
            );
        }
        if !(self.sync_ratio.is_finite() && self.sync_ratio > 0.0) {
            return bad("sync ratio (P4)", "must be a finite number above 0");
        }
        if !(self.max_ratio.is_finite() && self.max_ratio > 0.0) {
            return bad("max ratio (P5)", "must be a finite number above 0");
        }
        if !(MIN_RESOLUTION..=MAX_RESOLUTION).contains(&self.resolution) {
            return bad("resolution (P7)", RESOLUTION_RANGE);
        }
        Ok(())
    }

    /// The sync ratio must not exceed the max ratio.
    pub(crate) fn check_ratio_order(&self) -> Result<(), TableError> {
        if self.sync_ratio > self.max_ratio {
            return Err(TableError::Infeasible {
                reason: "the sync ratio (P4) is above the max ratio (P5)",
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod range_tests {
    use super::*;

    #[test]
    fn the_message_states_the_limits() {
        let range = alloc::format!("between {MIN_RESOLUTION} and {MAX_RESOLUTION}");
        assert!(RESOLUTION_RANGE.ends_with(&range));
    }
}
