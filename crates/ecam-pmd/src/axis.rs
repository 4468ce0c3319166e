//! One axis of the motion processor: its modes, positions, cam and status words.

use crate::{Breakpoint, CamSettings, PmdError, RunningCam};

/// Profile modes this emulation runs (`SetProfileMode`).
///
/// Document 002 adds ElectronicCam (8) to the processor's modes; the other
/// profile generators (velocity contouring, S-curve, electronic gear,
/// external) are not part of the cam face and are refused. Trapezoidal is
/// the power-up mode; here an axis in it moves only by the simulation
/// commands (`MoveTo`, `SetActualPosition`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ProfileMode {
    /// 0: the power-up mode (moves come from the simulation commands).
    #[default]
    Trapezoidal,
    /// 8: electronic cam (document 002).
    ElectronicCam,
}

impl ProfileMode {
    /// Decodes a `SetProfileMode` argument: a number or a name.
    ///
    /// # Errors
    /// [`PmdError::NotSimulated`] for modes 1–4, [`PmdError::OutOfRange`] otherwise.
    pub fn decode(code: i64) -> Result<Self, PmdError> {
        match code {
            0 => Ok(Self::Trapezoidal),
            8 => Ok(Self::ElectronicCam),
            1..=4 => Err(PmdError::NotSimulated {
                what: "profile mode",
                code,
            }),
            _ => Err(PmdError::OutOfRange {
                what: "profile mode",
                value: code,
                allowed: "0 Trapezoidal or 8 ElectronicCam",
            }),
        }
    }

    /// The mode's number.
    pub const fn code(self) -> i64 {
        match self {
            Self::Trapezoidal => 0,
            Self::ElectronicCam => 8,
        }
    }
}

/// `SetStopMode` arguments (PMD numbering).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum StopMode {
    /// 0: no stop pending.
    #[default]
    None,
    /// 1: abrupt: a cam or a simulated move holds its position at the `Update`.
    Abrupt,
    /// 2: smooth: a cam stops at the next end of its table (at once when
    /// on one); a simulated move, which has no deceleration, at once.
    Smooth,
}

impl StopMode {
    /// Decodes a `SetStopMode` argument.
    ///
    /// # Errors
    /// [`PmdError::OutOfRange`] unless 0, 1 or 2.
    pub fn decode(code: i64) -> Result<Self, PmdError> {
        match code {
            0 => Ok(Self::None),
            1 => Ok(Self::Abrupt),
            2 => Ok(Self::Smooth),
            _ => Err(PmdError::OutOfRange {
                what: "stop mode",
                value: code,
                allowed: "0 none, 1 abrupt or 2 smooth",
            }),
        }
    }
}

/// Event status bits (PMD numbering).
pub mod event_bit {
    /// Bit 0: a cam stopped (its motion is complete).
    pub const MOTION_COMPLETE: u16 = 1 << 0;
    /// Bit 2: breakpoint 0 ("Breakpoint 1") fired.
    pub const BREAKPOINT_0: u16 = 1 << 2;
    /// Bit 4: motion error — a `StartCam` found the cam not ready.
    pub const MOTION_ERROR: u16 = 1 << 4;
    /// Bit 7: instruction error — an `Update` action was refused.
    pub const INSTRUCTION_ERROR: u16 = 1 << 7;
    /// Bit 14: breakpoint 1 ("Breakpoint 2") fired.
    pub const BREAKPOINT_1: u16 = 1 << 14;
}

/// Activity status bits this emulation drives.
pub mod activity_bit {
    /// Bit 10: the axis is in motion (cam active or a simulated move).
    pub const IN_MOTION: u16 = 1 << 10;
    /// Bits 15:13, the profile segment field; document 002: 1 = cam active.
    pub const CAM_ACTIVE: u16 = 1 << 13;
}

/// A simulated linear move (`MoveTo`): constant velocity from the command
/// on, with no acceleration or deceleration. Abrupt and smooth stops both
/// end it where it is (see `docs/pmd.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LinearMove {
    /// Position at the command.
    pub from: i64,
    /// Target.
    pub to: i64,
    /// Cycles the move takes (≥ 1).
    pub ticks: u32,
    /// Cycles done.
    pub done: u32,
}

impl LinearMove {
    /// Advances one cycle and gives the new position (exactly `to` at the end).
    pub fn step(&mut self) -> i64 {
        self.done = self.done.saturating_add(1).min(self.ticks);
        let span = i128::from(self.to) - i128::from(self.from);
        let pos =
            i128::from(self.from) + span * i128::from(self.done) / i128::from(self.ticks.max(1));
        i64::try_from(pos).unwrap_or(self.to)
    }

    /// Whether the move has arrived.
    pub fn finished(&self) -> bool {
        self.done >= self.ticks
    }
}

/// What drives an axis' position: nothing, a simulated move, or a cam;
/// never a move and a cam at once (a cam start ends a move, a move is
/// refused while a cam runs).
#[derive(Debug, Default)]
pub enum Motion {
    /// The axis stands.
    #[default]
    Still,
    /// A simulated linear move (`MoveTo`) in progress.
    Moving(LinearMove),
    /// The started cam, while active.
    Camming(Box<RunningCam>),
}

impl Motion {
    /// Whether a cam drives the axis.
    pub fn is_camming(&self) -> bool {
        matches!(self, Self::Camming(_))
    }
}

/// One axis.
#[derive(Debug, Default)]
pub struct Axis {
    /// The mode in effect.
    pub mode: ProfileMode,
    /// The mode `Update` will put into effect.
    pub pending_mode: ProfileMode,
    /// The stop `Update` will perform.
    pub pending_stop: StopMode,
    /// Actual (encoder) position.
    pub actual: i64,
    /// Commanded position.
    pub commanded: i64,
    /// `SetCam` parameters and the last offsets.
    pub cam: CamSettings,
    /// What drives the position.
    pub motion: Motion,
    /// Breakpoints 0 and 1.
    pub breakpoints: [Breakpoint; 2],
    /// Event status word.
    pub event_status: u16,
}

impl Axis {
    /// Whether the axis moves (a cam active or a simulated move under way).
    pub fn in_motion(&self) -> bool {
        !matches!(self.motion, Motion::Still)
    }

    /// The activity status word.
    pub fn activity_status(&self) -> u16 {
        let mut word = 0;
        if self.in_motion() {
            word |= activity_bit::IN_MOTION;
        }
        if self.motion.is_camming() {
            word |= activity_bit::CAM_ACTIVE;
        }
        word
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_move_is_exact_at_the_end() {
        let mut m = LinearMove {
            from: 0,
            to: 10,
            ticks: 3,
            done: 0,
        };
        assert_eq!([m.step(), m.step(), m.step(), m.step()], [3, 6, 10, 10]);
        assert!(m.finished());
    }

    #[test]
    fn modes_decode() {
        assert_eq!(ProfileMode::decode(8), Ok(ProfileMode::ElectronicCam));
        assert!(matches!(
            ProfileMode::decode(3),
            Err(PmdError::NotSimulated { .. })
        ));
        assert!(ProfileMode::decode(9).is_err());
        assert_eq!(StopMode::decode(2), Ok(StopMode::Smooth));
        assert!(StopMode::decode(3).is_err());
    }
}
