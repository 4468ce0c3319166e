//! Each segment's characteristic values and peaks.

use super::law::SegmentLaw;
use super::shape::Shape;

/// Peaks of one segment, from closed forms (`docs/design.md`, "Continuity
/// and peaks").
///
/// `cv`, `ca`, `cj` are the dimensionless factors of the cam-design tables:
/// a segment rising `h` over `β` counts peaks at `cv·|h|/β`, `ca·|h|/β²`,
/// `cj·|h|/β³`. They are `None` for a segment that does not rise (`h = 0`:
/// a dwell, or a motion that returns to where it started, whose peaks are
/// given in pulses only), and infinite where the segment has an impulse
/// inside (the jerk of constant acceleration at mid-rise). Impulses at the
/// points belong to the joints ([`super::ContinuityReport`]).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SegmentPeaks {
    /// Segment number (1-based: segment `k` ends at point `k`).
    pub segment: usize,
    /// Its law.
    pub law: SegmentLaw,
    /// First and last master (counts).
    pub master: (i64, i64),
    /// Slave travel from its first point to its last (pulses).
    pub rise: i64,
    /// Peak |velocity| / (|h|/β).
    pub cv: Option<f64>,
    /// Peak |acceleration| / (|h|/β²).
    pub ca: Option<f64>,
    /// Peak |jerk| / (|h|/β³).
    pub cj: Option<f64>,
    /// Peak |velocity ratio|, pulses/count.
    pub peak_velocity: f64,
    /// Peak |acceleration|, pulses/count².
    pub peak_acceleration: f64,
    /// Peak |jerk|, pulses/count³.
    pub peak_jerk: f64,
}

impl SegmentPeaks {
    /// The peaks of `shape`, segment `segment` from `from` to `to` (master, slave).
    pub(crate) fn of(
        segment: usize,
        law: SegmentLaw,
        shape: &Shape,
        from: (i64, i64),
        to: (i64, i64),
    ) -> Self {
        let beta = (to.0 - from.0) as f64;
        let rise = to.1 - from.1;
        let (pv, pa, pj) = shape.peaks();
        let h = (rise as f64).abs();
        let factor = |peak: f64| (h > 0.0).then(|| peak / h);
        Self {
            segment,
            law,
            master: (from.0, to.0),
            rise,
            cv: factor(pv),
            ca: factor(pa),
            cj: factor(pj),
            peak_velocity: pv / beta,
            peak_acceleration: pa / (beta * beta),
            peak_jerk: pj / (beta * beta * beta),
        }
    }
}
