//! Document 001's E-CAM types.

use ecam_engine::Coupling;

use crate::UserUnit;

/// How the E-CAM table repeats along the master.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CamType {
    /// No repetition: beyond the table the slave holds the end value.
    #[default]
    Normal,
    /// The table repeats; if its first and last slave positions differ the
    /// slave jumps at the seam.
    Periodic,
    /// The table repeats and the slave is made continuous at each seam: each
    /// cycle adds `last − first`. Ends less than one user unit apart are not
    /// joined (the cam then behaves as Periodic); equal ends make Repeat and
    /// Periodic identical.
    Repeat,
}

impl CamType {
    /// The engine coupling for this type, with `unit` the slave's user unit.
    pub fn coupling(self, unit: UserUnit) -> Coupling {
        match self {
            Self::Normal => Coupling::Normal,
            Self::Periodic => Coupling::Periodic,
            Self::Repeat => Coupling::Repeat {
                min_stroke: unit.pulses(),
            },
        }
    }
}
