//! [`CamTable`]: any table kind behind one type, so the engine and the faces
//! can hold "a cam" without generics.

use crate::{CamCurve, Cursor, Kinematics, PointTable, SegmentProfile, UniformTable};

/// Every table kind this crate makes. Implements [`CamCurve`] by delegating
/// to the table it holds.
///
/// In JSON it is tagged by `kind`: `{"kind": "points", "points": [...]}`,
/// `{"kind": "uniform", "values": [...], "cam_counts": N}` or
/// `{"kind": "profile", "start": {...}, "segments": [...]}`.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum CamTable {
    /// (master, slave) points joined by straight lines (PLC register block).
    Points(PointTable),
    /// Evenly spaced values over `CamCounts` (document 002).
    Uniform(UniformTable),
    /// Key points joined by motion laws, evaluated exactly.
    Profile(SegmentProfile),
}

impl From<PointTable> for CamTable {
    fn from(t: PointTable) -> Self {
        Self::Points(t)
    }
}

impl From<UniformTable> for CamTable {
    fn from(t: UniformTable) -> Self {
        Self::Uniform(t)
    }
}

impl From<SegmentProfile> for CamTable {
    fn from(t: SegmentProfile) -> Self {
        Self::Profile(t)
    }
}

macro_rules! delegate {
    ($self:ident, $t:ident => $e:expr) => {
        match $self {
            CamTable::Points($t) => $e,
            CamTable::Uniform($t) => $e,
            CamTable::Profile($t) => $e,
        }
    };
}

impl CamCurve for CamTable {
    fn master_first(&self) -> i64 {
        delegate!(self, t => t.master_first())
    }
    fn master_last(&self) -> i64 {
        delegate!(self, t => t.master_last())
    }
    fn slave_first(&self) -> i64 {
        delegate!(self, t => t.slave_first())
    }
    fn slave_last(&self) -> i64 {
        delegate!(self, t => t.slave_last())
    }
    fn segment_count(&self) -> usize {
        delegate!(self, t => t.segment_count())
    }
    fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics {
        delegate!(self, t => t.eval(master, cursor))
    }
    fn position(&self, master: f64, cursor: &mut Cursor) -> f64 {
        delegate!(self, t => t.position(master, cursor))
    }
    fn positions_into(&self, masters: &[f64], out: &mut [f64]) {
        delegate!(self, t => t.positions_into(masters, out))
    }
    fn turns_back(&self) -> bool {
        delegate!(self, t => t.turns_back())
    }
}
