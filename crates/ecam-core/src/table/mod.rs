//! Cam tables: the shapes a cam is stored in.
//!
//! - [`PointTable`]: (master, slave) points joined by straight lines, what
//!   the PLC register block holds;
//! - [`UniformTable`]: evenly spaced slave values over `CamCounts`
//!   (document 002's motion processor);
//! - [`SegmentProfile`]: key points joined by motion laws (PC editor dialog,
//!   ECAMTBX K2), exact, and sampled into a point table on demand;
//! - [`CamTable`]: any of them behind one type;
//! - [`sample_function`]: a point table from a function of the master;
//! - [`Summary`]: a table's sections, stroke, peaks and continuity;
//! - [`steps`]: where a curve's velocity or acceleration steps (the
//!   impulses its plots draw), by one rule;
//! - [`derivatives`]: velocity, acceleration and jerk estimated from a
//!   point table's points where no exact curve is known.
//!
//! All of them evaluate through [`crate::CamCurve`] with a [`crate::Cursor`]:
//! O(1) when the master moves a little, a binary search after a jump.

mod cam_point;
mod cam_table;
mod continuity;
pub mod derivatives;
mod function;
mod lines;
mod point;
mod resolution;
mod segment;
pub mod steps;
mod summary;
mod uniform;

pub use cam_point::CamPoint;
pub use cam_table::CamTable;
pub use continuity::Continuity;
pub use function::sample_function;
pub use point::PointTable;
pub(crate) use resolution::distribute;
pub use resolution::{MAX_TOTAL_RESOLUTION, MIN_TOTAL_RESOLUTION};
pub use segment::{MAX_PROFILE_POSITION, MAX_SEGMENT_RESOLUTION, Segment, SegmentProfile};
pub(crate) use segment::{sample_spans, sample_uniform};
pub use summary::Summary;
pub use uniform::{MAX_CAM_COUNTS, UniformTable};

/// Whether slave values taken in master order move both up and down
/// (see [`crate::CamCurve::turns_back`]); straight lines between them add
/// no turn of their own.
pub(crate) fn turns_back(slaves: impl Iterator<Item = i64>) -> bool {
    let (mut up, mut down) = (false, false);
    let mut last: Option<i64> = None;
    for s in slaves {
        if let Some(l) = last {
            up |= s > l;
            down |= s < l;
        }
        last = Some(s);
    }
    up && down
}
