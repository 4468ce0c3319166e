//! "Make continuous": fill every free boundary value from the neighbouring
//! segments, so the cam is C2 wherever its laws allow (C3 where poly-7
//! segments take the jerk too).
//!
//! Per point and per value (velocity, then acceleration, then jerk), the
//! segments arriving and leaving are asked what they give there:
//!
//! - a value the point fixes stays (at the seam, a value fixed at one end of
//!   the cycle is copied to the other);
//! - a law that does not adapt to the value (a rise law, constant velocity,
//!   the velocity cycloid's zero acceleration, a poly-5's jerk) gives it,
//!   and the point takes it; when both sides give one and they differ, the
//!   point cannot be made continuous: an error for velocity and
//!   acceleration, and for jerk the point is left free (reported as C2);
//! - where both sides adapt, velocity follows the neighbouring chords by the
//!   monotone rule of Fritsch and Carlson (0 where the slave turns or rests,
//!   else the weighted harmonic mean of the chord slopes), acceleration and
//!   jerk are 0.
//!
//! The first and last points are one joint, the seam (the cam repeats with
//! its stroke carried over), so a cam made continuous is continuous across
//! cycles too.

use alloc::vec::Vec;

use super::error::SegmentError;
use super::point::{InterpolationPoint, Quantity, SegmentSpec};
use super::solve::{agree, check_points, solve_segment, value_at};

/// Fills the free boundary values of `start` and `segments` (see the module).
///
/// # Errors
/// As [`super::SegmentCam::new`] for the points, and
/// [`SegmentError::Conflict`] naming the point where both neighbours fix a
/// velocity or an acceleration and differ.
pub fn make_continuous(
    start: InterpolationPoint,
    segments: Vec<SegmentSpec>,
) -> Result<(InterpolationPoint, Vec<SegmentSpec>), SegmentError> {
    check_points(&start, &segments)?;
    let n = segments.len();
    let mut points: Vec<InterpolationPoint> = core::iter::once(start)
        .chain(segments.iter().map(SegmentSpec::end))
        .collect();
    for q in Quantity::ALL {
        // The seam last, so a clash between two points is named at the first.
        for joint in (1..n).chain([0]) {
            // Joint 0 is the seam: points 0 and n.
            let (at, left, right): (&[usize], usize, usize) = if joint == 0 {
                (&[0, n], n - 1, 0)
            } else {
                (&[joint], joint - 1, joint)
            };
            if let Some(fixed) = at.iter().find_map(|&p| points[p].get(q)) {
                for &p in at {
                    if points[p].get(q).is_none() {
                        points[p].set(q, Some(fixed));
                    }
                }
                continue;
            }
            let arriving = given(&segments, &points, left, 1.0, q);
            let leaving = given(&segments, &points, right, 0.0, q);
            let value = match (arriving, leaving) {
                (Some(a), Some(b)) => {
                    let scale = chord(&points, left).abs().max(chord(&points, right).abs());
                    if agree(a, b, scale * 1e-6) {
                        Some(a)
                    } else if q == Quantity::Jerk {
                        None
                    } else {
                        let point = if joint == 0 { n } else { joint };
                        return Err(SegmentError::Conflict {
                            point,
                            master: points[point].master,
                            quantity: q,
                            arriving: (left + 1, segments[left].law, a),
                            leaving: (right + 1, segments[right].law, b),
                        });
                    }
                }
                (Some(v), None) | (None, Some(v)) => Some(v),
                (None, None) => Some(match q {
                    Quantity::Velocity => monotone_velocity(&points, left, right),
                    Quantity::Acceleration | Quantity::Jerk => 0.0,
                }),
            };
            for &p in at {
                points[p].set(q, value);
            }
        }
    }
    let start = points[0];
    let segments = segments
        .iter()
        .zip(&points[1..])
        .map(|(s, p)| s.with_end(*p))
        .collect();
    Ok((start, segments))
}

/// What segment `i` gives for `q` at `u` (0 or 1), if its law does not adapt to `q`.
fn given(
    segments: &[SegmentSpec],
    points: &[InterpolationPoint],
    i: usize,
    u: f64,
    q: Quantity,
) -> Option<f64> {
    let law = segments[i].law;
    let adapts = law.adapts();
    let adapted = match q {
        Quantity::Velocity => adapts.velocity,
        Quantity::Acceleration => adapts.acceleration,
        Quantity::Jerk => adapts.jerk,
    };
    if adapted {
        return None;
    }
    let (shape, beta) = solve_segment(law, &points[i], &points[i + 1]);
    Some(value_at(&shape, beta, u, q))
}

/// Segment `i`'s chord slope and span.
fn chord_and_span(points: &[InterpolationPoint], i: usize) -> (f64, f64) {
    let span = (points[i + 1].master - points[i].master) as f64;
    ((points[i + 1].slave - points[i].slave) as f64 / span, span)
}

fn chord(points: &[InterpolationPoint], i: usize) -> f64 {
    chord_and_span(points, i).0
}

/// Fritsch–Carlson: 0 unless both chords have one sign, else their
/// weighted harmonic mean (weights from the spans, as PCHIP).
fn monotone_velocity(points: &[InterpolationPoint], left: usize, right: usize) -> f64 {
    let (d1, h1) = chord_and_span(points, left);
    let (d2, h2) = chord_and_span(points, right);
    if d1 * d2 <= 0.0 {
        return 0.0;
    }
    let w1 = 2.0 * h2 + h1;
    let w2 = h2 + 2.0 * h1;
    (w1 + w2) / (w1 / d1 + w2 / d2)
}
