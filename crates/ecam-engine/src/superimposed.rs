//! A superimposed move (PLCopen `MC_MoveSuperimposed`,
//! `MC_HaltSuperimposed`): a relative distance added to whatever else
//! drives the slave (cam, gear), over time under its own velocity,
//! acceleration and deceleration.
//!
//! The move is a [`TimedMove`] in pulses: a new command while one runs
//! replaces it, taking over from where it stands with the velocity it has,
//! and the new distance counts from there (PLCopen: only the superimposed
//! command is replaced, never the motion under it). What has been covered
//! stays: the moves of a run add up exactly, each ending on a whole pulse.

use crate::CouplingError;
use crate::timed_move::{ONE, TimedMove, whole};
use crate::trapezoid::MoveLimits;

/// An `MC_MoveSuperimposed` command.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveSuperimposed {
    /// `Distance`: pulses added to the slave.
    pub distance: i64,
    /// `VelocityDiff`, `Acceleration`, `Deceleration`: the move's own
    /// limits (pulses/s, pulses/s²), on top of the motion under it.
    pub limits: MoveLimits,
}

/// What the superimposed move reports every tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SuperimposedStatus {
    /// `Busy`/`Active`: a move (or a halt) is running.
    pub active: bool,
    /// `Done`: the last move commanded is complete (until the next command).
    pub done: bool,
    /// The pulses all superimposed moves have added so far.
    pub position: i64,
    /// `CoveredDistance`: how far the current command has moved.
    pub covered: i64,
    /// The move's velocity, pulses per second.
    pub velocity: f64,
}

/// The superimposed part of a slave axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Superimposed {
    part: TimedMove,
    started_at: i128,
    done: bool,
}

impl Superimposed {
    pub(crate) const fn new() -> Self {
        Self {
            part: TimedMove::at_rest(0),
            started_at: 0,
            done: false,
        }
    }

    /// Takes a command; the distance counts from where the part stands
    /// (on a whole pulse).
    ///
    /// # Errors
    /// [`CouplingError::AboveCeiling`] when the velocity is above `ceiling_hz`.
    pub(crate) fn command(
        &mut self,
        command: &MoveSuperimposed,
        ceiling_hz: u32,
    ) -> Result<(), CouplingError> {
        if command.limits.velocity() > f64::from(ceiling_hz) {
            return Err(CouplingError::AboveCeiling);
        }
        let to = (whole(self.part.position()) + i128::from(command.distance)) * ONE;
        self.started_at = self.part.position();
        self.done = false;
        self.part.start(to, command.limits);
        Ok(())
    }

    /// `MC_HaltSuperimposed`: to rest at `deceleration` pulses/s².
    pub(crate) fn halt(&mut self, deceleration: f64) {
        self.part.halt(deceleration);
    }

    /// Ends a running move where it stands.
    pub(crate) fn stop(&mut self) {
        self.part.stop();
    }

    /// Advances by `dt_us`; the part in whole pulses.
    pub(crate) fn advance(&mut self, dt_us: u32) -> i64 {
        if self.part.advance(dt_us) {
            self.done = true;
        }
        self.pulses()
    }

    /// The part in whole pulses.
    pub(crate) fn pulses(&self) -> i64 {
        clamp(whole(self.part.position()))
    }

    pub(crate) fn status(&self) -> SuperimposedStatus {
        SuperimposedStatus {
            active: self.part.is_active(),
            done: self.done,
            position: self.pulses(),
            covered: clamp(whole(self.part.position()) - whole(self.started_at)),
            velocity: self.part.velocity(),
        }
    }

    /// The part's position as a float (for tests of the profile).
    #[cfg(test)]
    pub(crate) fn exact(&self) -> f64 {
        crate::timed_move::to_units(self.part.position())
    }
}

fn clamp(v: i128) -> i64 {
    i64::try_from(v).unwrap_or(if v < 0 { i64::MIN } else { i64::MAX })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moves_add_up_exactly() {
        let limits = MoveLimits::new(2000.0, 10_000.0, 10_000.0).unwrap();
        let mut s = Superimposed::new();
        s.command(
            &MoveSuperimposed {
                distance: 777,
                limits,
            },
            200_000,
        )
        .unwrap();
        for _ in 0..200 {
            s.advance(1000);
        }
        // Replaced half way: the new 100 counts from where it stood.
        s.command(
            &MoveSuperimposed {
                distance: 100,
                limits,
            },
            200_000,
        )
        .unwrap();
        let from = s.pulses();
        while !s.status().done {
            s.advance(1000);
        }
        assert_eq!(s.pulses(), from + 100);
        assert_eq!(s.exact(), (from + 100) as f64);
        let fast = MoveLimits::new(300_000.0, 1.0, 1.0).unwrap();
        assert_eq!(
            s.command(
                &MoveSuperimposed {
                    distance: 1,
                    limits: fast
                },
                200_000
            ),
            Err(CouplingError::AboveCeiling)
        );
    }
}
