//! The exact motion behind a generated table.
//!
//! The S-curve, rotary-cut and flying-saw generators first design a smooth
//! motion (constant-velocity pieces joined by ramps shaped by an
//! [`AccelCurve`](super::AccelCurve)), then sample it into a
//! [`PointTable`](crate::PointTable) of whole pulses. The table is what a PLC
//! runs; the design is what a motion engineer reasons about: its velocity,
//! acceleration and jerk are the motion law, where finite differences of the
//! rounded table only show the rounding.
//!
//! A [`DesignCurve`] keeps that design. Its derivatives are analytic. It is
//! not a [`CamCurve`](crate::CamCurve): that trait promises exact integer end
//! points, and the design's ends are only within half a pulse of the
//! table's (the midCAM placements start up to ½ pulse off zero, which the
//! sampler pins back onto the integer; elsewhere the ends are sums of
//! floating-point ramp lengths). Every table point lies within ½ pulse of
//! the design.
//!
//! ```
//! use ecam_core::generator::rotary_cut::{Params, generate};
//!
//! let g = generate(&Params::default())?;
//! let (lo, hi) = g.sync.unwrap_or_default();
//! // In the sync zone the designed velocity is the sync ratio, exactly.
//! let k = g.design.eval(0.5 * (lo + hi) as f64);
//! assert_eq!(k.v, g.sync_ratio);
//! assert_eq!((k.a, k.j), (0.0, 0.0));
//! // Every table point lies within half a pulse of the design.
//! for p in g.table.points() {
//!     assert!((g.design.eval(p.master as f64).s - p.slave as f64).abs() <= 0.5 + 1e-9);
//! }
//! # Ok::<(), ecam_core::TableError>(())
//! ```

use alloc::vec::Vec;

use super::motion_path::Path;
use crate::Kinematics;
use crate::table::steps::{Corner, Corners};

/// The continuous motion a generator designed before rounding it into its
/// table: slave position, velocity ratio, acceleration and jerk at any
/// master position, with respect to the master in counts.
#[derive(Clone, Debug, PartialEq)]
pub struct DesignCurve {
    path: Path,
    master_first: f64,
    master_last: f64,
}

impl DesignCurve {
    /// The design `path` over `[0, master_last]`.
    pub(crate) fn new(path: Path, master_last: i64) -> Self {
        Self {
            path,
            master_first: 0.0,
            master_last: master_last as f64,
        }
    }

    /// The same motion with the slave running the other way.
    pub(crate) fn mirrored(&self) -> Self {
        Self {
            path: self.path.mirrored(),
            ..*self
        }
    }

    /// Position, velocity ratio (slave pulses per master count),
    /// acceleration (per count²) and jerk (per count³) at `master`, analytic.
    ///
    /// A master on a joint between two pieces belongs to the piece starting
    /// there (as a table's joint belongs to the section starting there); a
    /// master outside [`DesignCurve::master_range`] is clamped onto it, and
    /// NaN means the first master.
    pub fn eval(&self, master: f64) -> Kinematics {
        let master = if master.is_nan() {
            self.master_first
        } else {
            master.clamp(self.master_first, self.master_last)
        };
        self.path.kinematics_at(master)
    }

    /// First and last master position of the design (those of its table).
    pub fn master_range(&self) -> (f64, f64) {
        (self.master_first, self.master_last)
    }

    /// Designed slave position at the first master (within ½ pulse of the
    /// table's first slave).
    pub fn slave_first(&self) -> f64 {
        self.eval(self.master_first).s
    }

    /// Designed slave position at the last master (within ½ pulse of the
    /// table's last slave).
    pub fn slave_last(&self) -> f64 {
        self.eval(self.master_last).s
    }

    /// Number of pieces (constant-velocity stretches and ramps).
    pub fn piece_count(&self) -> usize {
        self.path.pieces().len()
    }

    /// Master positions where one piece ends and the next begins: where
    /// acceleration (uniform curve) or jerk (S-type) may step.
    pub fn joints(&self) -> impl Iterator<Item = f64> + '_ {
        self.path.pieces().iter().skip(1).map(|p| p.master_start)
    }

    /// This motion, then `next` moved to start where this one ends (master
    /// and slave): e.g. a flying saw's forward and return tables as one cut
    /// cycle.
    pub fn followed_by(&self, next: &DesignCurve) -> DesignCurve {
        let mut path = self.path.clone();
        path.append_shifted(
            &next.path,
            self.master_last - next.master_first,
            self.slave_last() - next.slave_first(),
        );
        DesignCurve {
            path,
            master_first: self.master_first,
            master_last: self.master_last + (next.master_last - next.master_first),
        }
    }

    /// Points to draw the design with: `per_piece + 1` evenly spaced samples
    /// over every piece, both ends included and each evaluated on its own
    /// piece, so a step of acceleration or jerk at a joint shows as a
    /// vertical edge (two samples at the same master).
    pub fn sample_pieces(&self, per_piece: usize) -> Vec<(f64, Kinematics)> {
        let per_piece = per_piece.max(1);
        let pieces = self.path.pieces();
        if pieces.is_empty() {
            return [self.master_first, self.master_last]
                .into_iter()
                .map(|m| (m, self.eval(m)))
                .collect();
        }
        let mut out = Vec::with_capacity(pieces.len().saturating_mul(per_piece + 1));
        for p in pieces {
            for i in 0..=per_piece {
                let master = if i == per_piece {
                    p.master_end()
                } else {
                    p.master_start + p.len * (i as f64 / per_piece as f64)
                };
                out.push((master, p.kinematics_at(master)));
            }
        }
        out
    }
}

/// Where the design's pieces meet, and its seam (the last piece's end
/// meeting the first piece's start). Pieces of no length are passed over:
/// a corner joins the pieces either side of them.
impl Corners for DesignCurve {
    fn corners(&self) -> Vec<Corner> {
        let pieces: Vec<_> = self.path.pieces().iter().filter(|p| p.len > 0.0).collect();
        let mut corners = Vec::with_capacity(pieces.len());
        for pair in pieces.windows(2) {
            if let [before, after] = pair {
                corners.push(Corner {
                    master: after.master_start,
                    before: before.kinematics_at(before.master_end()),
                    after: after.kinematics_at(after.master_start),
                    reach: before.len.max(after.len),
                    seam: false,
                });
            }
        }
        if let (Some(first), Some(last)) = (pieces.first(), pieces.last()) {
            corners.push(Corner {
                master: self.master_last,
                before: last.kinematics_at(last.master_end()),
                after: first.kinematics_at(first.master_start),
                reach: first.len.max(last.len),
                seam: true,
            });
        }
        corners
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::generator::AccelCurve;
    use crate::generator::motion_path::Ramp;

    fn trapezoid(curve: AccelCurve) -> DesignCurve {
        let mut p = Path::starting_at(0.0, 0.0);
        p.push(
            Ramp {
                v0: 0.0,
                v1: 2.0,
                len: 50.0,
            },
            curve,
        );
        p.push_constant(2.0, 100.0);
        p.push(
            Ramp {
                v0: 2.0,
                v1: 0.0,
                len: 50.0,
            },
            curve,
        );
        DesignCurve::new(p, 200)
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for curve in AccelCurve::ALL {
            let d = trapezoid(curve);
            let h = 1e-4;
            for i in 1..400 {
                let m = f64::from(i) / 2.0;
                // Keep the difference inside one piece (and one half of an
                // S-type ramp, whose jerk steps in the middle).
                if [0.0, 25.0, 50.0, 150.0, 175.0, 200.0]
                    .iter()
                    .any(|j| (m - j).abs() < 2.0 * h)
                {
                    continue;
                }
                let (lo, k, hi) = (d.eval(m - h), d.eval(m), d.eval(m + h));
                let tol = |x: f64| 1e-5 * x.abs().max(1.0);
                assert!(
                    (k.v - (hi.s - lo.s) / (2.0 * h)).abs() < tol(k.v),
                    "{curve:?} v {m}"
                );
                assert!(
                    (k.a - (hi.v - lo.v) / (2.0 * h)).abs() < tol(k.a),
                    "{curve:?} a {m}"
                );
                assert!(
                    (k.j - (hi.a - lo.a) / (2.0 * h)).abs() < tol(k.j),
                    "{curve:?} j {m}"
                );
            }
        }
    }

    #[test]
    fn ends_clamp_and_nan_is_the_start() {
        let d = trapezoid(AccelCurve::BType);
        assert_eq!(d.master_range(), (0.0, 200.0));
        assert_eq!(d.eval(-5.0), d.eval(0.0));
        assert_eq!(d.eval(f64::NAN), d.eval(0.0));
        assert!((d.slave_last() - 300.0).abs() < 1e-9);
        assert_eq!(d.piece_count(), 3);
        assert_eq!(d.joints().collect::<Vec<_>>(), [50.0, 150.0]);
    }

    #[test]
    fn mirror_and_sequence() {
        let d = trapezoid(AccelCurve::UniformAcceleration);
        let back = d.mirrored();
        for i in 0..=40 {
            let m = f64::from(i) * 5.0;
            let (k, b) = (d.eval(m), back.eval(m));
            assert_eq!((b.s, b.v, b.a, b.j), (-k.s, -k.v, -k.a, -k.j));
        }
        let cycle = d.followed_by(&back);
        assert_eq!(cycle.master_range(), (0.0, 400.0));
        assert!(cycle.slave_last().abs() < 1e-9);
        assert!((cycle.eval(300.0).s - (300.0 + back.eval(100.0).s)).abs() < 1e-9);
        assert_eq!(cycle.eval(300.0).v, back.eval(100.0).v);
    }

    #[test]
    fn a_uniform_ramps_steps_are_at_its_joints_and_its_seam() {
        use crate::table::steps::Steps;
        // Acceleration 2/50 = 0.04 up to 50, 0 to 150, −0.04 to 200.
        let s = Steps::of(&trapezoid(AccelCurve::Uniform));
        assert!(s.velocity.is_empty());
        let a: Vec<(f64, f64, bool)> = s
            .acceleration
            .iter()
            .map(|s| (s.master, (s.size * 1e12).round() / 1e12, s.seam))
            .collect();
        assert_eq!(
            a,
            [
                (50.0, -0.04, false),
                (150.0, -0.04, false),
                (200.0, 0.08, true)
            ]
        );
        // The S-type ramp's acceleration is continuous everywhere.
        assert_eq!(
            Steps::of(&trapezoid(AccelCurve::UniformAcceleration)),
            Steps::default()
        );
    }

    #[test]
    fn samples_show_both_sides_of_a_joint() {
        let d = trapezoid(AccelCurve::Uniform);
        let samples = d.sample_pieces(4);
        assert_eq!(samples.len(), 15);
        // The acceleration steps from 2/50 to 0 at master 50.
        let at_50: Vec<f64> = samples
            .iter()
            .filter(|(m, _)| *m == 50.0)
            .map(|(_, k)| k.a)
            .collect();
        assert_eq!(at_50.len(), 2);
        assert!((at_50[0] - 0.04).abs() < 1e-12 && at_50[1] == 0.0);
    }
}
