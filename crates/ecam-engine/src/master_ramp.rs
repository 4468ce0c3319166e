//! The one shape of every change the engine spreads over master travel:
//! the ramp-in (`ramp.rs`), the offset and slave-scaling changes
//! (`offset_ramp.rs`, `scaling.rs`) and a switch's blend (`blend.rs`) each
//! start at a master position and run for a master distance, in either
//! direction, with `u = |master − from| / distance` saying how far along
//! they are. Being functions of the master and not of time, they stay
//! exact whatever the master does, and stopping or reversing the master
//! stops or reverses them.

use core::num::NonZeroU64;

use crate::MasterPosition;
use crate::rounding::unsigned_to_f64;

/// The smooth-step `w(u) = 10u³ − 15u⁴ + 6u⁵` on `0 ≤ u ≤ 1`: 0 and 1 at
/// the ends with zero slope and curvature there. The ramp-in, the offset
/// and scaling ramps and a blend's end fraction all move along it, and so
/// do the gear's and registration's corrections.
pub(crate) fn quintic(u: f64) -> f64 {
    u * u * u * (10.0 + u * (-15.0 + 6.0 * u))
}

/// `∫₀ᵘ (3t² − 2t³) dt`: the distance a velocity blended along the cubic
/// smooth-step covers (a switch's blend, a gear's ratio blend).
#[inline]
pub(crate) fn smoothstep_integral(u: f64) -> f64 {
    u * u * u * (1.0 - 0.5 * u)
}

/// The smooth-step's slope `w'(u) = 30u²(1 − u)²`: what a ratio ramped
/// along [`quintic`] adds to the velocity (the slave-scaling ramp).
#[inline]
pub(crate) fn quintic_slope(u: f64) -> f64 {
    30.0 * u * u * (1.0 - u) * (1.0 - u)
}

/// A stretch of master travel from where a change began, either way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct MasterRamp {
    from: i64,
    distance: u64,
}

impl MasterRamp {
    /// From master `from` over `distance` counts.
    pub(crate) fn new(from: i64, distance: NonZeroU64) -> Self {
        Self {
            from,
            distance: distance.get(),
        }
    }

    /// Where it began.
    pub(crate) fn from(&self) -> i64 {
        self.from
    }

    /// Its master distance.
    pub(crate) fn distance(&self) -> u64 {
        self.distance
    }

    /// Master counts from the start to `master`, either way.
    pub(crate) fn travelled(&self, master: i64) -> u128 {
        (i128::from(master) - i128::from(self.from)).unsigned_abs()
    }

    /// `master` lies before the start (the master went backwards).
    pub(crate) fn backwards(&self, master: i64) -> bool {
        master < self.from
    }

    /// The whole distance has been travelled at `master`.
    pub(crate) fn finished(&self, master: i64) -> bool {
        self.travelled(master) >= u128::from(self.distance)
    }

    /// [`Self::finished`] for the position itself, fraction included: a
    /// ramp ends where the position reaches its end, not its whole count
    /// (below the position when the master runs backwards).
    pub(crate) fn finished_at(&self, at: MasterPosition) -> bool {
        self.finished(at.count_toward(self.from))
    }

    /// `u`: the travel at `master` over the distance (beyond 1 past the end).
    pub(crate) fn progress(&self, master: i64) -> f64 {
        unsigned_to_f64(self.travelled(master)) / self.distance as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ramp_ends_at_its_distance_either_way() {
        let ramp = MasterRamp::new(50, NonZeroU64::new(100).unwrap());
        assert!(!ramp.finished(149));
        assert!(ramp.finished(150));
        assert!(ramp.finished(-50));
        assert!(!ramp.finished(-49));
        assert!(ramp.backwards(49) && !ramp.backwards(50));
        assert_eq!(ramp.progress(100), 0.5);
        assert_eq!(ramp.progress(0), 0.5);
        assert_eq!(quintic(0.5), 0.5);
        assert_eq!((quintic(0.0), quintic(1.0)), (0.0, 1.0));
    }
}
