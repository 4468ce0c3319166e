//! Segment profiles: key points joined by motion laws, as the PC editor's
//! table dialog and the PLC's key-point generator (ECAMTBX K2) describe a cam.

use alloc::vec::Vec;

use crate::table::resolution;
use crate::table::uniform::MAX_CAM_COUNTS;
use crate::{
    CamCurve, CamPoint, Cursor, Kinematics, MotionLaw, PointTable, TableError, UniformTable,
};

/// Largest position magnitude a profile accepts (2⁵²): every position and
/// every difference of two positions is then exact in `f64`.
pub const MAX_PROFILE_POSITION: i64 = 1 << 52;

/// Largest resolution a single segment may ask for (document 000, K2: 1–512).
pub const MAX_SEGMENT_RESOLUTION: u16 = 512;

/// One segment: from the previous key point to (`master_end`, `slave_end`)
/// along `law`.
// Unknown keys are refused: a misspelt `resolution` would otherwise silently
// fall back to sharing the total.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Segment {
    /// Master position at the end of the segment (counts).
    pub master_end: i64,
    /// Slave position at the end of the segment (pulses).
    pub slave_end: i64,
    /// The law the slave follows across the segment.
    pub law: MotionLaw,
    /// Number of table points this segment gets when sampled (1..=512);
    /// `None` shares what the total resolution leaves equally.
    #[serde(default)]
    pub resolution: Option<u16>,
}

impl Segment {
    /// A segment to (`master_end`, `slave_end`) along `law`, resolution unset.
    pub const fn new(master_end: i64, slave_end: i64, law: MotionLaw) -> Self {
        Self {
            master_end,
            slave_end,
            law,
            resolution: None,
        }
    }

    /// The same segment with a fixed resolution.
    pub const fn with_resolution(mut self, resolution: u16) -> Self {
        self.resolution = Some(resolution);
        self
    }
}

/// A cam made of segments that start at `start` and end at their key points.
///
/// It evaluates exactly (the laws' closed forms scaled onto each segment);
/// [`SegmentProfile::sample`] turns it into the point table a PLC runs.
///
/// ```
/// use ecam_core::{CamCurve, CamPoint, Cursor, MotionLaw, Segment, SegmentProfile};
///
/// let profile = SegmentProfile::new(
///     CamPoint::new(0, 0),
///     vec![
///         Segment::new(1000, 500, MotionLaw::Cycloid),
///         Segment::new(2000, 500, MotionLaw::Cycloid), // dwell
///     ],
/// )?;
/// let mut c = Cursor::new();
/// assert_eq!(profile.position(500.0, &mut c), 250.0);
/// let table = profile.sample(100)?;
/// assert_eq!(table.points().len(), 100);
/// assert_eq!(table.slave_last(), 500);
/// # Ok::<(), ecam_core::TableError>(())
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "RawProfile")]
pub struct SegmentProfile {
    start: CamPoint,
    segments: Vec<Segment>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawProfile {
    start: CamPoint,
    segments: Vec<Segment>,
}

impl TryFrom<RawProfile> for SegmentProfile {
    type Error = TableError;
    fn try_from(raw: RawProfile) -> Result<Self, TableError> {
        Self::new(raw.start, raw.segments)
    }
}

fn in_range(value: i64) -> bool {
    (-MAX_PROFILE_POSITION..=MAX_PROFILE_POSITION).contains(&value)
}

impl SegmentProfile {
    /// Checks and wraps a profile. Section 0 is `start`; segment `i` ends at
    /// section `i + 1`, which is the number errors name.
    ///
    /// # Errors
    /// [`TableError::SectionCount`] without segments;
    /// [`TableError::ValueOutOfRange`] for a position beyond ±2⁵²;
    /// [`TableError::MasterNotIncreasing`] when a segment does not end after
    /// it starts; [`TableError::Parameter`] for a resolution outside 1..=512.
    pub fn new(start: CamPoint, segments: Vec<Segment>) -> Result<Self, TableError> {
        if segments.is_empty() {
            return Err(TableError::SectionCount {
                count: 0,
                min: 1,
                max: usize::MAX,
            });
        }
        if !in_range(start.master) || !in_range(start.slave) {
            return Err(TableError::ValueOutOfRange { section: 0 });
        }
        let mut previous = start.master;
        for (i, seg) in segments.iter().enumerate() {
            let section = i + 1;
            if !in_range(seg.master_end) || !in_range(seg.slave_end) {
                return Err(TableError::ValueOutOfRange { section });
            }
            if seg.master_end <= previous {
                return Err(TableError::MasterNotIncreasing { section });
            }
            if let Some(r) = seg.resolution {
                if r == 0 || r > MAX_SEGMENT_RESOLUTION {
                    return Err(TableError::Parameter {
                        name: "segment resolution",
                        reason: "must be between 1 and 512",
                    });
                }
            }
            previous = seg.master_end;
        }
        Ok(Self { start, segments })
    }

    /// The start point (section 0).
    pub fn start(&self) -> CamPoint {
        self.start
    }

    /// The segments, in master order.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The key points: the start, then each segment's end.
    pub fn key_points(&self) -> impl Iterator<Item = CamPoint> + '_ {
        core::iter::once(self.start).chain(
            self.segments
                .iter()
                .map(|s| CamPoint::new(s.master_end, s.slave_end)),
        )
    }

    /// Where segment `i` starts.
    fn segment_start(&self, i: usize) -> CamPoint {
        match i.checked_sub(1).and_then(|p| self.segments.get(p)) {
            Some(prev) => CamPoint::new(prev.master_end, prev.slave_end),
            None => self.start,
        }
    }

    /// How many table points each segment gets from `total_resolution`
    /// (see [`SegmentProfile::sample`]).
    ///
    /// # Errors
    /// As [`SegmentProfile::sample`].
    pub fn resolutions(&self, total_resolution: u16) -> Result<Vec<u16>, TableError> {
        let wanted: Vec<Option<u16>> = self.segments.iter().map(|s| s.resolution).collect();
        resolution::distribute(total_resolution, &wanted)
    }

    /// The point table a PLC runs: the start point, then each segment's
    /// points evenly spaced over its master span, the last exactly on the
    /// key point.
    ///
    /// `total_resolution` (10..=512) is the number of points in the table,
    /// the start point included (the register block's section count). A
    /// segment with a resolution gets that many points; the points left over
    /// are shared equally by the segments without one, the first ones getting
    /// one more when the share is not whole. Slave values are rounded to
    /// whole pulses; key points are exact.
    ///
    /// # Errors
    /// [`TableError::Parameter`] (6781) for a total below 10, set resolutions
    /// that leave nothing for the others or exceed the total, or a segment
    /// shorter (in master counts) than its number of points;
    /// [`TableError::SectionCount`] (6783) for a total above 512.
    pub fn sample(&self, total_resolution: u16) -> Result<PointTable, TableError> {
        let per_segment = self.resolutions(total_resolution)?;
        let ends: Vec<CamPoint> = self.key_points().skip(1).collect();
        sample_spans(self.start, &ends, &per_segment, |i, u| {
            let from = self.segment_start(i);
            let seg = self.segments[i];
            from.slave as f64 + (seg.slave_end - from.slave) as f64 * seg.law.eval(u).s
        })
    }

    /// The evenly spaced table of document 002's motion processor: `values`
    /// slave values at `k · span / (values − 1)` counts from the start
    /// (fractional spacing allowed), rounded to whole pulses; `CamCounts` is
    /// the profile's master span. The uniform table's master starts at 0, so
    /// it is this profile shifted by `−master_first`.
    ///
    /// # Errors
    /// As [`UniformTable::new`]: fewer than two values, a span outside
    /// 2..=2²⁹, or a slave value beyond 32 bits.
    pub fn sample_uniform(&self, values: usize) -> Result<UniformTable, TableError> {
        sample_uniform(self, values)
    }

    /// Points to draw the profile with: `per_segment + 1` evenly spaced
    /// samples over every segment, both ends included and each evaluated on
    /// its own segment, and both sides of every knot where a law's
    /// acceleration turns ([`MotionLaw::acceleration_knots`](crate::MotionLaw::acceleration_knots)),
    /// so every step shows as a vertical edge (two samples at one master).
    pub fn sample_pieces(&self, per_segment: usize) -> Vec<(f64, Kinematics)> {
        let per_segment = per_segment.max(1);
        let mut out = Vec::with_capacity(self.segments.len().saturating_mul(per_segment + 3));
        for (i, seg) in self.segments.iter().enumerate() {
            let from = self.segment_start(i);
            let span = seg.master_end.saturating_sub(from.master) as f64;
            let rise = seg.slave_end.saturating_sub(from.slave) as f64;
            let at = |u: f64, k: Kinematics| {
                (
                    from.master as f64 + span * u,
                    k.scaled(from.slave as f64, rise, span),
                )
            };
            let mut knots = seg.law.acceleration_knots().iter().peekable();
            for k in 0..=per_segment {
                let u = k as f64 / per_segment as f64;
                let mut on_knot = false;
                while let Some(&&knot) = knots.peek().filter(|&&&knot| knot <= u) {
                    out.push(at(knot, seg.law.eval(knot)));
                    out.push(at(knot, seg.law.eval_after(knot)));
                    on_knot |= knot == u;
                    knots.next();
                }
                if !on_knot {
                    out.push(at(u, seg.law.eval_after(u)));
                }
            }
        }
        out
    }

    /// Index of the segment holding `master`: the cursor's, a neighbour, or
    /// a binary search.
    fn locate(&self, master: f64, cursor: &mut Cursor) -> usize {
        let last = self.segments.len() - 1;
        let holds = |i: usize| {
            let lo = self.segment_start(i).master as f64;
            let hi = self.segments[i].master_end as f64;
            // Half-open [lo, hi), as point tables: a joint belongs to the
            // segment starting there.
            (master >= lo || i == 0) && (master < hi || i == last)
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
                .partition_point(|s| (s.master_end as f64) <= master)
                .min(last)
        };
        cursor.segment = found;
        found
    }
}

/// The point table of a cam made of segments between key points: `start`,
/// then `per_segment[i]` points evenly spaced in whole counts over segment
/// `i` (which ends at `ends[i]`), the last exactly on its key point, the
/// others at `slave_at(i, u)` (the exact slave at the normalised master `u`
/// of segment `i`) rounded to whole pulses. The sampling rules of
/// [`SegmentProfile::sample`], shared by every segment cam.
///
/// # Errors
/// A segment shorter (in master counts) than its number of points (6781);
/// a table [`PointTable::new`] refuses.
pub(crate) fn sample_spans(
    start: CamPoint,
    ends: &[CamPoint],
    per_segment: &[u16],
    slave_at: impl Fn(usize, f64) -> f64,
) -> Result<PointTable, TableError> {
    let capacity = per_segment.iter().map(|&r| usize::from(r)).sum::<usize>() + 1;
    let mut points = Vec::with_capacity(capacity);
    points.push(start);
    let mut from = start;
    for (i, (end, &count)) in ends.iter().zip(per_segment).enumerate() {
        // Positions are within ±2^52, so spans and products fit i128 easily.
        let span = i128::from(end.master) - i128::from(from.master);
        let count_wide = i128::from(count);
        if span < count_wide {
            return Err(TableError::Parameter {
                name: "segment resolution",
                reason: "is larger than the segment's length in master counts",
            });
        }
        for k in 1..=count_wide {
            if k == count_wide {
                points.push(*end);
                continue;
            }
            let offset = span * k / count_wide;
            // offset < span ≤ 2^53: exact in f64 and i64.
            let master = from.master + offset as i64;
            let slave = slave_at(i, offset as f64 / span as f64);
            points.push(CamPoint::new(master, libm::round(slave) as i64));
        }
        from = *end;
    }
    PointTable::new(points)
}

/// The evenly spaced table of document 002 sampled from `curve` (see
/// [`SegmentProfile::sample_uniform`]).
///
/// # Errors
/// As [`SegmentProfile::sample_uniform`].
pub(crate) fn sample_uniform(
    curve: &impl CamCurve,
    values: usize,
) -> Result<UniformTable, TableError> {
    if values < 2 {
        return Err(TableError::SectionCount {
            count: values,
            min: 2,
            max: usize::MAX,
        });
    }
    let span = curve.master_span();
    if !(2..=MAX_CAM_COUNTS).contains(&span) {
        return Err(TableError::Parameter {
            name: "CamCounts (the profile's master span)",
            reason: "must be between 2 and 2^29 (536870912)",
        });
    }
    let first = curve.master_first() as f64;
    let pieces = (values - 1) as f64;
    let masters: Vec<f64> = (0..values)
        .map(|k| first + span as f64 * k as f64 / pieces)
        .collect();
    let mut positions = alloc::vec![0.0; values];
    curve.positions_into(&masters, &mut positions);
    if let Some(end) = positions.last_mut() {
        *end = curve.slave_last() as f64;
    }
    let slaves = positions.iter().map(|&s| libm::round(s) as i64).collect();
    UniformTable::new(slaves, span)
}

impl CamCurve for SegmentProfile {
    fn master_first(&self) -> i64 {
        self.start.master
    }
    fn master_last(&self) -> i64 {
        self.segments
            .last()
            .map_or(self.start.master, |s| s.master_end)
    }
    fn slave_first(&self) -> i64 {
        self.start.slave
    }
    fn slave_last(&self) -> i64 {
        self.segments
            .last()
            .map_or(self.start.slave, |s| s.slave_end)
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
        let from = self.segment_start(i);
        let seg = self.segments[i];
        let span = (seg.master_end - from.master) as f64;
        let rise = (seg.slave_end - from.slave) as f64;
        let u = (master - from.master as f64) / span;
        // At a law's knot (the constant-acceleration law's middle) the value
        // after it, as a joint belongs to the segment starting there.
        seg.law.eval_after(u).scaled(from.slave as f64, rise, span)
    }
}
