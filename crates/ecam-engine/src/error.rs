//! What can go wrong when configuring or running a cam axis.

use core::fmt;

/// An engine error: a refused configuration or a fault that stopped a cam.
///
/// [`EngineError::code`] maps each onto the PLC manual's (document 003)
/// operation error codes, so the PLC face can report them the device's way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EngineError {
    /// The axis is armed or following a cam; stop it before changing this.
    Busy,
    /// A zoom numerator or denominator is zero (allowed: 1 to 65535).
    BadZoom,
    /// The cam's master range is empty or reversed (`master_last <= master_first`).
    EmptyCycle,
    /// The single-turn range is too large (at most 2^62 counts).
    BadTurn,
    /// A single-turn cam table reaches outside the turn `[0, turn]`.
    TableOutsideTurn,
    /// The commanded slave position (or a value on the way to it) no longer
    /// fits 64 bits; the cam was stopped where it was.
    SlaveOverflow,
    /// The cam curve returned a value that is not a finite number.
    CurveNotFinite,
    /// The master moved more than [`crate::AxisConfig::max_master_step`] in
    /// one tick; the cam was stopped where it was.
    MasterStep,
    /// A normal (non-repeating) cam has no seam at which a queued table
    /// could take over.
    NoSeam,
    /// The request needs a running cam (e.g. offsets changed on the fly).
    NotRunning,
    /// A ramp-in cannot keep to its limits: the cam alone, at the master's
    /// speed, needs more velocity than the limit leaves for a catch-up.
    RampInLimits,
    /// A ramp-in restricted to one direction cannot close its gap that
    /// way (a cam without a stroke to add).
    RampDirection,
    /// A PLCopen `BufferMode` the cam facade does not offer (the blending
    /// modes); aborting and buffered are supported.
    UnsupportedBufferMode,
    /// A negative master zoom on a one-shot cam: its travel is counted
    /// forwards from the engage point, so it cannot run backwards.
    ReversedOneShot,
}

use ecam_core::CamErrorCode;

impl EngineError {
    /// The document 003 operation error: a parameter error for parameters
    /// and runtime faults, a table error for a table that does not fit the
    /// configuration.
    pub const fn kind(self) -> CamErrorCode {
        match self {
            Self::EmptyCycle | Self::TableOutsideTurn | Self::CurveNotFinite => CamErrorCode::Table,
            Self::Busy
            | Self::BadZoom
            | Self::BadTurn
            | Self::SlaveOverflow
            | Self::MasterStep
            | Self::NoSeam
            | Self::NotRunning
            | Self::RampInLimits
            | Self::RampDirection
            | Self::UnsupportedBufferMode
            | Self::ReversedOneShot => CamErrorCode::Parameter,
        }
    }

    /// The document 003 operation error code: 6781 for parameters and
    /// runtime faults, 6782 for a table that does not fit the configuration.
    pub const fn code(self) -> u16 {
        self.kind().number()
    }
}

impl fmt::Display for EngineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match self {
            Self::Busy => {
                "the cam axis is armed or running: stop it before changing its table or configuration"
            }
            Self::BadZoom => "zoom numerator and denominator must each be between 1 and 65535",
            Self::EmptyCycle => {
                "the cam table's last master position must be greater than its first"
            }
            Self::BadTurn => "the single-turn range must be between 1 and 2^62 master counts",
            Self::TableOutsideTurn => "a single-turn cam table must lie within the turn [0, turn]",
            Self::SlaveOverflow => {
                "the commanded slave position overflowed 64 bits; the cam was stopped"
            }
            Self::CurveNotFinite => {
                "the cam curve returned a value that is not a finite number; the cam was stopped"
            }
            Self::MasterStep => {
                "the master moved more than the allowed step in one tick; the cam was stopped"
            }
            Self::NoSeam => "a normal cam has no seam: stop it before changing its table",
            Self::NotRunning => {
                "the cam is not running: engage it first, or set this in the configuration"
            }
            Self::RampInLimits => {
                "the ramp-in cannot keep to its velocity limit at this master speed; the cam was stopped"
            }
            Self::RampDirection => {
                "the ramp-in cannot close its gap in the allowed direction (no stroke to add); the cam was stopped"
            }
            Self::ReversedOneShot => {
                "a one-shot cam cannot run backwards: use a positive master scaling, or a periodic or absolute-master table"
            }
            Self::UnsupportedBufferMode => {
                "this BufferMode is not supported for cams: use aborting (at once or at the activation position, blended over CamIn::blend) or buffered (at the next seam, blended)"
            }
        };
        write!(f, "{text} (error {})", self.code())
    }
}

impl core::error::Error for EngineError {}

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::ToString;

    #[test]
    fn display_names_the_code() {
        assert!(EngineError::BadZoom.to_string().contains("6781"));
        assert!(EngineError::TableOutsideTurn.to_string().contains("6782"));
        assert_eq!(EngineError::CurveNotFinite.code(), 6782);
    }
}
