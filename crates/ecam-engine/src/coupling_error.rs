//! What can go wrong with the couplings beyond the cam (modulo slave,
//! gear, phasing, superimposed moves, registration, direction guard, cam
//! switches): one error enum for the slave axis and its PLCopen blocks.

use core::fmt;

use ecam_core::CODE_PARAMETER;

use crate::EngineError;

/// A refused coupling command or setting. The running motion is left as
/// it was.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CouplingError {
    /// The cam refused (its own error).
    Engine(EngineError),
    /// A modulo of 0 or above 2^62 pulses.
    BadModulo,
    /// A velocity, acceleration or deceleration that is not a finite
    /// number above zero.
    BadLimit,
    /// A superimposed move asked for more velocity than the axis' pulse
    /// ceiling allows.
    AboveCeiling,
    /// `MC_GearInPos`: the master has already passed the sync position.
    SyncPassed,
    /// Registration: the window or the ramp does not fit the cycle (the
    /// window must be below half a cycle, the ramp at least twice the
    /// largest correction so that a correction cannot reverse the slave).
    BadRegistration,
    /// A cam-switch track number beyond the 32 tracks.
    BadTrack,
}

impl CouplingError {
    /// The document 003 operation error code (6781: a parameter), or the
    /// cam's own code.
    pub const fn code(self) -> u16 {
        match self {
            Self::Engine(e) => e.code(),
            Self::BadModulo
            | Self::BadLimit
            | Self::AboveCeiling
            | Self::SyncPassed
            | Self::BadRegistration
            | Self::BadTrack => CODE_PARAMETER,
        }
    }
}

impl From<EngineError> for CouplingError {
    fn from(e: EngineError) -> Self {
        Self::Engine(e)
    }
}

impl fmt::Display for CouplingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match self {
            Self::Engine(e) => return write!(f, "{e}"),
            Self::BadModulo => "the modulo must be between 1 and 2^62 pulses",
            Self::BadLimit => {
                "velocity, acceleration and deceleration must be finite numbers above zero"
            }
            Self::AboveCeiling => {
                "the superimposed velocity is above the axis' pulse frequency ceiling"
            }
            Self::SyncPassed => {
                "the master has already passed the sync position: choose one ahead of it"
            }
            Self::BadRegistration => {
                "registration: the window must be below half a cycle and the ramp at least twice the largest correction"
            }
            Self::BadTrack => "a cam-switch track must be between 0 and 31",
        };
        write!(f, "{text} (error {})", self.code())
    }
}

impl core::error::Error for CouplingError {}

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::ToString;

    #[test]
    fn messages_name_the_code() {
        assert!(CouplingError::BadModulo.to_string().contains("6781"));
        assert_eq!(
            CouplingError::Engine(EngineError::EmptyCycle).code(),
            EngineError::EmptyCycle.code()
        );
    }
}
