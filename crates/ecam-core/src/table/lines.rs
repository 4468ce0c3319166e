//! The float side of a point table: each section's start, rise, span and
//! slope as `f64`, derived once from the exact integer points so that a
//! lookup is a compare, a subtraction, a division and a multiply-add.
//!
//! The figures are exactly the ones the integer points give through the
//! 128-bit route (differences of any two `i64` positions taken exactly,
//! then converted once), computed in 64 bits whenever the difference fits
//! and in 128 bits only when it does not. So a lookup gives bit for bit
//! what it gave before these copies existed; the unit tests below check
//! that against the 128-bit formula on random tables.

use alloc::vec::Vec;

use crate::{CamPoint, Cursor, Kinematics};

/// One section `[points[i], points[i+1]]` in floats.
#[derive(Clone, Copy, Debug)]
struct Section {
    /// The masters this section answers for, `[from, until)`: its own
    /// points, but from −∞ for the first section and up to +∞ for the
    /// last (a master outside the table is clamped afterwards).
    from: f64,
    until: f64,
    /// Master at the section's start.
    master: f64,
    /// Slave at the section's start.
    slave: f64,
    /// Master change over the section (exact difference, rounded once).
    span: f64,
    /// Slave change over the section (exact difference, rounded once).
    rise: f64,
    /// `rise / span`, the section's d(slave)/d(master).
    slope: f64,
}

impl Section {
    /// A master in `[from, until)`.
    #[inline(always)]
    fn holds(&self, master: f64) -> bool {
        master >= self.from && master < self.until
    }

    /// The slave at `master` (already clamped into the table).
    #[inline(always)]
    fn position(&self, master: f64) -> f64 {
        self.slave + self.rise * ((master - self.master) / self.span)
    }
}

/// The lookup copies of a validated point table (at least two points,
/// master strictly increasing).
#[derive(Clone, Debug)]
pub(super) struct Lines {
    /// Every point's master as a float (the binary search runs on these).
    masters: Vec<f64>,
    sections: Vec<Section>,
    /// The first and last master, as floats.
    first: f64,
    last: f64,
}

impl Default for Lines {
    fn default() -> Self {
        Self::new(&[])
    }
}

/// `b − a` as a float: one 64-bit subtraction when it cannot overflow,
/// the 128-bit difference otherwise (extreme positions only).
#[inline]
fn difference(a: i64, b: i64) -> f64 {
    match b.checked_sub(a) {
        Some(d) => d as f64,
        None => (i128::from(b) - i128::from(a)) as f64,
    }
}

impl Lines {
    /// The copies for `points` (validated by the caller; fewer than two
    /// points give a table that answers 0 everywhere).
    pub(super) fn new(points: &[CamPoint]) -> Self {
        let masters: Vec<f64> = points.iter().map(|p| p.master as f64).collect();
        let count = points.len().saturating_sub(1);
        let mut sections: Vec<Section> = points
            .windows(2)
            .enumerate()
            .map(|(i, w)| {
                let span = difference(w[0].master, w[1].master);
                let rise = difference(w[0].slave, w[1].slave);
                Section {
                    from: if i == 0 {
                        f64::NEG_INFINITY
                    } else {
                        w[0].master as f64
                    },
                    until: if i + 1 == count {
                        f64::INFINITY
                    } else {
                        w[1].master as f64
                    },
                    master: w[0].master as f64,
                    slave: w[0].slave as f64,
                    span,
                    rise,
                    slope: rise / span,
                }
            })
            .collect();
        if sections.is_empty() {
            sections.push(Section {
                from: f64::NEG_INFINITY,
                until: f64::INFINITY,
                master: 0.0,
                slave: 0.0,
                span: 1.0,
                rise: 0.0,
                slope: 0.0,
            });
        }
        Self {
            first: masters.first().copied().unwrap_or(0.0),
            last: masters.last().copied().unwrap_or(0.0),
            masters,
            sections,
        }
    }

    /// The section holding `master` (not NaN), trying the cursor's section
    /// and its neighbours before a binary search. Half-open: a master
    /// exactly on a point belongs to the section starting there, whichever
    /// way it was reached.
    #[inline(always)]
    fn locate(&self, master: f64, cursor: &mut Cursor) -> &Section {
        let sections = self.sections.as_slice();
        if let Some(section) = sections.get(cursor.segment)
            && section.holds(master)
        {
            return section;
        }
        self.relocate(master, cursor)
    }

    /// [`Lines::locate`] away from the cursor's section.
    #[inline(never)]
    fn relocate(&self, master: f64, cursor: &mut Cursor) -> &Section {
        let sections = self.sections.as_slice();
        let guess = cursor.segment;
        let near = [guess.wrapping_add(1), guess.wrapping_sub(1)]
            .into_iter()
            .find(|&i| sections.get(i).is_some_and(|s| s.holds(master)));
        let found = near.unwrap_or_else(|| {
            // First point whose master exceeds `master`, minus one.
            let upper = self.masters.partition_point(|&m| m <= master);
            upper.saturating_sub(1).min(sections.len() - 1)
        });
        cursor.segment = found;
        // `found` is in range: a neighbour that exists, or clamped above.
        &sections[found.min(sections.len() - 1)]
    }

    /// `master` with NaN read as the first master.
    #[inline(always)]
    fn sane(&self, master: f64) -> f64 {
        if master.is_nan() { self.first } else { master }
    }

    /// `master` clamped into the table (as `clamp`, which cannot fail
    /// here: first <= last, neither NaN).
    #[inline(always)]
    fn clamp(&self, master: f64) -> f64 {
        if master < self.first {
            self.first
        } else if master > self.last {
            self.last
        } else {
            master
        }
    }

    /// Slave position and slope at `master`.
    #[inline]
    pub(super) fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics {
        let master = self.sane(master);
        let section = self.locate(master, cursor);
        Kinematics {
            s: section.position(self.clamp(master)),
            v: section.slope,
            a: 0.0,
            j: 0.0,
        }
    }

    /// Slave position at `master`.
    #[inline]
    pub(super) fn position(&self, master: f64, cursor: &mut Cursor) -> f64 {
        let master = self.sane(master);
        self.locate(master, cursor).position(self.clamp(master))
    }

    /// [`Lines::position`] for each master, one cursor throughout.
    ///
    /// Ascending masters are taken in runs that fall in one section, the
    /// end of each found by a binary search among the masters (no search
    /// per master); each run is one pass with the section's figures fixed,
    /// which the compiler turns into vector instructions, and which also
    /// checks that every master of the run was in the section. Should one
    /// not be (the masters are not in order), that run and the rest are
    /// placed one by one. The arithmetic is the same either way, so is
    /// every result.
    pub(super) fn positions_into(&self, masters: &[f64], out: &mut [f64]) {
        let count = masters.len().min(out.len());
        let (masters, out) = (&masters[..count], &mut out[..count]);
        let mut cursor = Cursor::new();
        let mut start = 0;
        while let Some(&query) = masters.get(start) {
            let section = *self.locate(self.sane(query), &mut cursor);
            let run = masters[start..]
                .partition_point(|&m| m < section.until)
                .max(1);
            let end = start + run;
            let (queries, results) = (&masters[start..end], &mut out[start..end]);
            // One pass computes the run and checks that every master was
            // in the section (a NaN fails the check); it vectorises, as it
            // neither branches nor stops early. Should one not be (the
            // masters are not in order), the run is redone one by one.
            let inside = if section.from >= self.first && section.until <= self.last {
                // An inner section: every master of the run is inside the
                // table already, so clamping would change nothing.
                results
                    .iter_mut()
                    .zip(queries)
                    .fold(true, |all, (slot, &m)| {
                        *slot = section.position(m);
                        all & section.holds(m)
                    })
            } else {
                results
                    .iter_mut()
                    .zip(queries)
                    .fold(true, |all, (slot, &m)| {
                        *slot = section.position(self.clamp(m));
                        all & section.holds(m)
                    })
            };
            if !inside {
                for (slot, &m) in out[start..].iter_mut().zip(&masters[start..]) {
                    *slot = self.position(m, &mut cursor);
                }
                return;
            }
            start = end;
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use alloc::vec;
    use proptest::prelude::*;

    /// The formula a point table used before the float copies: the section
    /// found by binary search, differences in 128 bits, converted per call.
    fn exact(points: &[CamPoint], master: f64) -> Kinematics {
        let first = points[0].master as f64;
        let last = points[points.len() - 1].master as f64;
        let master = if master.is_nan() { first } else { master };
        let upper = points.partition_point(|p| (p.master as f64) <= master);
        let i = upper.saturating_sub(1).min(points.len() - 2);
        let (p0, p1) = (points[i], points[i + 1]);
        let span = (i128::from(p1.master) - i128::from(p0.master)) as f64;
        let rise = (i128::from(p1.slave) - i128::from(p0.slave)) as f64;
        let m = master.clamp(first, last);
        let u = (m - p0.master as f64) / span;
        Kinematics {
            s: p0.slave as f64 + rise * u,
            v: rise / span,
            a: 0.0,
            j: 0.0,
        }
    }

    /// Strictly increasing masters from positive steps; any slaves. Masters
    /// stay within 2^52 of each other's scale so every point has its own float.
    fn table(scale: i64) -> impl Strategy<Value = Vec<CamPoint>> {
        (
            -scale..scale,
            proptest::collection::vec((1..scale / 64 + 2, any::<i64>()), 1..40),
        )
            .prop_map(|(start, steps)| {
                let mut master = start;
                let mut points = vec![CamPoint::new(master, steps[0].1)];
                for (step, slave) in steps {
                    master = master.saturating_add(step);
                    points.push(CamPoint::new(master, slave));
                }
                points.dedup_by_key(|p| p.master);
                if points.len() < 2 {
                    points.push(CamPoint::new(master.saturating_sub(1), 0));
                    points.sort_by_key(|p| p.master);
                }
                points
            })
    }

    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    proptest! {
        #[test]
        fn fast_lookup_equals_the_exact_formula(
            points in prop_oneof![table(1 << 20), table(1 << 50)],
            probes in proptest::collection::vec(-1.2f64..1.2, 1..60),
            nan in any::<bool>(),
        ) {
            let lines = Lines::new(&points);
            let first = points[0].master as f64;
            let span = points[points.len() - 1].master as f64 - first;
            let mut masters: Vec<f64> = probes.iter().map(|u| first + u * span).collect();
            // Every point exactly, and NaN.
            masters.extend(points.iter().map(|p| p.master as f64));
            if nan {
                masters.push(f64::NAN);
            }
            let mut cursor = Cursor::new();
            for &m in &masters {
                let want = exact(&points, m);
                let got = lines.eval(m, &mut cursor);
                prop_assert!(same(got.s, want.s) && same(got.v, want.v), "eval at {m}: {got:?} vs {want:?}");
                let fresh = lines.position(m, &mut Cursor::new());
                prop_assert!(same(fresh, want.s), "position at {m}");
            }
            let mut batch = vec![0.0; masters.len()];
            lines.positions_into(&masters, &mut batch);
            for (m, got) in masters.iter().zip(&batch) {
                prop_assert!(same(*got, exact(&points, *m).s), "batch at {m}");
            }
            masters.sort_by(f64::total_cmp);
            lines.positions_into(&masters, &mut batch);
            for (m, got) in masters.iter().zip(&batch) {
                prop_assert!(same(*got, exact(&points, *m).s), "sorted batch at {m}");
            }
        }
    }

    #[test]
    fn extreme_differences_take_the_wide_route() {
        let points = [
            CamPoint::new(i64::MIN, i64::MAX),
            CamPoint::new(i64::MAX, i64::MIN),
        ];
        let lines = Lines::new(&points);
        for m in [0.0, -1e18, 1e18, f64::NAN, f64::INFINITY] {
            let (got, want) = (lines.eval(m, &mut Cursor::new()), exact(&points, m));
            assert!(same(got.s, want.s) && same(got.v, want.v));
        }
    }
}
