//! [`SegmentCam`]: interpolation points joined by segments, each solved for
//! its law and boundary values.

use alloc::vec::Vec;

use super::error::SegmentError;
use super::law::SegmentLaw;
use super::peaks::SegmentPeaks;
use super::point::{InterpolationPoint, Quantity, SegmentSpec};
use super::shape::Shape;
use super::solve::{agree, check_points, solve_segment, value_at};
use crate::table::steps::{Corner, Corners};
use crate::table::{distribute, sample_spans, sample_uniform};
use crate::{CamCurve, CamPoint, Cursor, Kinematics, PointTable, TableError, UniformTable};

/// A cam made of segments between interpolation points, every segment's
/// law solved for the boundary values at its points.
///
/// Point 0 is `start`; segment `k` (1-based) runs from point `k − 1` to
/// point `k`, the end point it carries. It evaluates exactly; sample it with
/// [`SegmentCam::sample`] (a point table, the DECAM register image via
/// [`crate::register_image::to_words`]) or [`SegmentCam::sample_uniform`]
/// (document 002's buffer).
///
/// ```
/// use ecam_core::CamCurve;
/// use ecam_core::segments::{InterpolationPoint, SegmentCam, SegmentLaw, SegmentSpec};
///
/// // Synchronous at 2 pulses/count, then a poly-5 back to the next cycle.
/// let cam = SegmentCam::new(
///     InterpolationPoint { velocity: Some(2.0), ..InterpolationPoint::new(0, 0) },
///     vec![
///         SegmentSpec::new(SegmentLaw::Rise(ecam_core::MotionLaw::ConstantVelocity), 100, 200)
///             .with_velocity(2.0),
///         SegmentSpec::new(SegmentLaw::Poly5, 1000, 1000).with_velocity(2.0),
///     ],
/// )?;
/// let k = cam.eval(100.0, &mut ecam_core::Cursor::new());
/// assert!((k.v - 2.0).abs() < 1e-12); // the poly-5 leaves at the sync speed
/// assert_eq!(cam.continuity().cam.to_string(), "C2");
/// # Ok::<(), ecam_core::segments::SegmentError>(())
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "RawCam", into = "RawCam")]
pub struct SegmentCam {
    start: InterpolationPoint,
    segments: Vec<SegmentSpec>,
    shapes: Vec<Shape>,
}

/// The JSON/TOML shape: `{"start": {...}, "segments": [{"law", "master", "slave", ...}]}`.
#[derive(Clone, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCam {
    #[serde(default)]
    start: InterpolationPoint,
    segments: Vec<SegmentSpec>,
}

impl TryFrom<RawCam> for SegmentCam {
    type Error = SegmentError;
    fn try_from(raw: RawCam) -> Result<Self, SegmentError> {
        Self::new(raw.start, raw.segments)
    }
}

impl From<SegmentCam> for RawCam {
    fn from(cam: SegmentCam) -> Self {
        Self {
            start: cam.start,
            segments: cam.segments,
        }
    }
}

impl SegmentCam {
    /// Checks and solves a cam: the points in master order, each segment's
    /// law solved for the values its points fix (free values it adapts to
    /// are 0), then each point's fixed values checked against what the
    /// segments on both sides give there.
    ///
    /// # Errors
    /// [`SegmentError::NoSegments`]; [`SegmentError::OutOfRange`] or
    /// [`SegmentError::MasterNotIncreasing`] naming the point;
    /// [`SegmentError::CannotMeet`] where a law cannot give a value its
    /// point asks for (a rest-to-rest law where the point wants a velocity);
    /// a segment resolution outside 1..=512.
    pub fn new(
        start: InterpolationPoint,
        segments: Vec<SegmentSpec>,
    ) -> Result<Self, SegmentError> {
        check_points(&start, &segments)?;
        let mut shapes = Vec::with_capacity(segments.len());
        let mut from = start;
        for (i, seg) in segments.iter().enumerate() {
            let to = seg.end();
            let (shape, beta) = solve_segment(seg.law, &from, &to);
            let rise = (to.slave - from.slave) as f64;
            let adapts = seg.law.adapts();
            for (point, p, u) in [(i, &from, 0.0), (i + 1, &to, 1.0)] {
                for q in Quantity::ALL {
                    let Some(wanted) = p.get(q) else { continue };
                    let adapted = match q {
                        Quantity::Velocity => adapts.velocity,
                        Quantity::Acceleration => adapts.acceleration,
                        Quantity::Jerk => adapts.jerk,
                    };
                    // Met by construction (up to rounding, which the
                    // comparison below could mistake for a miss on a dwell).
                    if adapted {
                        continue;
                    }
                    let gives = value_at(&shape, beta, u, q);
                    let ends = [from.get(q), to.get(q)]
                        .into_iter()
                        .flatten()
                        .fold(0.0_f64, |m, v| m.max(v.abs()));
                    let scale = (rise.abs() / libm::pow(beta, f64::from(q.order()))).max(ends);
                    if !agree(gives, wanted, scale) {
                        return Err(SegmentError::CannotMeet {
                            point,
                            master: p.master,
                            segment: i + 1,
                            law: seg.law,
                            quantity: q,
                            wanted,
                            gives,
                        });
                    }
                }
            }
            shapes.push(shape);
            from = to;
        }
        Ok(Self {
            start,
            segments,
            shapes,
        })
    }

    /// The cam after [`make_continuous`](super::make_continuous): every free
    /// boundary value filled in from the neighbouring segments.
    ///
    /// # Errors
    /// As [`SegmentCam::new`], and [`SegmentError::Conflict`] where two
    /// neighbouring laws fix a velocity or acceleration differently.
    pub fn continuous(
        start: InterpolationPoint,
        segments: Vec<SegmentSpec>,
    ) -> Result<Self, SegmentError> {
        let (start, segments) = super::fill::make_continuous(start, segments)?;
        Self::new(start, segments)
    }

    /// The first point.
    pub fn start(&self) -> &InterpolationPoint {
        &self.start
    }

    /// The segments, each with its end point, in master order.
    pub fn segments(&self) -> &[SegmentSpec] {
        &self.segments
    }

    /// Every point: the start, then each segment's end.
    pub fn points(&self) -> Vec<InterpolationPoint> {
        core::iter::once(self.start)
            .chain(self.segments.iter().map(SegmentSpec::end))
            .collect()
    }

    fn point(&self, index: usize) -> InterpolationPoint {
        match index.checked_sub(1).and_then(|i| self.segments.get(i)) {
            Some(seg) => seg.end(),
            None => self.start,
        }
    }

    /// Segment `i`'s (0-based) first master and its span.
    fn span(&self, i: usize) -> (f64, f64) {
        let from = self.point(i).master;
        let to = self.point(i + 1).master;
        (from as f64, (to - from) as f64)
    }

    /// Kinematics of segment `i` (0-based) at its normalised master `u`,
    /// per count.
    pub(crate) fn segment_at(&self, i: usize, u: f64) -> Kinematics {
        self.per_count(i, self.shapes[i].at(u))
    }

    /// As [`SegmentCam::segment_at`], at a knot of its law the value just
    /// before it.
    fn segment_before(&self, i: usize, u: f64) -> Kinematics {
        self.per_count(i, self.shapes[i].at_before(u))
    }

    /// A shape's value in units of `u` as kinematics per count of segment `i`.
    fn per_count(&self, i: usize, k: Kinematics) -> Kinematics {
        let (_, beta) = self.span(i);
        let base = self.point(i).slave as f64;
        let inv = 1.0 / beta;
        Kinematics {
            s: base + k.s,
            v: k.v * inv,
            a: k.a * inv * inv,
            j: k.j * inv * inv * inv,
        }
    }

    /// The coefficients of segment `i` (0-based) when it is a poly-5 or
    /// poly-7: `S(u) = Σ c[k] uᵏ`, the slave travel from its first point
    /// over its normalised master `u = (master − first)/span`.
    pub fn polynomial(&self, i: usize) -> Option<super::poly::Polynomial> {
        match self.shapes.get(i) {
            Some(Shape::Polynomial(p)) => Some(*p),
            _ => None,
        }
    }

    /// Each segment's peaks: the characteristic values `Cv`, `Ca`, `Cj`
    /// and the peak velocity, acceleration and jerk in pulses per count (ⁿ).
    pub fn peaks(&self) -> Vec<SegmentPeaks> {
        (0..self.segments.len())
            .map(|i| {
                let (from, to) = (self.point(i), self.point(i + 1));
                SegmentPeaks::of(
                    i + 1,
                    self.segments[i].law,
                    &self.shapes[i],
                    (from.master, from.slave),
                    (to.master, to.slave),
                )
            })
            .collect()
    }

    /// Points to draw the cam with: `per_segment + 1` evenly spaced samples
    /// over every segment, both ends included and each evaluated on its own
    /// segment, and both sides of a knot where a law's acceleration turns,
    /// so a step shows as a vertical edge (two samples at the same master).
    pub fn sample_segments(&self, per_segment: usize) -> Vec<(f64, Kinematics)> {
        let per = per_segment.max(1);
        let mut out = Vec::with_capacity(self.segments.len().saturating_mul(per + 1));
        for i in 0..self.segments.len() {
            let (lo, beta) = self.span(i);
            let mut knots = self.shapes[i].acceleration_knots().iter().peekable();
            for k in 0..=per {
                let u = k as f64 / per as f64;
                // Both sides of a knot where the law's acceleration turns.
                let mut on_knot = false;
                while let Some(&&knot) = knots.peek().filter(|&&&knot| knot <= u) {
                    out.push((lo + beta * knot, self.segment_before(i, knot)));
                    out.push((lo + beta * knot, self.segment_at(i, knot)));
                    on_knot |= knot == u;
                    knots.next();
                }
                if !on_knot {
                    out.push((lo + beta * u, self.segment_at(i, u)));
                }
            }
        }
        out
    }

    /// How many table points each segment gets from `total_resolution`
    /// (the rules of [`crate::SegmentProfile::sample`]).
    ///
    /// # Errors
    /// As [`SegmentCam::sample`].
    pub fn resolutions(&self, total_resolution: u16) -> Result<Vec<u16>, TableError> {
        let wanted: Vec<Option<u16>> = self.segments.iter().map(|s| s.resolution).collect();
        distribute(total_resolution, &wanted)
    }

    /// The point table a PLC runs, sampled as [`crate::SegmentProfile::sample`]
    /// samples a profile: `total_resolution` points (10..=512), points shared
    /// among segments without their own resolution, evenly spaced in whole
    /// counts, slaves rounded to whole pulses, interpolation points exact.
    ///
    /// # Errors
    /// 6781 for a total below 10 or resolutions that do not fit, 6783 above 512.
    pub fn sample(&self, total_resolution: u16) -> Result<PointTable, TableError> {
        let per_segment = self.resolutions(total_resolution)?;
        let ends: Vec<CamPoint> = self
            .segments
            .iter()
            .map(|s| CamPoint::new(s.master, s.slave))
            .collect();
        let start = CamPoint::new(self.start.master, self.start.slave);
        sample_spans(start, &ends, &per_segment, |i, u| self.segment_at(i, u).s)
    }

    /// Document 002's evenly spaced buffer: `values` slave values over the
    /// cam's master span (`CamCounts`), as
    /// [`crate::SegmentProfile::sample_uniform`].
    ///
    /// # Errors
    /// Fewer than two values, a span outside 2..=2²⁹, a value beyond 32 bits.
    pub fn sample_uniform(&self, values: usize) -> Result<UniformTable, TableError> {
        sample_uniform(self, values)
    }

    fn locate(&self, master: f64, cursor: &mut Cursor) -> usize {
        let last = self.segments.len() - 1;
        let holds = |i: usize| {
            let (lo, beta) = self.span(i);
            (master >= lo || i == 0) && (master < lo + beta || i == last)
        };
        let guess = cursor.segment.min(last);
        let found = if holds(guess) {
            guess
        } else if guess < last && holds(guess + 1) {
            guess + 1
        } else if guess > 0 && holds(guess - 1) {
            guess - 1
        } else {
            self.segments
                .partition_point(|s| (s.master as f64) <= master)
                .min(last)
        };
        cursor.segment = found;
        found
    }
}

impl TryFrom<&crate::SegmentProfile> for SegmentCam {
    type Error = SegmentError;
    /// The same cam as segments: each profile segment's law as a
    /// [`SegmentLaw::Rise`], its resolution kept, every boundary value free.
    fn try_from(profile: &crate::SegmentProfile) -> Result<Self, SegmentError> {
        let start = profile.start();
        let segments = profile
            .segments()
            .iter()
            .map(|s| SegmentSpec {
                resolution: s.resolution,
                ..SegmentSpec::new(SegmentLaw::Rise(s.law), s.master_end, s.slave_end)
            })
            .collect();
        Self::new(InterpolationPoint::new(start.master, start.slave), segments)
    }
}

/// Where the segments meet (the interpolation points), where a rise law's
/// acceleration turns inside its segment, and the seam
/// ([`crate::table::steps`]).
impl Corners for SegmentCam {
    fn corners(&self) -> Vec<Corner> {
        let n = self.segments.len();
        let mut corners = Vec::with_capacity(n.saturating_mul(2));
        for i in 0..n {
            let (lo, beta) = self.span(i);
            let knots = self.shapes[i].acceleration_knots();
            for &u in knots {
                corners.push(Corner {
                    master: lo + beta * u,
                    before: self.segment_before(i, u),
                    after: self.segment_at(i, u),
                    reach: beta * u.max(1.0 - u),
                    seam: false,
                });
            }
            let next = if i + 1 < n { i + 1 } else { 0 };
            let next_beta = self.span(next).1;
            let next_knot = self.shapes[next].acceleration_knots().first().copied();
            corners.push(Corner {
                master: lo + beta,
                before: self.segment_at(i, 1.0),
                after: self.segment_at(next, 0.0),
                // The stretches beside the point run to the laws' knots.
                reach: (beta * (1.0 - knots.last().copied().unwrap_or(0.0)))
                    .max(next_beta * next_knot.unwrap_or(1.0)),
                seam: i + 1 == n,
            });
        }
        corners
    }
}

impl CamCurve for SegmentCam {
    fn master_first(&self) -> i64 {
        self.start.master
    }
    fn master_last(&self) -> i64 {
        self.segments.last().map_or(self.start.master, |s| s.master)
    }
    fn slave_first(&self) -> i64 {
        self.start.slave
    }
    fn slave_last(&self) -> i64 {
        self.segments.last().map_or(self.start.slave, |s| s.slave)
    }
    fn segment_count(&self) -> usize {
        self.segments.len()
    }
    fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics {
        let master = if master.is_nan() {
            self.master_first() as f64
        } else {
            master
        };
        let i = self.locate(master, cursor);
        let (lo, beta) = self.span(i);
        self.segment_at(i, (master - lo) / beta)
    }
}
