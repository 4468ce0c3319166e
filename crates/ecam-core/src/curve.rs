//! The one interface the engine needs from any cam: [`CamCurve`].
//!
//! Every table kind (point tables, evenly spaced tables, segment profiles)
//! implements it, so the engine never cares how a cam was designed. The end
//! points are exact integers because the engine's cycle bookkeeping is
//! integer arithmetic: the stroke of a repeat cam is `slave_last − slave_first`
//! added once per cycle, so a year of running drifts by nothing.

use crate::Kinematics;

/// Remembers which segment the last evaluation fell in, so that evaluating
/// a master that moves a little each cycle costs O(1); a jump falls back to a
/// binary search. A cursor holds no reference to its curve; using one cursor
/// with two curves is harmless (only slower).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Cursor {
    /// Index of the segment found last time.
    pub segment: usize,
}

impl Cursor {
    /// A cursor at the first segment.
    pub const fn new() -> Self {
        Self { segment: 0 }
    }
}

/// A cam curve: slave position as a function of master position over one
/// cycle `[master_first, master_last]`.
pub trait CamCurve {
    /// Master position where the curve starts (exact, in master counts).
    fn master_first(&self) -> i64;
    /// Master position where the curve ends (exact, in master counts).
    fn master_last(&self) -> i64;
    /// Slave position at `master_first` (exact, in slave pulses).
    fn slave_first(&self) -> i64;
    /// Slave position at `master_last` (exact, in slave pulses).
    fn slave_last(&self) -> i64;
    /// Number of segments (pieces) the curve is made of.
    fn segment_count(&self) -> usize;
    /// Slave position and derivatives with respect to the master at `master`.
    /// A master outside the cycle is clamped onto its nearer end.
    fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics;

    /// Slave position only; curves override this when it is cheaper than [`CamCurve::eval`].
    fn position(&self, master: f64, cursor: &mut Cursor) -> f64 {
        self.eval(master, cursor).s
    }

    /// Slave positions for many masters at once: `out[i]` is the position
    /// at `masters[i]`, for every `i` both slices have (a plot, a
    /// generator's samples, a user's batch). Exactly the values
    /// [`CamCurve::position`] gives; curves override this when a whole
    /// slice is cheaper, and any order is allowed (ascending is fastest).
    fn positions_into(&self, masters: &[f64], out: &mut [f64]) {
        let mut cursor = Cursor::new();
        for (master, slot) in masters.iter().zip(out.iter_mut()) {
            *slot = self.position(*master, &mut cursor);
        }
    }

    /// Length of one cycle in master counts.
    fn master_span(&self) -> i64 {
        self.master_last().saturating_sub(self.master_first())
    }

    /// Slave change over one cycle (what a repeat cam adds per cycle).
    fn stroke(&self) -> i64 {
        self.slave_last().saturating_sub(self.slave_first())
    }

    /// Whether the slave turns back inside one cycle (it moves both up and
    /// down between `master_first` and `master_last`). The engine's start
    /// rule asks (docs/engine.md, "The start rule"): a cam that starts away
    /// from its origin engages at the equivalent position ahead of the
    /// slave when the table never turns back, so a start sends no reverse
    /// pulse, and at the nearest one either way when it does (document
    /// 001's example). O(1): tables work it out when they are built.
    /// Curves that cannot tell answer `false` (the default), which is the
    /// safe answer for a pulse output.
    fn turns_back(&self) -> bool {
        false
    }
}

impl<C: CamCurve + ?Sized> CamCurve for &C {
    fn master_first(&self) -> i64 {
        (**self).master_first()
    }
    fn master_last(&self) -> i64 {
        (**self).master_last()
    }
    fn slave_first(&self) -> i64 {
        (**self).slave_first()
    }
    fn slave_last(&self) -> i64 {
        (**self).slave_last()
    }
    fn segment_count(&self) -> usize {
        (**self).segment_count()
    }
    fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics {
        (**self).eval(master, cursor)
    }
    fn position(&self, master: f64, cursor: &mut Cursor) -> f64 {
        (**self).position(master, cursor)
    }
    fn positions_into(&self, masters: &[f64], out: &mut [f64]) {
        (**self).positions_into(masters, out)
    }
    fn turns_back(&self) -> bool {
        (**self).turns_back()
    }
}

impl<C: CamCurve + ?Sized> CamCurve for alloc::boxed::Box<C> {
    fn master_first(&self) -> i64 {
        (**self).master_first()
    }
    fn master_last(&self) -> i64 {
        (**self).master_last()
    }
    fn slave_first(&self) -> i64 {
        (**self).slave_first()
    }
    fn slave_last(&self) -> i64 {
        (**self).slave_last()
    }
    fn segment_count(&self) -> usize {
        (**self).segment_count()
    }
    fn eval(&self, master: f64, cursor: &mut Cursor) -> Kinematics {
        (**self).eval(master, cursor)
    }
    fn position(&self, master: f64, cursor: &mut Cursor) -> f64 {
        (**self).position(master, cursor)
    }
    fn positions_into(&self, masters: &[f64], out: &mut [f64]) {
        (**self).positions_into(masters, out)
    }
    fn turns_back(&self) -> bool {
        (**self).turns_back()
    }
}
