//! Phasing (PLCopen `MC_PhasingAbsolute` / `MC_PhasingRelative`, Omron's
//! phase shift): the master the slave sees is shifted by a distance, ramped
//! over time under velocity and acceleration limits, while the cam (and a
//! gear) keeps running on the shifted master.
//!
//! The shift is a [`TimedMove`] in master counts: it starts from the shift
//! in force (and its velocity, when it replaces a running one), ends on a
//! whole number of counts, and from then on the slave is again the exact
//! function of the shifted master. The limits are those of the shift
//! itself, in master counts per second (as TwinCAT reads them for
//! camming): the master the slave sees moves at the master's speed plus at
//! most `velocity`, and speeds up by at most `acceleration`.

use crate::CouplingError;
use crate::timed_move::{ONE, TimedMove, to_units};
use crate::trapezoid::MoveLimits;

/// Whether a phase shift is the new total or added to the one in force.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PhasingMode {
    /// `MC_PhasingAbsolute`: the shift becomes this many counts.
    #[default]
    Absolute,
    /// `MC_PhasingRelative`: this many counts are added to the shift in
    /// force where it stands (a running shift's unreached rest is dropped).
    Relative,
}

/// An `MC_Phasing` command.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Phasing {
    /// `PhaseShift`: master counts (positive: the slave sees the master
    /// further on, so it runs ahead).
    pub shift: i64,
    /// Absolute or relative.
    pub mode: PhasingMode,
    /// `Velocity`, `Acceleration`, `Deceleration` of the shift.
    pub limits: MoveLimits,
}

/// What the phasing reports every tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhasingStatus {
    /// `Busy`/`Active`: a shift is being ramped.
    pub active: bool,
    /// `Done`: the last shift commanded is complete (until the next command).
    pub done: bool,
    /// `AbsolutePhaseShift`: the shift in force, master counts (with its fraction).
    pub shift: f64,
    /// `CoveredPhaseShift`: how far the current command has moved the shift.
    pub covered: f64,
    /// The shift's velocity, master counts per second.
    pub velocity: f64,
}

/// The shift and the bookkeeping of its commands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PhaseShift {
    shift: TimedMove,
    started_at: i128,
    done: bool,
}

impl PhaseShift {
    pub(crate) const fn new() -> Self {
        Self {
            shift: TimedMove::at_rest(0),
            started_at: 0,
            done: false,
        }
    }

    /// Takes a command.
    pub(crate) fn command(&mut self, phasing: &Phasing) -> Result<(), CouplingError> {
        let shift = i128::from(phasing.shift) * ONE;
        let to = match phasing.mode {
            PhasingMode::Absolute => shift,
            PhasingMode::Relative => (crate::timed_move::whole(self.shift.position()) << 32)
                .checked_add(shift)
                .ok_or(CouplingError::BadLimit)?,
        };
        self.started_at = self.shift.position();
        self.done = false;
        self.shift.start(to, phasing.limits);
        Ok(())
    }

    /// Ends a running shift where it stands (on a whole count).
    pub(crate) fn stop(&mut self) {
        self.shift.stop();
    }

    /// Brings a running shift to rest at `deceleration` (counts/s²).
    pub(crate) fn halt(&mut self, deceleration: f64) {
        self.shift.halt(deceleration);
    }

    /// Advances by `dt_us`; the shift in fixed point.
    pub(crate) fn advance(&mut self, dt_us: u32) -> i128 {
        if self.shift.advance(dt_us) {
            self.done = true;
        }
        self.shift.position()
    }

    pub(crate) fn status(&self) -> PhasingStatus {
        PhasingStatus {
            active: self.shift.is_active(),
            done: self.done,
            shift: to_units(self.shift.position()),
            covered: to_units(self.shift.position() - self.started_at),
            velocity: self.shift.velocity(),
        }
    }
}
