//! Solving one segment between two points, and the checks on the points
//! alone: what [`SegmentCam`](super::SegmentCam) and
//! [`make_continuous`](super::make_continuous) both need.

use super::error::SegmentError;
use super::law::SegmentLaw;
use super::point::{InterpolationPoint, Quantity, SegmentSpec};
use super::shape::{End, Shape};
use crate::TableError;
use crate::table::{MAX_PROFILE_POSITION, MAX_SEGMENT_RESOLUTION};

/// Most segments a cam may have: a 512-point table holds the start and 511 ends.
pub const MAX_SEGMENTS: usize = crate::table::MAX_TOTAL_RESOLUTION as usize - 1;

fn in_range(value: i64) -> bool {
    (-MAX_PROFILE_POSITION..=MAX_PROFILE_POSITION).contains(&value)
}

/// Checks the points alone: positions, order, finite values, resolutions.
pub(crate) fn check_points(
    start: &InterpolationPoint,
    segments: &[SegmentSpec],
) -> Result<(), SegmentError> {
    if segments.is_empty() {
        return Err(SegmentError::NoSegments);
    }
    // Every point must fit a sampled table (512 points, the start one of
    // them); this also bounds the work a file or a request can ask for.
    if segments.len() > MAX_SEGMENTS {
        return Err(TableError::SectionCount {
            count: segments.len(),
            min: 1,
            max: MAX_SEGMENTS,
        }
        .into());
    }
    let points = core::iter::once(*start).chain(segments.iter().map(SegmentSpec::end));
    let mut previous: Option<i64> = None;
    for (point, p) in points.enumerate() {
        for (what, value) in [("master", p.master), ("slave", p.slave)] {
            if !in_range(value) {
                return Err(SegmentError::OutOfRange { point, what });
            }
        }
        for q in Quantity::ALL {
            if p.get(q).is_some_and(|v| !v.is_finite()) {
                return Err(SegmentError::OutOfRange {
                    point,
                    what: q.name(),
                });
            }
        }
        if previous.is_some_and(|m| p.master <= m) {
            return Err(SegmentError::MasterNotIncreasing { point });
        }
        previous = Some(p.master);
    }
    for s in segments {
        if let Some(r) = s.resolution
            && (r == 0 || r > MAX_SEGMENT_RESOLUTION)
        {
            return Err(TableError::Parameter {
                name: "segment resolution",
                reason: "must be between 1 and 512",
            }
            .into());
        }
    }
    Ok(())
}

/// A point's boundary values in units of `u` over a span `beta` (free ones 0).
fn end_values(p: &InterpolationPoint, beta: f64) -> End {
    End {
        v: p.velocity.unwrap_or(0.0) * beta,
        a: p.acceleration.unwrap_or(0.0) * beta * beta,
        j: p.jerk.unwrap_or(0.0) * beta * beta * beta,
    }
}

/// The shape of a segment from `from` to `to` along `law`.
pub(crate) fn solve_segment(
    law: SegmentLaw,
    from: &InterpolationPoint,
    to: &InterpolationPoint,
) -> (Shape, f64) {
    let beta = (to.master - from.master) as f64;
    let rise = (to.slave - from.slave) as f64;
    let shape = Shape::solve(law, rise, end_values(from, beta), end_values(to, beta));
    (shape, beta)
}

/// `quantity` of `shape` at `u` (0 or 1), per count.
pub(crate) fn value_at(shape: &Shape, beta: f64, u: f64, quantity: Quantity) -> f64 {
    let k = shape.at(u);
    let per_u = match quantity {
        Quantity::Velocity => k.v,
        Quantity::Acceleration => k.a,
        Quantity::Jerk => k.j,
    };
    per_u / libm::pow(beta, f64::from(quantity.order()))
}

/// Two values agree within rounding, against the scale `scale`.
pub(crate) fn agree(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(scale)
}
