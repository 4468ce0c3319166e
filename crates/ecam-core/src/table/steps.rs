//! Where a cam's velocity or acceleration steps: the impulses its plots
//! draw, the continuity its summary reports.
//!
//! The rule, in one place for the command line's plots, `ecam table show`
//! and the designer page:
//!
//! - **What an impulse is.** A step of velocity at a master position is an
//!   impulse of acceleration there, of area `v(after) − v(before)`; a step
//!   of acceleration is an impulse of jerk, of area `a(after) − a(before)`.
//! - **Where.** Only at the curve's corners ([`Corner`]): where two pieces
//!   of a generator's design meet, where two segments of a profile meet
//!   and where a law's own acceleration turns (the constant-acceleration
//!   law's middle, [`MotionLaw::acceleration_knots`](crate::MotionLaw::acceleration_knots)),
//!   at every point of a table of straight sections, and at the **seam**,
//!   where the end of one cycle meets the start of the next. Nowhere else.
//!   The seam is read as a repeat cam runs it: the slave carries on from
//!   where the cycle ended (a periodic cam also jumps back by the stroke
//!   there), so its step is `value at the start − value at the end`. It is
//!   reported at the last master.
//! - **How big.** A step counts when, held over the longer of the two
//!   stretches beside its corner (`reach`: the pieces of a design, the
//!   segments of a profile, the sections of a point table), it moves the
//!   slave by at least [`HALF_PULSE`], the rounding every point of a
//!   whole-pulse table carries: `|Δv| · reach ≥ ½` and `|Δa| · reach² / 2
//!   ≥ ½`. (The longer: a step next to a sliver of a piece, such as the
//!   fraction of a count a generator dwells before its first ramp, acts
//!   over the ramp.) A smaller step cannot be told from the rounding of the table
//!   that samples it; a floating-point difference of an exact curve is
//!   many orders below it. (Not a share of the curve's peak: a real step
//!   of a few percent of the peak counts, rounding noise never does.)
//! - **A table known only at its points** ([`Steps::of_columns`]: a file
//!   with velocity, acceleration and jerk columns, no design): a column
//!   steps between two points when it changes by more than its derivative
//!   column, anywhere between its values at the two points, can make it
//!   change (plus the curvature of that column, from its neighbours). The
//!   step lies somewhere after the first point and is reported at the
//!   second; its reach runs to the next such step. At a point the columns
//!   hold the value of the piece starting there, as generators write them.
//!
//! ```
//! use ecam_core::PointTable;
//! use ecam_core::table::steps::Steps;
//!
//! // Document 001's table: straight sections, so velocity steps at its two
//! // inner points (acceleration impulses); its last section's slope is its
//! // first's, so the seam does not step.
//! let t = PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)])?;
//! let steps = Steps::of(&t);
//! let at: Vec<f64> = steps.velocity.iter().map(|s| s.master).collect();
//! assert_eq!(at, [10000.0, 20000.0]);
//! assert!((steps.velocity[0].size + 0.15).abs() < 1e-12); // 0.1 → −0.05
//! assert!(steps.velocity.iter().all(|s| !s.seam));
//! assert!(steps.acceleration.is_empty());
//! # Ok::<(), ecam_core::TableError>(())
//! ```

use alloc::vec::Vec;

use super::continuity::Continuity;
use crate::{CamPoint, CamTable, Kinematics, PointTable, SegmentProfile, UniformTable};

/// The slave movement, in pulses, below which a step is not one: the
/// rounding of every point of a whole-pulse table (each lies within half a
/// pulse of the curve it samples).
pub const HALF_PULSE: f64 = 0.5;

/// Relative size of a floating-point difference between two values of one
/// column that is noise, not a change.
const COLUMN_NOISE: f64 = 1e-9;

/// One corner of a curve: both sides of it, and how far the curve runs
/// beside it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    /// Master position of the corner (the last master for the seam).
    pub master: f64,
    /// The curve just before the corner.
    pub before: Kinematics,
    /// The curve just after it.
    pub after: Kinematics,
    /// Length in master counts of the longer of the two stretches (pieces,
    /// segments, sections) that meet at the corner.
    pub reach: f64,
    /// Whether this is the seam: the end of the cycle meeting its start.
    pub seam: bool,
}

/// One step of a curve: an impulse of the next derivative.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Step {
    /// Master position (counts); the last master for the seam.
    pub master: f64,
    /// The step, after minus before: the impulse's area (pulses/count for a
    /// velocity step, pulses/count² for an acceleration step).
    pub size: f64,
    /// Whether it is the seam's step.
    pub seam: bool,
}

/// Every step of a curve, by the rule of this module.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Steps {
    /// Steps of velocity: impulses of acceleration.
    pub velocity: Vec<Step>,
    /// Steps of acceleration: impulses of jerk.
    pub acceleration: Vec<Step>,
}

/// Whether a velocity step `dv` counts over `reach` counts: it moves the
/// slave by at least [`HALF_PULSE`] there.
pub fn velocity_step_counts(dv: f64, reach: f64) -> bool {
    dv.abs() * reach >= HALF_PULSE
}

/// Whether an acceleration step `da` counts over `reach` counts: it moves
/// the slave by at least [`HALF_PULSE`] there (`|da|·reach²/2`).
pub fn acceleration_step_counts(da: f64, reach: f64) -> bool {
    da.abs() * reach * reach / 2.0 >= HALF_PULSE
}

impl Steps {
    /// The steps at `corners` that count.
    pub fn at_corners(corners: impl IntoIterator<Item = Corner>) -> Self {
        let mut steps = Self::default();
        for c in corners {
            let (dv, da) = (c.after.v - c.before.v, c.after.a - c.before.a);
            let step = |size| Step {
                master: c.master,
                size,
                seam: c.seam,
            };
            if velocity_step_counts(dv, c.reach) {
                steps.velocity.push(step(dv));
            }
            if acceleration_step_counts(da, c.reach) {
                steps.acceleration.push(step(da));
            }
        }
        steps
    }

    /// The steps of `curve`, at its corners.
    pub fn of(curve: &impl Corners) -> Self {
        Self::at_corners(curve.corners())
    }

    /// The steps of a curve known only at `points`, by its velocity,
    /// acceleration and jerk there (`known`, one per point, each the value
    /// of the piece starting at the point): see the module's rule.
    pub fn of_columns(points: &[CamPoint], known: &[Kinematics]) -> Self {
        let n = points.len().min(known.len());
        let x: Vec<f64> = points.iter().take(n).map(|p| p.master as f64).collect();
        let at = |i: usize| known.get(i).copied().unwrap_or_default();
        // Sections (index of their end point) where a column changes by
        // more than the next one explains: (end, Δv rest, Δa rest).
        let mut found: Vec<(usize, f64, f64)> = Vec::new();
        for i in 1..n {
            let h = x[i] - x[i - 1];
            let (k0, k1) = (at(i - 1), at(i));
            // How far the derivative column bends around the section: a
            // smooth one may overshoot its end values by about an eighth
            // of its second difference.
            let bend = |f: fn(&Kinematics) -> f64| {
                let d2 = |m: usize| {
                    if m >= 1 && m + 1 < n {
                        (f(&at(m + 1)) - 2.0 * f(&at(m)) + f(&at(m - 1))).abs()
                    } else {
                        0.0
                    }
                };
                d2(i - 1).max(d2(i)) / 8.0
            };
            let da = unexplained(k1.a - k0.a, h, (k0.j, k1.j), bend(|k| k.j));
            // Acceleration with a corner inside the section (its jerk
            // turning, an S-type ramp's peak) bends by up to h·|Δj|/8 on
            // average beyond its end values.
            let kink = h * (k1.j - k0.j).abs() / 8.0;
            let dv = unexplained(k1.v - k0.v, h, (k0.a, k1.a), bend(|k| k.a).max(kink));
            if da != 0.0 || dv != 0.0 {
                // What the next column explains on average is not part of
                // the step (for a column held between points, none is).
                let rest = |change: f64, d: (f64, f64), flagged: f64| {
                    if flagged == 0.0 {
                        0.0
                    } else {
                        change - h * (d.0 + d.1) / 2.0
                    }
                };
                found.push((
                    i,
                    rest(k1.v - k0.v, (k0.a, k1.a), dv),
                    rest(k1.a - k0.a, (k0.j, k1.j), da),
                ));
            }
        }
        let mut corners = Vec::with_capacity(found.len() + 1);
        let (first, last) = (
            x.first().copied().unwrap_or(0.0),
            x.last().copied().unwrap_or(0.0),
        );
        for (k, &(i, dv, da)) in found.iter().enumerate() {
            // The step lies in (x[i − 1], x[i]]: its stretches run to the
            // neighbouring steps (or the table's ends) from either side.
            let before = k
                .checked_sub(1)
                .and_then(|p| found.get(p))
                .map_or(first, |&(p, ..)| x[p]);
            let after = found.get(k + 1).map_or(last, |&(p, ..)| x[p - 1]);
            corners.push(Corner {
                master: x[i],
                before: Kinematics::default(),
                after: Kinematics {
                    v: dv,
                    a: da,
                    ..Kinematics::default()
                },
                reach: (x[i] - before).max(after - x[i - 1]),
                seam: false,
            });
        }
        if n >= 2 {
            let (end, start) = (at(n - 1), at(0));
            let noise = |a: f64, b: f64| (b - a).abs() > COLUMN_NOISE * a.abs().max(b.abs());
            let (dv, da) = (start.v - end.v, start.a - end.a);
            if noise(end.v, start.v) || noise(end.a, start.a) {
                let into_last = found.last().map_or(first, |&(p, ..)| x[p - 1]);
                let out_of_first = found.first().map_or(last, |&(p, ..)| x[p]);
                corners.push(Corner {
                    master: last,
                    before: end,
                    after: Kinematics {
                        v: end.v + dv,
                        a: end.a + da,
                        ..end
                    },
                    reach: (last - into_last).max(out_of_first - first),
                    seam: true,
                });
            }
        }
        Self::at_corners(corners)
    }

    /// How smooth the curve is inside its cycle and at its seam: `C0` where
    /// velocity steps, `C1` where only acceleration does, `C2` otherwise.
    pub fn continuity(&self) -> (Continuity, Continuity) {
        let class = |seam: bool| {
            if self.velocity.iter().any(|s| s.seam == seam) {
                Continuity::C0
            } else if self.acceleration.iter().any(|s| s.seam == seam) {
                Continuity::C1
            } else {
                Continuity::C2
            }
        };
        (class(false), class(true))
    }
}

/// How far `change` (of a column over a section of length `h`) lies outside
/// what its derivative column, anywhere between its two end values `d` and
/// bending by up to `bend`, can make it; 0 inside (with float noise).
fn unexplained(change: f64, h: f64, d: (f64, f64), bend: f64) -> f64 {
    let lo = h * (d.0.min(d.1) - bend);
    let hi = h * (d.0.max(d.1) + bend);
    let noise = COLUMN_NOISE * (change.abs() + lo.abs().max(hi.abs()));
    if change > hi + noise {
        change - hi
    } else if change < lo - noise {
        change - lo
    } else {
        0.0
    }
}

/// A curve that knows its corners (see the module's rule).
pub trait Corners {
    /// Every corner, in master order, the seam last.
    fn corners(&self) -> Vec<Corner>;
}

/// The corners of straight sections through `(x, s)` points: every inner
/// point and the seam, velocity stepping from one section's slope to the
/// next, acceleration zero on both sides.
fn straight_corners(x: &[f64], s: &[f64]) -> Vec<Corner> {
    let n = x.len().min(s.len());
    let slope = |i: usize| (s[i + 1] - s[i]) / (x[i + 1] - x[i]);
    let moving = |v: f64| Kinematics {
        v,
        ..Kinematics::default()
    };
    let mut corners = Vec::with_capacity(n);
    if n < 2 {
        return corners;
    }
    for i in 1..n - 1 {
        corners.push(Corner {
            master: x[i],
            before: moving(slope(i - 1)),
            after: moving(slope(i)),
            reach: (x[i] - x[i - 1]).max(x[i + 1] - x[i]),
            seam: false,
        });
    }
    corners.push(Corner {
        master: x[n - 1],
        before: moving(slope(n - 2)),
        after: moving(slope(0)),
        reach: (x[1] - x[0]).max(x[n - 1] - x[n - 2]),
        seam: true,
    });
    corners
}

impl Corners for PointTable {
    fn corners(&self) -> Vec<Corner> {
        let points = self.points();
        let x: Vec<f64> = points.iter().map(|p| p.master as f64).collect();
        let s: Vec<f64> = points.iter().map(|p| p.slave as f64).collect();
        straight_corners(&x, &s)
    }
}

impl Corners for UniformTable {
    fn corners(&self) -> Vec<Corner> {
        let values = self.values();
        let pieces = values.len().saturating_sub(1).max(1) as f64;
        let counts = self.cam_counts() as f64;
        let x: Vec<f64> = (0..values.len())
            .map(|k| k as f64 * counts / pieces)
            .collect();
        let s: Vec<f64> = values.iter().map(|&v| v as f64).collect();
        straight_corners(&x, &s)
    }
}

impl Corners for SegmentProfile {
    fn corners(&self) -> Vec<Corner> {
        let segments = self.segments();
        let mut corners = Vec::with_capacity(segments.len().saturating_mul(2));
        // Each segment's law scaled onto it: (start, span, rise, law).
        let mut from = self.start();
        let mut scaled = Vec::with_capacity(segments.len());
        for seg in segments {
            let span = seg.master_end.saturating_sub(from.master) as f64;
            let rise = seg.slave_end.saturating_sub(from.slave) as f64;
            scaled.push((from, span, rise, seg.law));
            from = CamPoint::new(seg.master_end, seg.slave_end);
        }
        let at = |&(from, span, rise, law): &(CamPoint, f64, f64, crate::MotionLaw),
                  u: f64,
                  after: bool| {
            let k = if after {
                law.eval_after(u)
            } else {
                law.eval(u)
            };
            k.scaled(from.slave as f64, rise, span)
        };
        for (i, seg) in scaled.iter().enumerate() {
            let (from, span, _, law) = *seg;
            for &u in law.acceleration_knots() {
                corners.push(Corner {
                    master: from.master as f64 + u * span,
                    before: at(seg, u, false),
                    after: at(seg, u, true),
                    reach: span * u.max(1.0 - u),
                    seam: false,
                });
            }
            // The key point ending this segment (the seam after the last).
            if let Some(next) = scaled.get(i + 1).or(scaled.first()) {
                // The stretches beside it run to the nearest knot of each
                // law, or over the whole segment.
                let (_, next_span, _, next_law) = *next;
                let into = span * (1.0 - law.acceleration_knots().last().copied().unwrap_or(0.0));
                let out = next_span
                    * next_law
                        .acceleration_knots()
                        .first()
                        .copied()
                        .unwrap_or(1.0);
                corners.push(Corner {
                    master: from.master as f64 + span,
                    before: at(seg, 1.0, false),
                    after: at(next, 0.0, true),
                    reach: into.max(out),
                    seam: i + 1 == scaled.len(),
                });
            }
        }
        corners
    }
}

impl Corners for CamTable {
    fn corners(&self) -> Vec<Corner> {
        match self {
            Self::Points(t) => t.corners(),
            Self::Uniform(t) => t.corners(),
            Self::Profile(t) => t.corners(),
        }
    }
}

impl<C: Corners + ?Sized> Corners for &C {
    fn corners(&self) -> Vec<Corner> {
        (**self).corners()
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::{MotionLaw, Segment};

    #[test]
    fn a_point_tables_corners_are_its_points_and_its_seam() {
        let t = PointTable::from_pairs(&[(0, 0), (10, 10), (40, 100), (50, 100)]).unwrap();
        let s = Steps::of(&t);
        let v: Vec<(f64, f64, bool)> = s
            .velocity
            .iter()
            .map(|s| (s.master, s.size, s.seam))
            .collect();
        assert_eq!(
            v,
            [(10.0, 2.0, false), (40.0, -3.0, false), (50.0, 1.0, true)]
        );
        assert!(s.acceleration.is_empty());
        assert_eq!(s.continuity(), (Continuity::C0, Continuity::C0));
        // A straight line has no corner that steps, the seam included.
        let line = PointTable::from_pairs(&[(0, 0), (10, 20), (30, 60)]).unwrap();
        assert_eq!(Steps::of(&line), Steps::default());
    }

    #[test]
    fn a_constant_acceleration_segment_turns_in_its_middle() {
        // Rise 1000 over 100 counts: a = ±4·1000/100² = ±0.4.
        let p = SegmentProfile::new(
            CamPoint::new(0, 0),
            alloc::vec![
                Segment::new(100, 1000, MotionLaw::ConstantAcceleration),
                Segment::new(200, 1000, MotionLaw::Cycloid),
            ],
        )
        .unwrap();
        let s = Steps::of(&p);
        assert!(s.velocity.is_empty(), "{s:?}");
        let a: Vec<(f64, f64, bool)> = s
            .acceleration
            .iter()
            .map(|s| (s.master, (s.size * 1e9).round() / 1e9, s.seam))
            .collect();
        // Into the rise at the seam (0 → 0.4, reported at the end), the turn
        // at 50 (0.4 → −0.4), out of it at 100 (−0.4 → 0).
        assert_eq!(
            a,
            [(50.0, -0.8, false), (100.0, 0.4, false), (200.0, 0.4, true)]
        );
    }

    #[test]
    fn a_step_too_small_to_move_the_slave_half_a_pulse_is_none() {
        assert!(velocity_step_counts(0.05, 10.0));
        assert!(!velocity_step_counts(0.049, 10.0));
        assert!(acceleration_step_counts(0.01, 10.0));
        assert!(!acceleration_step_counts(0.0099, 10.0));
        // Floating-point noise of an exact curve never counts.
        assert!(!acceleration_step_counts(1e-12, 1e4));
    }

    #[test]
    fn columns_step_where_the_next_column_does_not_explain_the_change() {
        // Acceleration held at 0.01 from 0 to 100, then −0.01 (a step at
        // 100), sampled every 10 counts; the jerk column is 0.
        let x: Vec<i64> = (0..=20).map(|i| i * 10).collect();
        let a = |m: i64| if m < 100 { 0.01 } else { -0.01 };
        let v = |m: i64| {
            let m = m as f64;
            if m < 100.0 {
                0.01 * m
            } else {
                1.0 - 0.01 * (m - 100.0)
            }
        };
        let points: Vec<CamPoint> = x.iter().map(|&m| CamPoint::new(m, 0)).collect();
        let known: Vec<Kinematics> = x
            .iter()
            .map(|&m| Kinematics {
                s: 0.0,
                v: v(m),
                a: a(m),
                j: 0.0,
            })
            .collect();
        let s = Steps::of_columns(&points, &known);
        assert!(s.velocity.is_empty(), "{s:?}");
        let at: Vec<(f64, f64, bool)> = s
            .acceleration
            .iter()
            .map(|s| (s.master, s.size, s.seam))
            .collect();
        assert_eq!(at.len(), 2, "{at:?}");
        assert_eq!((at[0].0, at[0].2), (100.0, false));
        assert!((at[0].1 + 0.02).abs() < 1e-12);
        // The seam: −0.01 at the end, 0.01 at the start.
        assert_eq!((at[1].0, at[1].2), (200.0, true));
        assert!((at[1].1 - 0.02).abs() < 1e-12);
    }

    #[test]
    fn a_smooth_law_known_at_its_points_has_no_steps() {
        // A cycloid rising 1000 pulses over 100 counts, at 11 points: its
        // acceleration changes between points only as its jerk says.
        let points: Vec<CamPoint> = (0..=10).map(|i| CamPoint::new(i * 10, 0)).collect();
        let known: Vec<Kinematics> = points
            .iter()
            .map(|p| {
                MotionLaw::Cycloid
                    .eval(p.master as f64 / 100.0)
                    .scaled(0.0, 1000.0, 100.0)
            })
            .collect();
        assert_eq!(Steps::of_columns(&points, &known), Steps::default());
    }
}
