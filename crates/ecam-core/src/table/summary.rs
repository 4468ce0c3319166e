//! What a designer wants to know about a cam at a glance.

use alloc::vec::Vec;

use super::continuity::Continuity;
use super::derivatives;
use super::steps::{Corners, Steps};
use crate::{CamCurve, Cursor, Kinematics};

/// A cam's key figures.
///
/// ```
/// use ecam_core::{CamPoint, MotionLaw, Segment, SegmentProfile};
/// use ecam_core::table::{Continuity, Summary};
///
/// let p = SegmentProfile::new(
///     CamPoint::new(0, 0),
///     vec![
///         Segment::new(100, 0, MotionLaw::Cycloid),
///         Segment::new(200, 1000, MotionLaw::Cycloid),
///     ],
/// )?;
/// let s = Summary::of(&p);
/// assert_eq!(s.continuity, Continuity::C2);
/// assert!((s.peak_velocity - 20.0).abs() < 1e-6); // Cv·h/β = 2·1000/100
/// # Ok::<(), ecam_core::TableError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Summary {
    /// Number of sections (segments).
    pub sections: usize,
    /// Master length of one cycle (counts).
    pub master_span: i64,
    /// Slave change over one cycle (pulses).
    pub stroke: i64,
    /// Lowest slave position reached (pulses).
    pub slave_min: f64,
    /// Highest slave position reached (pulses).
    pub slave_max: f64,
    /// Peak |slave velocity / master velocity|.
    pub peak_velocity: f64,
    /// Peak |d²slave/dmaster²| in pulses per count² (impulses at joints are
    /// not counted: see `continuity`). For a curve made only of straight
    /// sections (a point table, an evenly spaced table), whose acceleration
    /// is zero inside every section and all at the joints, this is instead
    /// an estimate of the motion the points sample: at each joint, the
    /// change of section velocity divided by the mean length of the two
    /// sections that meet there, `|v₂ − v₁| / ((L₁ + L₂)/2)` (the central
    /// second difference); the largest over the interior joints.
    pub peak_acceleration: f64,
    /// Weakest continuity found at a corner inside the cycle: `C0` where
    /// velocity steps, `C1` where only acceleration does, by the rule of
    /// [`super::steps`] (the corners that rule looks at, the tolerance it
    /// keeps).
    pub continuity: Continuity,
    /// Continuity where one cycle ends and the next begins, for a cam that
    /// repeats with its stroke added (repeat/incremental coupling: the
    /// position meets by construction, velocity and acceleration are
    /// compared, by the rule of [`super::steps`]). A periodic coupling also
    /// jumps by `stroke` unless it is 0.
    pub seam: Continuity,
}

/// Relative size of a jump, against the curve's own scale, that counts as a
/// discontinuity; laws evaluated in `f64` agree at joints to ~1e-12.
const JUMP_TOLERANCE: f64 = 1e-7;

/// Samples per section in the second pass: divisible by 2, 8, 9 and 16, so
/// the peaks of every law in [`crate::law`] (at u = 1/2, 1/8, 1/16, 1/9…)
/// fall on a sample.
const SAMPLES_PER_SECTION: usize = 288;

impl Summary {
    /// Measures `curve`: a sweep (at least 4096 samples, 32 per section)
    /// finds the joints between sections by bisection on the cursor's
    /// segment index and compares both sides of each; then every section is
    /// sampled 289 times, ends included, for the peaks. Velocity and
    /// acceleration continuity are those of its [`Steps`].
    pub fn of(curve: &(impl CamCurve + Corners)) -> Self {
        let first = curve.master_first() as f64;
        let last = curve.master_last() as f64;
        let span = last - first;
        let sections = curve.segment_count();
        let samples = sections.saturating_mul(32).clamp(4096, 1 << 20);

        let mut acc = Extremes::new(curve.slave_first() as f64);
        let mut worst_jump = Jumps::default();
        // Where each section starts (master, segment index), the first included.
        let mut starts: Vec<(f64, usize)> = Vec::new();
        // Velocity change at the start of each section after the first.
        let mut velocity_steps: Vec<f64> = Vec::new();
        let mut cursor = Cursor::new();
        let mut prev_master = first;
        let mut prev_segment = {
            curve.eval(first, &mut cursor);
            cursor.segment
        };
        starts.push((first, prev_segment));
        for i in 1..=samples {
            let master = first + span * (i as f64 / samples as f64);
            curve.eval(master, &mut cursor);
            let segment = cursor.segment;
            let mut lo = prev_master;
            let mut current = prev_segment;
            // One bisection per joint crossed since the last sample.
            while segment > current {
                let (left, right, at) = bisect(curve, lo, master, current);
                worst_jump.add(&left, &right);
                let next = right_segment(curve, at, current);
                if next <= current {
                    break;
                }
                starts.push((at, next));
                velocity_steps.push(right.v - left.v);
                lo = at;
                current = next;
            }
            prev_master = master;
            prev_segment = segment;
        }

        for (k, &(from, segment)) in starts.iter().enumerate() {
            let to = starts.get(k + 1).map_or(last, |next| next.0);
            for i in 0..=SAMPLES_PER_SECTION {
                let u = i as f64 / SAMPLES_PER_SECTION as f64;
                // Stay inside the section: its end belongs to the next one.
                let master = if i == SAMPLES_PER_SECTION {
                    to
                } else {
                    from + (to - from) * u
                };
                let mut c = Cursor { segment };
                acc.add(&curve.eval(master, &mut c));
            }
        }

        // Every curve here is continuous by construction; a position jump
        // would still show (the steps rule only looks at derivatives).
        let scale_s = (acc.slave_max - acc.slave_min).abs().max(1.0);
        let jumps = worst_jump.s > JUMP_TOLERANCE * scale_s;
        let (continuity, seam) = Steps::of(curve).continuity();
        let continuity = if jumps {
            Continuity::Discontinuous
        } else {
            continuity
        };
        // Straight sections only (see `peak_acceleration`); estimated after
        // the classification, which keeps comparing the sections' own
        // derivatives.
        let peak_acceleration = if acc.peak_a == 0.0 {
            joint_acceleration(&starts, &velocity_steps, first, last)
        } else {
            acc.peak_a
        };
        Self {
            sections,
            master_span: curve.master_span(),
            stroke: curve.stroke(),
            slave_min: acc.slave_min,
            slave_max: acc.slave_max,
            peak_velocity: acc.peak_v,
            peak_acceleration,
            continuity,
            seam,
        }
    }
}

/// Largest `|Δv| / mean length of the two sections` over the joints (see
/// [`derivatives::joint_acceleration`]). Joint `k` is `starts[k + 1]`, with
/// the velocity step `steps[k]`; its sections run from `starts[k]` to the
/// next joint (or the end `last`).
fn joint_acceleration(starts: &[(f64, usize)], steps: &[f64], first: f64, last: f64) -> f64 {
    let mut peak: f64 = 0.0;
    for (k, &step) in steps.iter().enumerate() {
        let before = starts.get(k).map_or(first, |s| s.0);
        let after = starts.get(k + 2).map_or(last, |s| s.0);
        // `max` ignores NaN.
        peak = peak.max(derivatives::joint_acceleration(step, before, after).abs());
    }
    peak
}

/// Running extremes of the samples.
struct Extremes {
    slave_min: f64,
    slave_max: f64,
    peak_v: f64,
    peak_a: f64,
}

impl Extremes {
    fn new(s: f64) -> Self {
        Self {
            slave_min: s,
            slave_max: s,
            peak_v: 0.0,
            peak_a: 0.0,
        }
    }
    fn add(&mut self, k: &Kinematics) {
        // `max`/`min` ignore NaN, so a misbehaving curve cannot poison the summary.
        self.slave_min = self.slave_min.min(k.s);
        self.slave_max = self.slave_max.max(k.s);
        self.peak_v = self.peak_v.max(k.v.abs());
        self.peak_a = self.peak_a.max(k.a.abs());
    }
}

/// Largest jumps seen at joints.
#[derive(Default)]
struct Jumps {
    s: f64,
    v: f64,
    a: f64,
}

impl Jumps {
    fn add(&mut self, left: &Kinematics, right: &Kinematics) {
        self.s = self.s.max((right.s - left.s).abs());
        self.v = self.v.max((right.v - left.v).abs());
        self.a = self.a.max((right.a - left.a).abs());
    }
}

/// The segment the curve reports at `master`, searching from `hint`.
fn right_segment(curve: &impl CamCurve, master: f64, hint: usize) -> usize {
    let mut c = Cursor { segment: hint };
    curve.eval(master, &mut c);
    c.segment
}

/// Narrows `(lo, hi]` onto the end of segment `segment`: returns the
/// kinematics just inside it, just past it, and the master just past it.
fn bisect(
    curve: &impl CamCurve,
    mut lo: f64,
    mut hi: f64,
    segment: usize,
) -> (Kinematics, Kinematics, f64) {
    for _ in 0..80 {
        let mid = lo + (hi - lo) / 2.0;
        if mid <= lo || mid >= hi {
            break;
        }
        if right_segment(curve, mid, segment) > segment {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let left = curve.eval(lo, &mut Cursor { segment });
    let right = curve.eval(hi, &mut Cursor { segment });
    (left, right, hi)
}
