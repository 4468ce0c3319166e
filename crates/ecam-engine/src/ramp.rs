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

use crate::coupling::{exact_f64, round_to_i128, unsigned_to_f64};
use crate::{MasterPosition, RampIn};

/// The smooth-step `w(u) = 10u³ − 15u⁴ + 6u⁵` on `0 ≤ u ≤ 1`: 0 and 1 at
/// the ends with zero slope and curvature there. The ramp-in, the offset
/// and scaling ramps and a blend's end fraction all move along it.
pub(crate) fn quintic(u: f64) -> f64 {
    u * u * u * (10.0 + u * (-15.0 + 6.0 * u))
}

/// A ramp in progress.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Ramp {
    from_master: i64,
    distance: u64,
    hold: i64,
}

impl Ramp {
    /// A ramp starting at master `from_master` with the slave at `hold`.
    pub(crate) fn new(ramp: RampIn, from_master: i64, hold: i64) -> Self {
        Self {
            from_master,
            distance: ramp.distance.get(),
            hold,
        }
    }

    /// Master counts from the ramp's start to `master`, either way.
    fn travelled(&self, master: i64) -> u128 {
        (i128::from(master) - i128::from(self.from_master)).unsigned_abs()
    }

    /// The blended position for `cam` at `master`, or `None` once the ramp
    /// is complete (the caller then follows the cam).
    pub(crate) fn blend(&self, master: i64, cam: i64) -> Option<i64> {
        let travelled = self.travelled(master);
        if travelled >= u128::from(self.distance) {
            return None;
        }
        let w = quintic(unsigned_to_f64(travelled) / self.distance as f64);
        let gap = exact_f64(i128::from(self.hold) - i128::from(cam));
        let offset = round_to_i128((1.0 - w) * gap);
        i64::try_from(i128::from(cam) + offset).ok()
    }

    /// The ramp is over at `at` (its whole distance travelled by the
    /// position itself, fraction included): the axis drops it then.
    pub(crate) fn finished_at(&self, at: MasterPosition) -> bool {
        self.travelled(at.count_toward(self.from_master)) >= u128::from(self.distance)
    }

    /// Velocity weight `w(u)` of the cam at `master` (for the reported ratio).
    pub(crate) fn weight(&self, master: i64) -> f64 {
        quintic((unsigned_to_f64(self.travelled(master)) / self.distance as f64).min(1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::num::NonZeroU64;

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
}
