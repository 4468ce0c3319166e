//! Stops: immediate (document 002 abrupt stop, document 003 start register
//! = 0) and at the end of the current cycle, forwards or backwards
//! (document 002 smooth stop, document 003 function register 4 bit 1).

use crate::coupling::{Extent, Geometry, Place};

/// How to stop a running cam.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopKind {
    /// The commanded position stays where it is now (a velocity step).
    Immediate,
    /// Keep following until the master reaches the end of the current cycle
    /// in either direction, then hold the slave at that cycle end.
    EndOfCycle,
}

/// The two ends of the cycle that was current when an end-of-cycle stop
/// was requested.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct CycleEnd {
    k: i128,
    forward: i128,
    backward: i128,
    single: bool,
}

impl CycleEnd {
    /// The ends of the cycle holding `place`.
    pub(crate) fn of(geo: &Geometry, place: Place) -> Self {
        Self {
            k: place.k,
            forward: geo.boundary(place.k, true),
            backward: geo.boundary(place.k, false),
            single: geo.extent == Extent::Single,
        }
    }

    /// Where the cam stops if table input `t_num` reached or passed an end,
    /// and whether that end is the forward one (a completed cycle).
    ///
    /// Forwards, reaching the end counts; backwards the start must be
    /// passed, so a stop requested exactly at a seam runs one more cycle
    /// forwards rather than stopping on the spot. A normal (non-repeating)
    /// cam stops at either end of its table.
    pub(crate) fn reached(&self, geo: &Geometry, t_num: i128) -> Option<(Place, bool)> {
        if t_num >= self.forward {
            Some((geo.cycle_end(self.k), true))
        } else if t_num < self.backward || (self.single && t_num == self.backward) {
            Some((Geometry::cycle_start(self.k), false))
        } else {
            None
        }
    }
}
