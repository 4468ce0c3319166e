//! A CiA 402 servo drive in CSP as an [`AxisDrive`]: the commanded
//! position goes out as the target position each cycle; the statusword,
//! position actual value, following error and error code come back.

use ecam_engine::Unwrap32;
use ecam_engine::drive::{AxisDrive, DriveFault, DriveStatus};

use crate::cia402::{DriveState, MODE_CSP, Request, Sequencer};
use crate::pdo::{CspInputs, CspOutputs};

/// One drive on the segment, as the master sees it.
///
/// Positions are the axis' `i64` counts; on the bus they are the drive's
/// 32-bit counts, which wrap (the target is the commanded position modulo
/// 2^32, the actual position is unwrapped), so an axis may run forever in
/// one direction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Cia402Drive {
    sequencer: Sequencer,
    request: Request,
    commanded: Option<i64>,
    inputs: CspInputs,
    actual: Option<Unwrap32>,
    reachable: bool,
    /// Exchanges in a row the drive did not answer.
    missed: u32,
}

impl Cia402Drive {
    /// A drive not yet heard from, asked to stay disabled.
    pub fn new() -> Self {
        Self::default()
    }

    /// What the master wants from the drive (enable, disable, quick stop,
    /// fault reset); it is walked there one state per cycle.
    pub fn set_request(&mut self, request: Request) {
        if request == Request::ResetFault {
            // Every reset asked for is a new rising edge of bit 7.
            self.sequencer.restart_fault_reset();
        }
        self.request = request;
    }

    /// The current request.
    pub fn request(&self) -> Request {
        self.request
    }

    /// The state the drive reported last.
    pub fn state(&self) -> DriveState {
        DriveState::from_statusword(self.inputs.statusword)
    }

    /// The raw inputs received last.
    pub fn inputs(&self) -> CspInputs {
        self.inputs
    }

    /// The drive answered in the last exchange.
    pub fn reachable(&self) -> bool {
        self.reachable
    }

    /// Exchanges in a row the drive has not answered (0: it answered the
    /// last one). Its inputs are the last it sent.
    pub fn missed_cycles(&self) -> u32 {
        self.missed
    }

    /// Actual position, unwrapped (0 before the first answer).
    pub fn actual(&self) -> i64 {
        self.actual.map_or(0, |a| a.position())
    }

    /// This cycle's outputs. Until the drive is in "operation enabled"
    /// the target is its own actual position, so enabling never jumps;
    /// the commanded position is applied from then on.
    pub fn outputs(&mut self) -> CspOutputs {
        let state = self.state();
        let controlword = self.sequencer.controlword(state, self.request);
        let hold = self.inputs.position_actual;
        let target_position = match self.commanded {
            // Truncation to 32 bits is the drive's modulo 2^32 position.
            Some(commanded) if state == DriveState::OperationEnabled => commanded as i32,
            _ => hold,
        };
        CspOutputs {
            controlword,
            target_position,
            mode: MODE_CSP,
        }
    }

    /// Takes the inputs of the last exchange; `None` when the drive did not
    /// answer (frame lost, working counter short, state not readable): its
    /// last inputs are kept and the miss is counted.
    pub fn update(&mut self, inputs: Option<CspInputs>) {
        match inputs {
            Some(inputs) => {
                let raw = inputs.position_actual as u32;
                match &mut self.actual {
                    Some(unwrap) => {
                        unwrap.update(raw);
                    }
                    None => self.actual = Some(Unwrap32::new(raw)),
                }
                self.inputs = inputs;
                self.reachable = true;
                self.missed = 0;
            }
            None => {
                self.reachable = false;
                self.missed = self.missed.saturating_add(1);
            }
        }
    }
}

impl AxisDrive for Cia402Drive {
    fn command(&mut self, commanded: i64, _dt_us: u32) {
        self.commanded = Some(commanded);
    }

    fn status(&self) -> DriveStatus {
        let state = self.state();
        let fault = if !self.reachable {
            Some(DriveFault::Communication)
        } else if matches!(state, DriveState::Fault | DriveState::FaultReactionActive) {
            Some(DriveFault::Drive {
                code: self.inputs.error_code,
            })
        } else {
            None
        };
        DriveStatus {
            actual: self.actual(),
            following_error: i64::from(self.inputs.following_error),
            enabled: self.reachable && state == DriveState::OperationEnabled,
            fault,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emulation::{DriveBehaviour, DriveModel};

    /// Runs the master-side drive against the emulated drive model.
    fn exchange(master: &mut Cia402Drive, drive: &mut DriveModel) {
        let outputs = master.outputs();
        drive.cycle(outputs);
        master.update(Some(drive.inputs()));
    }

    #[test]
    fn enables_without_a_jump_then_follows_the_command() {
        let mut drive = DriveModel::new(
            DriveBehaviour {
                lag_cycles: 0,
                ..DriveBehaviour::default()
            },
            1234,
        );
        let mut master = Cia402Drive::new();
        master.update(Some(drive.inputs()));
        master.set_request(Request::Operate);
        master.command(5000, 1000);
        for _ in 0..5 {
            exchange(&mut master, &mut drive);
            assert_eq!(
                drive.actual(),
                1234,
                "no motion before operation enabled is seen"
            );
            if master.state() == DriveState::OperationEnabled {
                break;
            }
        }
        assert!(master.status().enabled);
        master.command(1300, 1000);
        exchange(&mut master, &mut drive);
        assert_eq!(drive.actual(), 1300);
        assert_eq!(master.status().actual, 1300);
    }

    #[test]
    fn wraps_beyond_32_bits() {
        let mut drive = DriveModel::new(
            DriveBehaviour {
                lag_cycles: 0,
                ..DriveBehaviour::default()
            },
            i32::MAX - 10,
        );
        let mut master = Cia402Drive::new();
        master.update(Some(drive.inputs()));
        master.set_request(Request::Operate);
        let start = i64::from(i32::MAX) - 10;
        master.command(start, 1000);
        for _ in 0..5 {
            exchange(&mut master, &mut drive);
        }
        for k in 1..=40 {
            master.command(start + k, 1000);
            exchange(&mut master, &mut drive);
        }
        assert_eq!(master.status().actual, start + 40);
        assert_eq!(master.status().following_error, 0);
    }

    #[test]
    fn reports_faults_and_lost_communication() {
        let mut master = Cia402Drive::new();
        master.update(None);
        assert_eq!(master.status().fault, Some(DriveFault::Communication));
        master.update(Some(CspInputs {
            statusword: 0x0008,
            error_code: 0x7500,
            ..CspInputs::default()
        }));
        assert_eq!(
            master.status().fault,
            Some(DriveFault::Drive { code: 0x7500 })
        );
        assert!(!master.status().enabled);
    }
}
