//! Direction guards (Rockwell's master direction "forward only" /
//! "reverse only", a slip clutch): the slave follows the master only in
//! one direction. When the master reverses, the master the slave sees
//! stands still, so the slave holds without a jump; when the master comes
//! back the slave goes on from where it stood, again without a jump.
//!
//! Two ways of coming back ([`GuardResume`]):
//! - `AtOnce` (the slip clutch): the slave moves again as soon as the
//!   master moves the allowed way; the master's travel the other way is
//!   lost for good, and counted (`lost` grows by it);
//! - `AtReversalPoint` (Rockwell's master direction): the slave waits
//!   until the master has come back to where it turned, so the phase
//!   between master and slave is kept; `lost` is the distance still to
//!   make up, 0 once the slave follows again.
//!
//! The guard works on the master position in fixed point (a fraction of a
//! count included), before any phase shift: a phasing or a registration
//! correction the other way is a motion the command asked for.

use crate::timed_move::to_units;

/// The direction the slave may follow.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GuardDirection {
    /// Follow the master only while it moves forwards.
    #[default]
    Forward,
    /// Follow the master only while it moves backwards.
    Backward,
}

/// How the slave takes up the master again after a reversal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GuardResume {
    /// At once (a slip clutch): the reversed travel is lost.
    #[default]
    AtOnce,
    /// When the master is back where it turned: the phase is kept.
    AtReversalPoint,
}

/// A direction guard's settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DirectionGuard {
    /// The direction the slave follows.
    pub direction: GuardDirection,
    /// How it takes up the master again.
    pub resume: GuardResume,
}

/// What the guard reports every tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GuardStatus {
    /// The slave does not follow the master this tick (it moved the other
    /// way, or has not come back to where it turned).
    pub held: bool,
    /// Master counts not followed: the travel the other way lost so far
    /// (`AtOnce`), or the distance still to make up (`AtReversalPoint`).
    pub lost: f64,
}

/// The guard's state: the master followed, from the real one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Guard {
    config: DirectionGuard,
    last: Option<i128>,
    followed: i128,
    held: bool,
}

impl Guard {
    pub(crate) const fn new(config: DirectionGuard) -> Self {
        Self {
            config,
            last: None,
            followed: 0,
            held: false,
        }
    }

    /// The master the slave follows for the real master `m` (fixed point).
    pub(crate) fn update(&mut self, m: i128) -> i128 {
        let Some(last) = self.last else {
            self.last = Some(m);
            self.followed = m;
            return m;
        };
        self.last = Some(m);
        let forward = self.config.direction == GuardDirection::Forward;
        let step = m - last;
        let allowed = if forward { step > 0 } else { step < 0 };
        match self.config.resume {
            GuardResume::AtOnce => {
                if allowed {
                    self.followed += step;
                }
                if step != 0 {
                    self.held = !allowed;
                }
            }
            GuardResume::AtReversalPoint => {
                // The followed master is the farthest the real one has
                // been the allowed way, shifted by any slip (none here).
                self.followed = if forward {
                    self.followed.max(m)
                } else {
                    self.followed.min(m)
                };
                self.held = self.followed != m;
            }
        }
        self.followed
    }

    pub(crate) fn status(&self) -> GuardStatus {
        let gap = to_units(self.followed - self.last.unwrap_or(self.followed));
        GuardStatus {
            held: self.held,
            lost: match self.config.direction {
                GuardDirection::Forward => gap,
                GuardDirection::Backward => -gap,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::timed_move::ONE;

    fn run(config: DirectionGuard, masters: &[i64]) -> std::vec::Vec<i64> {
        let mut g = Guard::new(config);
        masters
            .iter()
            .map(|&m| (g.update(i128::from(m) * ONE) >> 32) as i64)
            .collect()
    }

    #[test]
    fn a_slip_clutch_loses_the_reversed_travel() {
        let c = DirectionGuard::default();
        let out = run(c, &[0, 10, 20, 15, 5, 8, 30]);
        assert_eq!(out, [0, 10, 20, 20, 20, 23, 45]);
        let mut g = Guard::new(c);
        for m in [0, 10, 20, 15, 5, 8, 30] {
            g.update(i128::from(m) * ONE);
        }
        assert_eq!(g.status().lost, 15.0);
    }

    #[test]
    fn at_the_reversal_point_keeps_the_phase() {
        let c = DirectionGuard {
            direction: GuardDirection::Forward,
            resume: GuardResume::AtReversalPoint,
        };
        assert_eq!(
            run(c, &[0, 10, 20, 15, 5, 8, 20, 30]),
            [0, 10, 20, 20, 20, 20, 20, 30]
        );
        let back = DirectionGuard {
            direction: GuardDirection::Backward,
            resume: GuardResume::AtOnce,
        };
        assert_eq!(run(back, &[0, -10, -5, -7]), [0, -10, -10, -12]);
    }
}
