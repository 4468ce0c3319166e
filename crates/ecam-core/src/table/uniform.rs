//! Evenly spaced tables, as document 002's motion processor stores them:
//! only the slave values are held; the master of value `k` is
//! `k · CamCounts / (N − 1)`.

use alloc::vec::Vec;

use crate::{CamCurve, Cursor, Kinematics, TableError};

/// Largest `CamCounts` document 002 allows (2²⁹).
pub const MAX_CAM_COUNTS: i64 = 1 << 29;

/// `N` slave values evenly spaced over `CamCounts` master counts.
///
/// `N` values define `N − 1` linear pieces (document 002: "the increment in
/// input is CamCounts/(N − 1), not CamCounts/N"); the spacing may be a
/// fraction of a count. The first value sits at master 0, the last exactly at
/// `CamCounts`.
///
/// ```
/// use ecam_core::{CamCurve, Cursor, UniformTable};
///
/// // Document 002's example: 3 values over 100 counts.
/// let t = UniformTable::new(vec![0, 100, 200], 100)?;
/// let mut c = Cursor::new();
/// assert_eq!(t.position(50.0, &mut c), 100.0);
/// assert_eq!(t.eval(75.0, &mut c).v, 2.0);
/// # Ok::<(), ecam_core::TableError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "RawUniform")]
pub struct UniformTable {
    values: Vec<i64>,
    cam_counts: i64,
    /// Derived from `values` ([`CamCurve::turns_back`]).
    #[serde(skip)]
    turns_back: bool,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawUniform {
    values: Vec<i64>,
    cam_counts: i64,
}

impl TryFrom<RawUniform> for UniformTable {
    type Error = TableError;
    fn try_from(raw: RawUniform) -> Result<Self, TableError> {
        Self::new(raw.values, raw.cam_counts)
    }
}

impl UniformTable {
    /// Checks and wraps `values` spread over `cam_counts` master counts.
    ///
    /// # Errors
    /// [`TableError::SectionCount`] for fewer than two values;
    /// [`TableError::Parameter`] when `cam_counts` is outside `2..=2²⁹`;
    /// [`TableError::ValueOutOfRange`] naming the first value that is not a
    /// signed 32-bit number (document 002's buffer holds signed dwords).
    pub fn new(values: Vec<i64>, cam_counts: i64) -> Result<Self, TableError> {
        if values.len() < 2 {
            return Err(TableError::SectionCount {
                count: values.len(),
                min: 2,
                max: usize::MAX,
            });
        }
        if !(2..=MAX_CAM_COUNTS).contains(&cam_counts) {
            return Err(TableError::Parameter {
                name: "CamCounts",
                reason: "must be between 2 and 2^29 (536870912)",
            });
        }
        if let Some(bad) = values.iter().position(|&v| i32::try_from(v).is_err()) {
            return Err(TableError::ValueOutOfRange { section: bad });
        }
        let turns_back = super::turns_back(values.iter().copied());
        Ok(Self {
            values,
            cam_counts,
            turns_back,
        })
    }

    /// The slave values, first at master 0, last at `cam_counts`.
    pub fn values(&self) -> &[i64] {
        &self.values
    }

    /// Length of the table in master counts (`CamCounts`).
    pub fn cam_counts(&self) -> i64 {
        self.cam_counts
    }

    /// Index of the piece holding `x`, measured in table steps.
    fn piece(&self, x: f64) -> usize {
        let last_piece = self.values.len() - 2;
        // `as` saturates; x is already clamped to [0, N − 1].
        (x as usize).min(last_piece)
    }
}

impl CamCurve for UniformTable {
    fn master_first(&self) -> i64 {
        0
    }
    fn master_last(&self) -> i64 {
        self.cam_counts
    }
    fn slave_first(&self) -> i64 {
        self.values.first().copied().unwrap_or(0)
    }
    fn slave_last(&self) -> i64 {
        self.values.last().copied().unwrap_or(0)
    }
    fn segment_count(&self) -> usize {
        self.values.len() - 1
    }

    fn turns_back(&self) -> bool {
        self.turns_back
    }

    /// O(1) for any master: the piece is found by division, so the cursor
    /// only records it.
    fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics {
        let counts = self.cam_counts as f64;
        let m = if master.is_nan() {
            0.0
        } else {
            master.clamp(0.0, counts)
        };
        let pieces = (self.values.len() - 1) as f64;
        // Work in "count·pieces" units so that whole-count masters give exact
        // results: m·(N−1) and i·CamCounts are exact integers below 2^53.
        let scaled = m * pieces;
        let i = self.piece(scaled / counts);
        cursor.segment = i;
        let (v0, v1) = (self.values[i] as f64, self.values[i + 1] as f64);
        let rise = v1 - v0;
        let into_piece = scaled - i as f64 * counts;
        Kinematics {
            s: v0 + rise * into_piece / counts,
            v: rise * pieces / counts,
            a: 0.0,
            j: 0.0,
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use alloc::vec;

    #[test]
    fn knows_whether_the_slave_turns_back() {
        assert!(
            !UniformTable::new(vec![0, 100, 200], 100)
                .unwrap()
                .turns_back()
        );
        assert!(
            UniformTable::new(vec![0, 100, 50], 100)
                .unwrap()
                .turns_back()
        );
    }

    #[test]
    fn document_002_example_is_a_straight_line() {
        let t = UniformTable::new(vec![0, 100, 200], 100).unwrap();
        let mut c = Cursor::new();
        for m in 0..=100 {
            assert_eq!(t.position(m as f64, &mut c), 2.0 * m as f64);
        }
        assert_eq!(t.stroke(), 200);
        assert_eq!(t.segment_count(), 2);
    }

    #[test]
    fn fractional_spacing_hits_the_end_exactly() {
        // 4 values over 10 counts: a piece every 3⅓ counts.
        let t = UniformTable::new(vec![5, -7, 11, 13], 10).unwrap();
        let mut c = Cursor::new();
        assert_eq!(t.position(0.0, &mut c), 5.0);
        assert_eq!(t.position(10.0, &mut c), 13.0);
        assert_eq!(t.position(10.0 / 3.0, &mut c), -7.0);
        assert_eq!(t.position(1e12, &mut c), 13.0);
        assert_eq!(t.position(f64::NAN, &mut c), 5.0);
    }

    #[test]
    fn refuses_bad_input() {
        assert_eq!(UniformTable::new(vec![1], 10).unwrap_err().code(), 6783);
        assert_eq!(UniformTable::new(vec![1, 2], 1).unwrap_err().code(), 6781);
        assert_eq!(
            UniformTable::new(vec![1, 2], MAX_CAM_COUNTS + 1)
                .unwrap_err()
                .code(),
            6781
        );
        assert_eq!(
            UniformTable::new(vec![1, 1 << 40], 10).unwrap_err(),
            TableError::ValueOutOfRange { section: 1 }
        );
    }
}
