//! Ramp-in (beyond the documents, after PLCopen `MC_CamIn` ramp-in): engage
//! a moving master without a velocity jump.
//!
//! The commanded position is `cam + (1 − w(u)) × (hold − cam)`, where `hold`
//! is the slave position at engage, `u` the master travel since engage over
//! the ramp distance, and `w(u) = 10u³ − 15u⁴ + 6u⁵`. Since `w` and its first
//! two derivatives are 0 at `u = 0` and `w(1) = 1` with `w'(1) = w''(1) = 0`,
//! the slave starts with the velocity it had (at rest) and meets the cam
//! with the cam's velocity and acceleration. The blend is a pure function of
//! the master, like the cam itself.

use core::num::NonZeroU64;

use crate::master_ramp::{MasterRamp, quintic};
use crate::rounding::{exact_f64, round_to_i128};
use crate::{MasterPosition, RampIn};

/// A ramp in progress.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Ramp {
    from: i64,
    hold: i64,
    /// `None` until a ramp under limits is sized (`Ramp::to_size`).
    distance: Option<NonZeroU64>,
}

impl Ramp {
    /// A ramp starting at master `from_master` with the slave at `hold`.
    pub(crate) fn new(ramp: RampIn, from_master: i64, hold: i64) -> Self {
        Self {
            from: from_master,
            hold,
            distance: Some(ramp.distance),
        }
    }

    /// A ramp under limits whose distance is not worked out yet: where a
    /// ramp starts it holds the slave whatever its length, so the tick
    /// that engages leaves the sizing (`ramp_in::LimitedLength`) to the
    /// next, which sizes it before it reads it ([`Ramp::size`];
    /// docs/engine.md, "Benchmarks"). Read unsized, it is a ramp at its
    /// start: the slave held, the weight 0, not finished.
    pub(crate) fn to_size(from_master: i64, hold: i64) -> Self {
        Self {
            from: from_master,
            hold,
            distance: None,
        }
    }

    /// Gives an unsized ramp its distance; a sized one keeps its own.
    #[inline]
    pub(crate) fn size(&mut self, distance: NonZeroU64) {
        if self.distance.is_none() {
            self.distance = Some(distance);
        }
    }

    /// Its distance is known.
    pub(crate) fn sized(&self) -> bool {
        self.distance.is_some()
    }

    /// The master travel it runs over, once sized.
    #[inline]
    fn span(&self) -> Option<MasterRamp> {
        debug_assert!(self.sized(), "a ramp read before it was sized");
        self.distance
            .map(|distance| MasterRamp::new(self.from, distance))
    }

    /// The blended position for `cam` at `master`, or `None` once the ramp
    /// is complete (the caller then follows the cam).
    pub(crate) fn blend(&self, master: i64, cam: i64) -> Option<i64> {
        // Where it starts the weight is 0: the slave holds, exactly (no
        // float of the gap, which a gap beyond 2^53 pulses would round),
        // and the engaging tick of a ramp-in skips the arithmetic.
        if master == self.from {
            return Some(self.hold);
        }
        let Some(span) = self.span() else {
            return Some(self.hold);
        };
        if span.finished(master) {
            return None;
        }
        let w = quintic(span.progress(master));
        let gap = exact_f64(i128::from(self.hold) - i128::from(cam));
        let offset = round_to_i128((1.0 - w) * gap);
        i64::try_from(i128::from(cam) + offset).ok()
    }

    /// The ramp is over at `at` (its whole distance travelled by the
    /// position itself, fraction included): the axis drops it then.
    pub(crate) fn finished_at(&self, at: MasterPosition) -> bool {
        self.span().is_some_and(|span| span.finished_at(at))
    }

    /// Velocity weight `w(u)` of the cam at `master` (for the reported ratio).
    pub(crate) fn weight(&self, master: i64) -> f64 {
        // Where it starts, `quintic(0)`, without the division.
        if master == self.from {
            return 0.0;
        }
        self.span()
            .map_or(0.0, |span| quintic(span.progress(master).min(1.0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blends_from_hold_onto_the_cam() {
        let ramp = Ramp::new(
            RampIn {
                distance: NonZeroU64::new(1000).unwrap(),
            },
            0,
            0,
        );
        assert_eq!(ramp.blend(0, 500), Some(0));
        assert_eq!(ramp.blend(500, 500), Some(250));
        assert_eq!(ramp.blend(1000, 500), None);
        // Quintic: the first steps move far less than the cam's own velocity.
        let first = ramp.blend(1, 1).unwrap_or(i64::MAX);
        assert_eq!(first, 0);
        assert!(ramp.weight(2000) == 1.0);
    }

    /// Where a ramp starts the slave holds exactly, however far the cam
    /// is (a float of a gap beyond 2^53 pulses is not exact), and the
    /// cam's weight is 0.
    #[test]
    fn the_start_holds_exactly_whatever_the_gap() {
        let distance = NonZeroU64::new(1000).unwrap();
        for (hold, cam) in [
            (i64::MAX - 3, -(1i64 << 60)),
            ((1i64 << 53) + 1, -7),
            (-5, 5),
            (12_345, 12_345),
        ] {
            let ramp = Ramp::new(RampIn { distance }, -20, hold);
            assert_eq!(ramp.blend(-20, cam), Some(hold), "{hold} {cam}");
            assert_eq!(ramp.weight(-20).to_bits(), 0.0f64.to_bits());
            // One count on, the cam's share is tiny but the ramp runs.
            assert!(ramp.weight(-19) > 0.0 && ramp.weight(-21) > 0.0);
        }
        // The blend's own arithmetic at the start, for an ordinary gap,
        // gives the same position.
        let ramp = Ramp::new(RampIn { distance }, 0, 700);
        let gap = exact_f64(700 - 300);
        assert_eq!(
            Some(300 + round_to_i128((1.0 - quintic(0.0)) * gap) as i64),
            ramp.blend(0, 300)
        );
    }
}
