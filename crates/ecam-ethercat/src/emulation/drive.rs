//! The emulated servo drive behind the ESC: a CiA 402 state machine in
//! CSP that follows its target position a fixed number of cycles late.

use std::collections::VecDeque;

use crate::cia402::{
    DriveState, MODE_CSP, SW_CSP_FOLLOWING, SW_CSP_FOLLOWING_ERROR, SW_REMOTE, SW_VOLTAGE_ENABLED,
};
use crate::pdo::{CspInputs, CspOutputs};

/// CiA 402 error code the emulated drive reports when its following error
/// leaves the window (the profile's "following error" code).
pub const ERROR_FOLLOWING: u16 = 0x8611;
/// Error code the emulated drive reports when its ESC's process-data
/// watchdog runs out while the power stage is on (CiA 301's "life guard
/// or heartbeat error": our choice for a communication watchdog).
pub const ERROR_WATCHDOG: u16 = 0x8130;

/// How an emulated drive behaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DriveBehaviour {
    /// The motor reaches a target this many cycles after it was sent (a
    /// pure delay, so positions stay exact integers).
    pub lag_cycles: usize,
    /// Largest |target − actual| before the drive faults with
    /// [`ERROR_FOLLOWING`].
    pub following_error_window: u32,
    /// Cycles the fault-reset bit must stay high after its rising edge
    /// before the drive leaves "fault" (0: the edge alone).
    pub reset_hold_cycles: u32,
    /// The drive offers CSP (mode 8). Without it, it takes 0x6060 = 8
    /// but stays in the mode it had: 0x6061 shows the mode it runs.
    pub csp: bool,
    /// The drive's PDO mapping is fixed (0x1600/0x1A00/0x1C12/0x1C13
    /// refuse writes) and its TxPDO carries the CSP inputs in another
    /// order: statusword, error code, position, following error.
    pub fixed_mapping: bool,
}

impl Default for DriveBehaviour {
    fn default() -> Self {
        Self {
            lag_cycles: 2,
            following_error_window: 1_000_000,
            reset_hold_cycles: 0,
            csp: true,
            fixed_mapping: false,
        }
    }
}

/// One emulated drive's application state.
#[derive(Clone, Debug)]
pub struct DriveModel {
    behaviour: DriveBehaviour,
    state: DriveState,
    previous_controlword: u16,
    target: i32,
    actual: i32,
    /// The mode the drive runs (0x6061).
    mode: i8,
    /// The mode last asked for (0x6060).
    requested_mode: i8,
    delay_line: VecDeque<i32>,
    error_code: u16,
    pending_fault: Option<u16>,
    window_exceeded: bool,
    cycles: u64,
    /// Cycles the drive still stays in "switch on disabled".
    switch_on_delay: u32,
    /// Cycles bit 7 has been high since its edge (in "fault").
    reset_held: Option<u32>,
    /// An emergency to send: the error code that appeared (or 0 when a
    /// fault was reset), not yet taken by the ESC.
    emergency: Option<u16>,
}

impl DriveModel {
    /// A drive at rest at `position`, just powered (not ready to switch on).
    pub fn new(behaviour: DriveBehaviour, position: i32) -> Self {
        Self {
            behaviour,
            state: DriveState::NotReadyToSwitchOn,
            previous_controlword: 0,
            target: position,
            actual: position,
            mode: 0,
            requested_mode: 0,
            // Sized once, so running the drive never allocates.
            delay_line: VecDeque::with_capacity(behaviour.lag_cycles + 1),
            error_code: 0,
            pending_fault: None,
            window_exceeded: false,
            cycles: 0,
            switch_on_delay: 0,
            reset_held: None,
            emergency: None,
        }
    }

    /// The behaviour the drive was built with (the following-error
    /// window as last set).
    pub fn behaviour(&self) -> DriveBehaviour {
        self.behaviour
    }

    /// Sets the following-error window (object 0x6065).
    pub fn set_following_error_window(&mut self, window: u32) {
        self.behaviour.following_error_window = window;
    }

    /// Asks for a mode of operation (object 0x6060, or the RxPDO). A
    /// drive without CSP keeps the mode it runs when CSP is asked for.
    pub fn set_mode(&mut self, mode: i8) {
        self.requested_mode = mode;
        if mode != MODE_CSP || self.behaviour.csp {
            self.mode = mode;
        }
    }

    /// The mode asked for (0x6060).
    pub fn requested_mode(&self) -> i8 {
        self.requested_mode
    }

    /// The mode the drive runs (0x6061).
    pub fn mode_display(&self) -> i8 {
        self.mode
    }

    /// The controlword last received (0x6040).
    pub fn controlword(&self) -> u16 {
        self.previous_controlword
    }

    /// The error code that appeared since the last call (0 when a fault
    /// was reset), for an emergency message.
    pub fn take_emergency(&mut self) -> Option<u16> {
        self.emergency.take()
    }

    /// Keeps the drive in "switch on disabled" for `cycles` more cycles
    /// (a slow power stage).
    pub fn delay_switch_on(&mut self, cycles: u32) {
        self.switch_on_delay = cycles;
    }

    /// The ESC's process-data watchdog ran out: a drive with its power
    /// stage on faults with [`ERROR_WATCHDOG`] at once (its own
    /// application reacts; it does not wait for the next frame).
    pub fn communication_lost(&mut self) {
        if matches!(
            self.state,
            DriveState::ReadyToSwitchOn
                | DriveState::SwitchedOn
                | DriveState::OperationEnabled
                | DriveState::QuickStopActive
        ) {
            self.state = DriveState::Fault;
            self.error_code = ERROR_WATCHDOG;
            self.emergency = Some(ERROR_WATCHDOG);
            self.delay_line.clear();
        }
    }

    /// Puts the motor at `position` (a drive powered up where its motor
    /// stands).
    pub fn place(&mut self, position: i32) {
        self.actual = position;
        self.target = position;
    }

    /// Makes the drive fault with `code` at its next cycle.
    pub fn inject_fault(&mut self, code: u16) {
        self.pending_fault = Some(code);
    }

    /// The CiA 402 state.
    pub fn state(&self) -> DriveState {
        self.state
    }

    /// Motor position (drive counts).
    pub fn actual(&self) -> i32 {
        self.actual
    }

    /// Last target position received.
    pub fn target(&self) -> i32 {
        self.target
    }

    /// Process-data cycles this drive has run.
    pub fn cycles(&self) -> u64 {
        self.cycles
    }

    /// One cycle: take the outputs, move, and update the state.
    pub fn cycle(&mut self, outputs: CspOutputs) {
        self.cycles = self.cycles.saturating_add(1);
        let controlword = outputs.controlword;
        let before = self.state;
        self.state = if let Some(code) = self.pending_fault.take() {
            self.error_code = code;
            DriveState::FaultReactionActive
        } else {
            match self.state {
                // Transition 1: initialisation done.
                DriveState::NotReadyToSwitchOn => DriveState::SwitchOnDisabled,
                // Transition 14: the fault reaction (an instant stop here).
                DriveState::FaultReactionActive => DriveState::Fault,
                DriveState::SwitchOnDisabled if self.switch_on_delay > 0 => {
                    self.switch_on_delay -= 1;
                    DriveState::SwitchOnDisabled
                }
                DriveState::Fault => self.fault_reset(controlword),
                state => state.after(controlword, self.previous_controlword),
            }
        };
        if before == DriveState::Fault && self.state != DriveState::Fault {
            self.error_code = 0;
            self.window_exceeded = false;
            self.emergency = Some(0);
        }
        self.previous_controlword = controlword;
        self.set_mode(outputs.mode);
        self.target = outputs.target_position;
        if self.state.follows_target() && self.mode == MODE_CSP {
            self.delay_line.push_back(outputs.target_position);
            while self.delay_line.len() > self.behaviour.lag_cycles {
                if let Some(next) = self.delay_line.pop_front() {
                    self.actual = next;
                }
            }
            let error = self.following_error().unsigned_abs();
            if error > self.behaviour.following_error_window {
                self.window_exceeded = true;
                self.error_code = ERROR_FOLLOWING;
                self.state = DriveState::FaultReactionActive;
            }
        } else {
            // Not following: the motor holds where it is.
            self.delay_line.clear();
        }
        let faulted =
            |s: DriveState| matches!(s, DriveState::FaultReactionActive | DriveState::Fault);
        if faulted(self.state) && !faulted(before) {
            self.emergency = Some(self.error_code);
        }
    }

    /// Transition 15, with the bit held for `reset_hold_cycles` after its
    /// edge.
    fn fault_reset(&mut self, controlword: u16) -> DriveState {
        let high = controlword & crate::cia402::CW_FAULT_RESET != 0;
        let edge = high && self.previous_controlword & crate::cia402::CW_FAULT_RESET == 0;
        self.reset_held = match (self.reset_held, high, edge) {
            (_, _, true) => Some(0),
            (Some(n), true, false) => Some(n + 1),
            _ => None,
        };
        match self.reset_held {
            Some(n) if n >= self.behaviour.reset_hold_cycles => {
                self.reset_held = None;
                DriveState::SwitchOnDisabled
            }
            _ => DriveState::Fault,
        }
    }

    fn following_error(&self) -> i32 {
        if self.state.follows_target() {
            self.target.wrapping_sub(self.actual)
        } else {
            0
        }
    }

    /// What the drive reports (TxPDO).
    pub fn inputs(&self) -> CspInputs {
        let mut statusword = self.state.statusword() | SW_REMOTE;
        if matches!(
            self.state,
            DriveState::ReadyToSwitchOn
                | DriveState::SwitchedOn
                | DriveState::OperationEnabled
                | DriveState::QuickStopActive
        ) {
            statusword |= SW_VOLTAGE_ENABLED;
        }
        if self.state.follows_target() && self.mode == MODE_CSP {
            statusword |= SW_CSP_FOLLOWING;
        }
        if self.window_exceeded {
            statusword |= SW_CSP_FOLLOWING_ERROR;
        }
        CspInputs {
            statusword,
            position_actual: self.actual,
            following_error: self.following_error(),
            error_code: self.error_code,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cia402::{Request, Sequencer};

    fn enable(drive: &mut DriveModel) {
        let mut sequencer = Sequencer::new();
        for _ in 0..6 {
            let state = DriveState::from_statusword(drive.inputs().statusword);
            let controlword = sequencer.controlword(state, Request::Operate);
            drive.cycle(CspOutputs {
                controlword,
                target_position: drive.actual(),
                mode: MODE_CSP,
            });
        }
        assert_eq!(drive.state(), DriveState::OperationEnabled);
    }

    #[test]
    fn follows_with_the_configured_lag() {
        let mut drive = DriveModel::new(
            DriveBehaviour {
                lag_cycles: 3,
                ..DriveBehaviour::default()
            },
            100,
        );
        enable(&mut drive);
        for k in 1..=10 {
            drive.cycle(CspOutputs {
                controlword: 0x0F,
                target_position: 100 + k * 10,
                mode: MODE_CSP,
            });
            let expected = if k > 3 { 100 + (k - 3) * 10 } else { 100 };
            assert_eq!(drive.actual(), expected, "cycle {k}");
            assert_eq!(drive.inputs().following_error, 100 + k * 10 - expected);
        }
        assert_ne!(drive.inputs().statusword & SW_CSP_FOLLOWING, 0);
    }

    #[test]
    fn injected_fault_stops_and_reset_recovers() {
        let mut drive = DriveModel::new(DriveBehaviour::default(), 0);
        enable(&mut drive);
        drive.inject_fault(0x2310);
        drive.cycle(CspOutputs {
            controlword: 0x0F,
            target_position: 50,
            mode: MODE_CSP,
        });
        assert_eq!(drive.state(), DriveState::FaultReactionActive);
        drive.cycle(CspOutputs {
            controlword: 0x0F,
            target_position: 60,
            mode: MODE_CSP,
        });
        assert_eq!(drive.state(), DriveState::Fault);
        assert_eq!(drive.inputs().error_code, 0x2310);
        assert_eq!(drive.actual(), 0, "a faulted drive does not follow");
        drive.cycle(CspOutputs {
            controlword: 0x80,
            target_position: 0,
            mode: MODE_CSP,
        });
        assert_eq!(drive.state(), DriveState::SwitchOnDisabled);
        assert_eq!(drive.inputs().error_code, 0);
    }

    #[test]
    fn following_error_window_faults() {
        let behaviour = DriveBehaviour {
            lag_cycles: 1,
            following_error_window: 5,
            ..DriveBehaviour::default()
        };
        let mut drive = DriveModel::new(behaviour, 0);
        enable(&mut drive);
        drive.cycle(CspOutputs {
            controlword: 0x0F,
            target_position: 6,
            mode: MODE_CSP,
        });
        assert_eq!(drive.state(), DriveState::FaultReactionActive);
        drive.cycle(CspOutputs {
            controlword: 0x0F,
            target_position: 6,
            mode: MODE_CSP,
        });
        let inputs = drive.inputs();
        assert_eq!(
            DriveState::from_statusword(inputs.statusword),
            DriveState::Fault
        );
        assert_eq!(inputs.error_code, ERROR_FOLLOWING);
        assert_ne!(inputs.statusword & SW_CSP_FOLLOWING_ERROR, 0);
    }
}
