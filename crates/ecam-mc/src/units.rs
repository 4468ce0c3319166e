//! Axis settings of document 001: single-turn ranges and user units.

use core::num::NonZeroU64;

use crate::McError;

/// A single-turn encoder range: the axis position lives in `[0, counts)`
/// and wraps (document 001, `SetSingleTurn`). Document 001's "range from 0
/// to 30000" is `SingleTurn::new(30000)`: 30000 is the same place as 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SingleTurn(NonZeroU64);

impl SingleTurn {
    /// A turn of `counts`.
    ///
    /// # Errors
    /// [`McError::EmptyTurn`] for 0.
    pub fn new(counts: u64) -> Result<Self, McError> {
        NonZeroU64::new(counts).map(Self).ok_or(McError::EmptyTurn)
    }

    /// Counts per turn.
    pub const fn counts(self) -> NonZeroU64 {
        self.0
    }

    /// `position` wrapped into `[0, counts)`.
    pub fn wrap(self, position: i64) -> i64 {
        let turn = i128::from(self.0.get());
        // The remainder is below `turn`, itself at most u64::MAX; clamp for
        // turns beyond i64 (never wrapped into then).
        i64::try_from(i128::from(position).rem_euclid(turn)).unwrap_or(position)
    }
}

/// How many pulses make one user unit (document 001: first and last slave
/// positions "less than one user unit apart" are not joined by a Repeat cam).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UserUnit(NonZeroU64);

impl UserUnit {
    /// One pulse per user unit (every nonzero stroke is joined).
    pub const PULSE: UserUnit = UserUnit(NonZeroU64::MIN);

    /// `pulses` per user unit.
    ///
    /// # Errors
    /// [`McError::EmptyUserUnit`] for 0.
    pub fn new(pulses: u64) -> Result<Self, McError> {
        NonZeroU64::new(pulses)
            .map(Self)
            .ok_or(McError::EmptyUserUnit)
    }

    /// Pulses per user unit.
    pub const fn pulses(self) -> u64 {
        self.0.get()
    }
}

impl Default for UserUnit {
    fn default() -> Self {
        Self::PULSE
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn wrap_into_the_turn() {
        let t = SingleTurn::new(30000).unwrap();
        assert_eq!(t.wrap(30000), 0);
        assert_eq!(t.wrap(45000), 15000);
        assert_eq!(t.wrap(-1), 29999);
        assert!(SingleTurn::new(0).is_err());
        assert!(UserUnit::new(0).is_err());
    }
}
