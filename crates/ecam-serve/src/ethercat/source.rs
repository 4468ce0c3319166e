//! The cycle driver's published image as this crate's bus snapshot (what
//! the Modbus bus areas and `GET /api/ethercat` show), and the server's bus
//! commands as the driver's.

use std::sync::Arc;

use ecam_ethercat::cia402::error_code_text;
use ecam_ethercat::monitor::{LineCommand, LineMonitor};
use ecam_ethercat::supervisor::{LineState, al_state_code};

use crate::{BusCommand, BusLineState, BusSnapshot, BusSource, DriveView};

/// The driver's published image as ecam-serve's snapshot, and its
/// commands as the driver's.
pub(super) struct Source {
    pub(super) monitor: Arc<LineMonitor>,
    pub(super) transport: String,
    pub(super) cycle_us: u32,
    pub(super) max_lost: u32,
    pub(super) names: Vec<String>,
    pub(super) outputs: Vec<Option<u8>>,
}

impl BusSource for Source {
    fn snapshot(&self) -> BusSnapshot {
        let s = self.monitor.snapshot();
        let c = s.counters;
        let drives = s
            .drives
            .iter()
            .enumerate()
            .map(|(position, d)| DriveView {
                position,
                name: self.names.get(position).cloned().unwrap_or_default(),
                state_code: d.state.code(),
                state: d.state.to_string(),
                statusword: d.statusword,
                error_code: d.error_code,
                error: error_code_text(d.error_code).to_string(),
                reachable: d.reachable,
                enabled: d.enabled,
                fault: s
                    .faults
                    .iter()
                    .find(|f| f.drive == Some(position))
                    .map(|f| f.cause.to_string()),
                actual: d.actual,
                target: self
                    .outputs
                    .get(position)
                    .copied()
                    .flatten()
                    .map(|_| d.target),
                following_error: d.following_error,
                output: self.outputs.get(position).copied().flatten(),
                al_state_code: al_state_code(d.al_state),
                al_state: d.al_state.name().to_string(),
                missed_cycles: d.missed,
            })
            .collect();
        BusSnapshot {
            transport: self.transport.clone(),
            cycle_us: self.cycle_us,
            state: match s.state {
                None | Some(LineState::Stopped) => BusLineState::Stopped,
                Some(LineState::Enabling) => BusLineState::Enabling,
                Some(LineState::Running) => BusLineState::Running,
                Some(LineState::Faulted) => BusLineState::Faulted,
                Some(LineState::Stopping) => BusLineState::Stopping,
                Some(LineState::Recovering) => BusLineState::Recovering,
            },
            faults: s.faults.iter().map(ToString::to_string).collect(),
            cycles: c.cycles,
            working_counter_errors: c.working_counter_errors,
            lateness_max_us: c.lateness_max_ns as f64 / 1000.0,
            lateness_mean_us: c.lateness_mean_ns as f64 / 1000.0,
            overruns: c.overruns,
            lost_cycles: c.lost_cycles,
            lost_in_a_row_max: c.lost_in_a_row_max,
            max_lost_cycles: self.max_lost,
            late_replies: c.late_replies,
            sync0_lead_us: c.sync0_lead_ns as f64 / 1000.0,
            drives,
        }
    }

    fn command(&self, command: BusCommand) -> bool {
        self.monitor.command(match command {
            BusCommand::Enable => LineCommand::Enable,
            BusCommand::Disable => LineCommand::Disable,
            BusCommand::Reset => LineCommand::Reset,
            BusCommand::EmulateFault { drive, code } => LineCommand::InjectFault { drive, code },
        })
    }
}
