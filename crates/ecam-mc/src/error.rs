//! Why the motion controller refused a request.

use core::fmt;

use ecam_engine::EngineError;

/// A refused motion-controller request; nothing changed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum McError {
    /// No axis with this number.
    NoSuchAxis {
        /// The axis asked for.
        axis: usize,
        /// How many axes there are.
        count: usize,
    },
    /// A single-turn range of 0 counts.
    EmptyTurn,
    /// A user unit of 0 pulses.
    EmptyUserUnit,
    /// The master and slave of a cam are the same axis.
    SameAxis {
        /// The axis.
        axis: usize,
    },
    /// The axis is already the slave of a running E-CAM.
    SlaveBusy {
        /// The axis.
        axis: usize,
    },
    /// The axis is the master or slave of a running E-CAM; stop it first.
    AxisInUse {
        /// The axis.
        axis: usize,
    },
    /// The engine refused the table or configuration.
    Engine(EngineError),
}

impl fmt::Display for McError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoSuchAxis { axis, count } => {
                write!(
                    f,
                    "no axis {axis}: axes are numbered 0 to {}",
                    count.saturating_sub(1)
                )
            }
            Self::EmptyTurn => f.write_str("a single-turn encoder range must be at least 1 count"),
            Self::EmptyUserUnit => f.write_str("a user unit must be at least 1 pulse"),
            Self::SameAxis { axis } => write!(f, "axis {axis} cannot be its own master"),
            Self::SlaveBusy { axis } => {
                write!(
                    f,
                    "axis {axis} already follows an E-CAM: stop it before starting another"
                )
            }
            Self::AxisInUse { axis } => {
                write!(
                    f,
                    "axis {axis} takes part in a running E-CAM: stop the E-CAM first"
                )
            }
            Self::Engine(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for McError {}

impl From<EngineError> for McError {
    fn from(e: EngineError) -> Self {
        Self::Engine(e)
    }
}
