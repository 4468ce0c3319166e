//! Leaving the cam at velocity (PLCopen `MC_CamOut`) and the decelerating
//! stop that ends such a motion.

use core::num::NonZeroU64;

use ecam_core::CamCurve;

use crate::EngineError;
use crate::coast::Coast;
use crate::config::effective_frequency;

use super::CamAxis;
use super::phase::Phase;

impl<C: CamCurve> CamAxis<C> {
    /// Disengages the cam and lets the slave continue at the velocity it
    /// has (PLCopen `MC_CamOut`): the cam's velocity ratio of the last tick
    /// times the master's mean velocity over the last ticks, bounded by the
    /// pulse frequency limit. The axis is [`crate::AxisState::Velocity`]
    /// until [`CamAxis::stop`] holds the slave where it is or
    /// [`CamAxis::stop_decelerating`] brings it to rest. Pulses stay exact:
    /// the position is the integer sum of velocity × tick length.
    ///
    /// # Errors
    /// [`EngineError::NotRunning`] unless the cam is engaged.
    pub fn cam_out_at_velocity(&mut self) -> Result<(), EngineError> {
        let velocity = self.last.velocity_ratio * self.speed.velocity();
        let ceiling = effective_frequency(self.config.max_frequency_hz);
        let phase = core::mem::replace(&mut self.phase, Phase::Idle);
        match phase {
            Phase::Running(engaged) | Phase::Stopping(engaged, _) => {
                self.end_run(engaged);
                self.phase = Phase::Velocity(Coast::new(self.commanded, velocity, ceiling));
                Ok(())
            }
            other => {
                self.phase = other;
                Err(EngineError::NotRunning)
            }
        }
    }

    /// Brings the slave to rest at `deceleration` pulses/s² without
    /// reversing: from a cam-out's velocity motion, or from a running cam
    /// (which it leaves at its velocity first, as
    /// [`CamAxis::cam_out_at_velocity`]). The tick it comes to rest reports
    /// `events.stopped` and the axis is idle.
    ///
    /// # Errors
    /// [`EngineError::NotRunning`] unless the cam is engaged or the slave
    /// moves at velocity.
    pub fn stop_decelerating(&mut self, deceleration: NonZeroU64) -> Result<(), EngineError> {
        if self.state().is_engaged() {
            self.cam_out_at_velocity()?;
        }
        match &mut self.phase {
            Phase::Velocity(coast) => {
                coast.decelerate(deceleration);
                Ok(())
            }
            _ => Err(EngineError::NotRunning),
        }
    }

    /// The slave's velocity (pulses/s) while it moves on after a cam-out.
    pub fn coast_velocity(&self) -> Option<f64> {
        match &self.phase {
            Phase::Velocity(coast) => Some(coast.velocity()),
            _ => None,
        }
    }
}
