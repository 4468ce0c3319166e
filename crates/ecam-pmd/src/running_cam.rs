//! One started cam: the engine axis that turns the input into the commanded position.
//!
//! Document 002's rules map onto the engine like this: the table wraps both
//! ways with the offset adjusted so the output stays continuous (repeat
//! coupling; a table whose first and last values are equal is periodic and
//! behaves the same); `CamStartCount` is the table input at the start
//! (`MasterAlign::StartAt`, so `CamInputOffset = CamStartCount − input`);
//! the start is bumpless (`SlaveAlign::Relative`, so
//! `CamOutputOffset = commanded − table value`). The document's prose says
//! the offset is "the current commanded position subtracted from the table
//! value", but then adds it to the table values to avoid a bump; only
//! commanded − table does that, so that is the sign used.

use ecam_engine::{
    AxisConfig, CamAxis, Coupling, EngineError, MasterAlign, SlaveAlign, StartMode, StopKind,
    TickInput,
};

use crate::BufferCam;

/// Time per processor cycle handed to the engine. The face reads the
/// commanded position (not the emitted pulses), so the pulse limit that
/// this feeds never delays a motion processor's servo reference.
const CYCLE_US: u32 = 100;

/// A cam that was started by `StartCam`.
pub struct RunningCam {
    axis: CamAxis<BufferCam>,
    /// The newest copy of the table: in use, or waiting for the next seam.
    newest: BufferCam,
    fault: Option<EngineError>,
}

/// What one cycle of a running cam produced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CamCycle {
    /// Commanded position.
    pub commanded: i64,
    /// `CamOutputOffset`.
    pub output_offset: i64,
    /// `CamInputOffset`.
    pub input_offset: i64,
    /// The cam is still active after this cycle.
    pub active: bool,
}

impl core::fmt::Debug for RunningCam {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("RunningCam")
            .field("state", &self.axis.status().state)
            .finish()
    }
}

impl RunningCam {
    /// Arms a cam on `table` starting at table input `start_count` from the
    /// commanded position `commanded`; it engages on the next [`RunningCam::tick`].
    ///
    /// # Errors
    /// The engine's refusal (e.g. an empty cycle).
    pub fn start(
        table: BufferCam,
        start_count: i64,
        commanded: i64,
    ) -> Result<Self, ecam_engine::EngineError> {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            start: StartMode::Immediate,
            master_align: MasterAlign::StartAt(start_count),
            slave_align: SlaveAlign::Relative,
            ..AxisConfig::default()
        };
        let newest = table.clone();
        let mut axis = CamAxis::new(table, config)?;
        axis.set_slave_position(commanded)?;
        axis.arm()?;
        Ok(Self {
            axis,
            newest,
            fault: None,
        })
    }

    /// Buffer values written since the newest copy wait for the next seam.
    fn take_buffer_writes(&mut self) {
        let Some(fresh) = self.newest.refreshed() else {
            return;
        };
        if fresh.same_table(&self.newest) {
            // Written, but with the values it had: nothing to switch.
            self.newest = fresh;
            return;
        }
        if self.axis.queue_curve(fresh.clone()).is_ok() {
            self.newest = fresh;
        }
    }

    /// Runs one processor cycle with the cam input `input`.
    pub fn tick(&mut self, input: i64) -> CamCycle {
        self.take_buffer_writes();
        let out = self.axis.tick(&TickInput {
            master: input,
            master_fraction: 0,
            start_input: false,
            watch: 0,
            dt_us: CYCLE_US,
            output_enabled: true,
        });
        if out.fault.is_some() {
            self.fault = out.fault;
        }
        drop(self.axis.take_retired_curve());
        CamCycle {
            commanded: out.slave,
            output_offset: out.output_offset,
            input_offset: out.input_offset,
            active: out.state.is_active(),
        }
    }

    /// The runtime fault that stopped this cam (e.g. an output past the
    /// 64-bit range), if the engine had to stop it.
    pub fn fault(&self) -> Option<EngineError> {
        self.fault
    }

    /// Abrupt stop: the commanded position stays where it is.
    pub fn stop_abrupt(&mut self) {
        self.axis.stop(StopKind::Immediate);
    }

    /// Smooth stop: at the next end of the table, in either direction; at
    /// once when the input is exactly on an end of the table (see
    /// [`RunningCam::active`]).
    pub fn stop_smooth(&mut self) {
        self.axis.stop(StopKind::EndOfCycle);
    }

    /// Whether the cam is still active: false once a stop took effect,
    /// even before the next [`RunningCam::tick`] reports it.
    pub fn active(&self) -> bool {
        self.axis.state().is_active()
    }
}
