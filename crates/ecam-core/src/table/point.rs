//! Point tables: (master, slave) pairs joined by straight lines, as the PLC's
//! DECAM register block and the motion controller's E-CAM table hold them.

use alloc::vec::Vec;

use super::lines::Lines;
use crate::{CamCurve, Cursor, Kinematics, TableError};

/// One point of a point table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamPoint {
    /// Master position, in master counts.
    pub master: i64,
    /// Slave position, in slave pulses.
    pub slave: i64,
}

impl CamPoint {
    /// A point at `(master, slave)`.
    pub const fn new(master: i64, slave: i64) -> Self {
        Self { master, slave }
    }
}

/// A validated point table: at least two points, master strictly increasing.
///
/// Between points the slave is interpolated linearly, as both devices do.
/// The Rust API puts no upper bound on the number of points; the PLC face
/// checks its own limit of 512 sections when writing a register image.
///
/// Beside the exact integer points the table keeps float copies of each
/// section (start, rise, span, slope), made once when it is built, so a
/// lookup costs a few float operations (see `lines.rs`); they never
/// change a result.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "RawPoints")]
pub struct PointTable {
    points: Vec<CamPoint>,
    /// Derived from `points`; not part of the table's identity or files.
    #[serde(skip)]
    lines: Lines,
    /// Derived from `points` ([`CamCurve::turns_back`]).
    #[serde(skip)]
    turns_back: bool,
}

impl PartialEq for PointTable {
    fn eq(&self, other: &Self) -> bool {
        self.points == other.points
    }
}

impl Eq for PointTable {}

/// The unchecked JSON shape of a point table; validated on the way in.
// Unknown keys are refused: a misspelt key would otherwise vanish silently.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPoints {
    points: Vec<CamPoint>,
}

impl TryFrom<RawPoints> for PointTable {
    type Error = TableError;
    fn try_from(raw: RawPoints) -> Result<Self, TableError> {
        Self::new(raw.points)
    }
}

impl PointTable {
    /// Checks and wraps `points`.
    ///
    /// # Errors
    /// [`TableError::SectionCount`] for fewer than two points,
    /// [`TableError::MasterNotIncreasing`] naming the first point whose master
    /// is not greater than its predecessor's.
    pub fn new(points: Vec<CamPoint>) -> Result<Self, TableError> {
        if points.len() < 2 {
            return Err(TableError::SectionCount {
                count: points.len(),
                min: 2,
                max: usize::MAX,
            });
        }
        if let Some(bad) = points.windows(2).position(|w| w[1].master <= w[0].master) {
            return Err(TableError::MasterNotIncreasing { section: bad + 1 });
        }
        let lines = Lines::new(&points);
        let turns_back = super::turns_back(points.iter().map(|p| p.slave));
        Ok(Self {
            points,
            lines,
            turns_back,
        })
    }

    /// Builds a table from `(master, slave)` pairs.
    ///
    /// # Errors
    /// As [`PointTable::new`].
    pub fn from_pairs(pairs: &[(i64, i64)]) -> Result<Self, TableError> {
        Self::new(pairs.iter().map(|&(m, s)| CamPoint::new(m, s)).collect())
    }

    /// The points, in master order.
    pub fn points(&self) -> &[CamPoint] {
        &self.points
    }

    /// Gives the points back.
    pub fn into_points(self) -> Vec<CamPoint> {
        self.points
    }
}

impl CamCurve for PointTable {
    fn master_first(&self) -> i64 {
        self.points[0].master
    }
    fn master_last(&self) -> i64 {
        self.points[self.points.len() - 1].master
    }
    fn slave_first(&self) -> i64 {
        self.points[0].slave
    }
    fn slave_last(&self) -> i64 {
        self.points[self.points.len() - 1].slave
    }
    fn segment_count(&self) -> usize {
        self.points.len() - 1
    }

    #[inline]
    fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics {
        self.lines.eval(master, cursor)
    }

    #[inline]
    fn position(&self, master: f64, cursor: &mut Cursor) -> f64 {
        self.lines.position(master, cursor)
    }

    fn positions_into(&self, masters: &[f64], out: &mut [f64]) {
        self.lines.positions_into(masters, out);
    }

    fn turns_back(&self) -> bool {
        self.turns_back
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn doc001() -> PointTable {
        PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)]).unwrap()
    }

    #[test]
    fn interpolates_linearly_between_points() {
        let t = doc001();
        let mut c = Cursor::new();
        assert_eq!(t.position(5000.0, &mut c), 1000.0);
        assert_eq!(t.position(15000.0, &mut c), 1250.0);
        assert_eq!(t.position(30000.0, &mut c), 2000.0);
        assert_eq!(t.eval(25000.0, &mut c).v, 0.1);
    }

    #[test]
    fn knows_whether_the_slave_turns_back() {
        assert!(doc001().turns_back(), "1500 then 1000: down after up");
        let knife = PointTable::from_pairs(&[(0, 0), (10, 0), (20, 700), (30, 1000)]).unwrap();
        assert!(!knife.turns_back(), "dwells and rises: never back");
        let falling = PointTable::from_pairs(&[(0, 0), (10, -5), (20, -5)]).unwrap();
        assert!(!falling.turns_back());
        let copy: PointTable =
            serde_json::from_str(&serde_json::to_string(&doc001()).unwrap()).unwrap();
        assert!(copy.turns_back(), "worked out again when read from JSON");
    }

    #[test]
    fn clamps_outside_the_cycle() {
        let t = doc001();
        let mut c = Cursor::new();
        assert_eq!(t.position(-10.0, &mut c), 500.0);
        assert_eq!(t.position(40000.0, &mut c), 2000.0);
        assert_eq!(t.position(f64::NAN, &mut c), 500.0);
    }

    #[test]
    fn extreme_positions_do_not_overflow() {
        let t = PointTable::from_pairs(&[(i64::MIN, i64::MAX), (i64::MAX, i64::MIN)]).unwrap();
        let k = t.eval(0.0, &mut Cursor::new());
        assert!(k.s.abs() < 1e5 && (k.v + 1.0).abs() < 1e-12);
    }

    #[test]
    fn cursor_and_binary_search_agree() {
        let t = doc001();
        let mut seq = Cursor::new();
        for m in (0..=30000).step_by(7) {
            let mut fresh = Cursor::new();
            assert_eq!(
                t.position(m as f64, &mut seq),
                t.position(m as f64, &mut fresh)
            );
        }
    }

    #[test]
    fn rejects_non_increasing_master_with_section_number() {
        let err = PointTable::from_pairs(&[(0, 0), (10, 1), (10, 2)]).unwrap_err();
        assert_eq!(err, TableError::MasterNotIncreasing { section: 2 });
        assert_eq!(err.code(), 6782);
        assert_eq!(err.section(), Some(2));
    }

    #[test]
    fn rejects_too_few_points() {
        let err = PointTable::from_pairs(&[(0, 0)]).unwrap_err();
        assert_eq!(err.code(), 6783);
    }
}
