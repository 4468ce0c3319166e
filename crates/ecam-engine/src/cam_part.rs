//! The cam of a [`crate::SlaveAxis`]: the engine's [`CamAxis`] itself, or
//! the PLCopen facade over it ([`crate::plcopen::McCamAxis`]). The slave
//! axis ticks it with the master it sees and adds its commanded position
//! to the other parts.

use core::fmt::Debug;

use ecam_core::CamCurve;

use crate::{CamAxis, EngineError, TickInput, TickOutput};

/// A cam a slave axis can carry.
pub trait CamPart {
    /// The cam curve.
    type Curve: CamCurve;
    /// What one tick of the cam reports.
    type Status: Clone + Copy + Debug;

    /// One tick of the cam with the master the slave sees.
    fn tick_cam(&mut self, input: &TickInput) -> Self::Status;

    /// The engine output inside a status.
    fn output(status: &Self::Status) -> &TickOutput;

    /// The engine axis.
    fn engine(&self) -> &CamAxis<Self::Curve>;

    /// Declares where the cam's part stands (while it is not active).
    ///
    /// # Errors
    /// [`EngineError::Busy`] while the cam is armed, engaged or moving.
    fn set_position(&mut self, position: i64) -> Result<(), EngineError>;
}

impl<C: CamCurve> CamPart for CamAxis<C> {
    type Curve = C;
    type Status = TickOutput;

    fn tick_cam(&mut self, input: &TickInput) -> TickOutput {
        *self.tick_in_place(input)
    }

    fn output(status: &TickOutput) -> &TickOutput {
        status
    }

    fn engine(&self) -> &CamAxis<C> {
        self
    }

    fn set_position(&mut self, position: i64) -> Result<(), EngineError> {
        self.set_slave_position(position)
    }
}
