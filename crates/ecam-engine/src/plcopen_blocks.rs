//! PLCopen function-block behaviour over [`crate::plcopen::McCamAxis`]:
//! `Execute` acts on its rising edge, and the outputs latch as PLCopen
//! Part 1 says (`Done`, `Error`/`ErrorID`, `CommandAborted` hold until the
//! next rising edge of `Execute`).
//!
//! Call each block once per cycle after [`crate::plcopen::McCamAxis::tick`],
//! with that cycle's status.

use ecam_core::CamCurve;

use crate::EngineError;
use crate::plcopen::{CamIn, CamStatus, CamTableSelect, ExecutionMode, McCamAxis};

/// `MC_CamTableSelect` outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TableSelectOutputs {
    /// The table was selected (for [`ExecutionMode::Queued`] while a cam
    /// runs: it took over).
    pub done: bool,
    /// A queued selection waits for the running cam's cycle to end.
    pub busy: bool,
    /// The selection was refused; see `error_id`.
    pub error: bool,
    /// Why it was refused.
    pub error_id: Option<EngineError>,
}

/// `MC_CamTableSelect` as a function block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TableSelectBlock {
    execute: bool,
    out: TableSelectOutputs,
}

impl TableSelectBlock {
    /// One call: on a rising edge of `execute` selects `table` (taken from
    /// `table` only then). A queued selection on a running cam is `Busy`
    /// until its table takes over, then `Done`.
    pub fn call<C: CamCurve>(
        &mut self,
        axis: &mut McCamAxis<C>,
        execute: bool,
        table: &mut Option<C>,
        select: CamTableSelect,
    ) -> TableSelectOutputs {
        if execute && !self.execute {
            let queued =
                select.execution_mode == ExecutionMode::Queued && axis.axis().state().is_engaged();
            self.out = match table.take().map(|t| axis.select_table(t, select)) {
                Some(Ok(())) => TableSelectOutputs {
                    done: !queued,
                    busy: queued,
                    ..TableSelectOutputs::default()
                },
                Some(Err(e)) => TableSelectOutputs {
                    done: false,
                    busy: false,
                    error: true,
                    error_id: Some(e),
                },
                None => TableSelectOutputs {
                    done: false,
                    busy: false,
                    error: true,
                    error_id: Some(EngineError::EmptyCycle),
                },
            };
        }
        if self.out.busy && !axis.has_queued_table() {
            self.out.busy = false;
            self.out.done = true;
        }
        self.execute = execute;
        self.out
    }
}

/// `MC_CamIn` outputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CamInOutputs {
    /// The slave follows the cam and no pulses are owed.
    pub in_sync: bool,
    /// A table cycle (or the non-periodic table) ended this cycle.
    pub end_of_profile: bool,
    /// The command is not finished (waiting, ramping or coupled).
    pub busy: bool,
    /// The command has control of the axis.
    pub active: bool,
    /// Another command (a later `MC_CamIn` or `MC_CamOut`) took over.
    pub command_aborted: bool,
    /// The command failed; see `error_id`.
    pub error: bool,
    /// Why, latched until the next rising edge of `Execute`.
    pub error_id: Option<EngineError>,
}

/// `MC_CamIn` as a function block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CamInBlock {
    execute: bool,
    /// The axis command this block issued, while it is in charge.
    command: Option<u64>,
    aborted: bool,
    error: Option<EngineError>,
}

impl CamInBlock {
    /// One call with this cycle's `status`: on a rising edge of `execute`
    /// issues `params` ([`McCamAxis::cam_in`]).
    pub fn call<C: CamCurve>(
        &mut self,
        axis: &mut McCamAxis<C>,
        execute: bool,
        params: &CamIn,
        status: &CamStatus,
    ) -> CamInOutputs {
        if execute && !self.execute {
            self.aborted = false;
            self.error = None;
            match axis.cam_in(params) {
                Ok(()) => self.command = Some(axis.command()),
                Err(e) => {
                    self.command = None;
                    self.error = Some(e);
                }
            }
        }
        self.execute = execute;
        let mut ended = false;
        if let Some(id) = self.command {
            if axis.command() != id {
                self.aborted = true;
                self.command = None;
            } else if let Some(e) = status.error {
                self.error = Some(e);
                self.command = None;
            } else {
                // Ran to its end (a one-shot): reported this cycle, then
                // no longer in charge.
                ended = !axis.axis().state().is_active() && !status.busy;
            }
        }
        let mine = self.command.is_some();
        if ended {
            self.command = None;
        }
        CamInOutputs {
            in_sync: mine && status.in_sync,
            end_of_profile: mine && status.end_of_profile,
            busy: mine,
            active: mine && status.active,
            command_aborted: self.aborted,
            error: self.error.is_some(),
            error_id: self.error,
        }
    }
}
