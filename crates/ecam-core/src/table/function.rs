//! Tables sampled from a mathematical function of the master, the PC
//! editor's first way of making a table (document 003 §6.2, its sine example).

use alloc::vec::Vec;

use crate::table::segment::MAX_PROFILE_POSITION;
use crate::{CamPoint, PointTable, TableError};

/// Samples `slave = f(master)` at `points` masters evenly spread (whole
/// counts) from `master_first` to `master_last`, both included exactly.
/// Slave values are rounded to whole pulses.
///
/// ```
/// use ecam_core::{CamCurve, table::sample_function};
///
/// // One sine period of ±1000 pulses over 3600 counts, 361 points.
/// let t = sample_function(
///     |m| 1000.0 * (m / 3600.0 * std::f64::consts::TAU).sin(),
///     0,
///     3600,
///     361,
/// )?;
/// assert_eq!(t.points()[90].slave, 1000);
/// assert_eq!(t.master_last(), 3600);
/// # Ok::<(), ecam_core::TableError>(())
/// ```
///
/// # Errors
/// [`TableError::SectionCount`] for fewer than two points;
/// [`TableError::MasterNotIncreasing`] when `master_last ≤ master_first`;
/// [`TableError::ValueOutOfRange`] for an end beyond ±2⁵², or naming the
/// first point where `f` is not finite or beyond ±2⁵²;
/// [`TableError::Parameter`] when there are more points than master counts.
pub fn sample_function(
    f: impl Fn(f64) -> f64,
    master_first: i64,
    master_last: i64,
    points: usize,
) -> Result<PointTable, TableError> {
    if points < 2 {
        return Err(TableError::SectionCount {
            count: points,
            min: 2,
            max: usize::MAX,
        });
    }
    let limit = -MAX_PROFILE_POSITION..=MAX_PROFILE_POSITION;
    if !limit.contains(&master_first) {
        return Err(TableError::ValueOutOfRange { section: 0 });
    }
    if !limit.contains(&master_last) {
        return Err(TableError::ValueOutOfRange {
            section: points - 1,
        });
    }
    if master_last <= master_first {
        return Err(TableError::MasterNotIncreasing {
            section: points - 1,
        });
    }
    let span = i128::from(master_last) - i128::from(master_first);
    let pieces = points as i128 - 1;
    if span < pieces {
        return Err(TableError::Parameter {
            name: "points",
            reason: "must not exceed the master span plus one (whole master counts)",
        });
    }
    let bound = MAX_PROFILE_POSITION as f64;
    let mut table = Vec::with_capacity(points);
    for k in 0..points {
        // span ≤ 2^53 and k < span + 1: the product fits i128, the quotient i64.
        let master = master_first + (span * k as i128 / pieces) as i64;
        let slave = f(master as f64);
        if !slave.is_finite() || slave.abs() > bound {
            return Err(TableError::ValueOutOfRange { section: k });
        }
        table.push(CamPoint::new(master, libm::round(slave) as i64));
    }
    PointTable::new(table)
}
