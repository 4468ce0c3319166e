//! The CiA 402 drive state machine (IEC 61800-7-201 profile): states read
//! from the statusword (object 0x6041), commands written as the
//! controlword (object 0x6040).
//!
//! Both sides live here: [`DriveState::from_statusword`] and
//! [`Sequencer`] are what a master needs; [`DriveState::after`] and
//! [`DriveState::statusword`] are the drive's side, which the emulated
//! drive uses, so master and emulation agree on one table.

/// Mode of operation (object 0x6060) for cyclic synchronous position.
pub const MODE_CSP: i8 = 8;

/// Controlword bit 0: switch on.
const CW_SWITCH_ON: u16 = 1 << 0;
/// Controlword bit 1: enable voltage.
const CW_ENABLE_VOLTAGE: u16 = 1 << 1;
/// Controlword bit 2: quick stop (active low: 0 requests the quick stop).
const CW_QUICK_STOP: u16 = 1 << 2;
/// Controlword bit 3: enable operation.
const CW_ENABLE_OPERATION: u16 = 1 << 3;
/// Controlword bit 7: fault reset (acts on the rising edge).
pub const CW_FAULT_RESET: u16 = 1 << 7;

/// Statusword bit 4: voltage enabled (power stage supplied).
pub const SW_VOLTAGE_ENABLED: u16 = 1 << 4;
/// Statusword bit 7: warning.
pub const SW_WARNING: u16 = 1 << 7;
/// Statusword bit 9: remote (the controlword is obeyed).
pub const SW_REMOTE: u16 = 1 << 9;
/// Statusword bit 12 in CSP: the drive follows the target position.
pub const SW_CSP_FOLLOWING: u16 = 1 << 12;
/// Statusword bit 13 in CSP: following error (window exceeded).
pub const SW_CSP_FOLLOWING_ERROR: u16 = 1 << 13;

/// The states of the CiA 402 power drive system.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DriveState {
    /// Initialising; the controlword is not obeyed yet.
    #[default]
    NotReadyToSwitchOn,
    /// Initialised, power stage off, waiting for "shutdown".
    SwitchOnDisabled,
    /// Ready; "switch on" powers the stage.
    ReadyToSwitchOn,
    /// Power stage on, no torque; "enable operation" starts following.
    SwitchedOn,
    /// Following the commanded position.
    OperationEnabled,
    /// Braking along the quick-stop ramp.
    QuickStopActive,
    /// A fault was detected; the drive runs its fault reaction.
    FaultReactionActive,
    /// Stopped on a fault; a fault reset (rising edge of bit 7) leaves it.
    Fault,
}

impl DriveState {
    /// The state's code in registers and status images: its place in
    /// [`DriveState::ALL`] (0 not ready to switch on … 7 fault).
    pub const fn code(self) -> u16 {
        match self {
            Self::NotReadyToSwitchOn => 0,
            Self::SwitchOnDisabled => 1,
            Self::ReadyToSwitchOn => 2,
            Self::SwitchedOn => 3,
            Self::OperationEnabled => 4,
            Self::QuickStopActive => 5,
            Self::FaultReactionActive => 6,
            Self::Fault => 7,
        }
    }

    /// Every state, for tables and tests.
    pub const ALL: [Self; 8] = [
        Self::NotReadyToSwitchOn,
        Self::SwitchOnDisabled,
        Self::ReadyToSwitchOn,
        Self::SwitchedOn,
        Self::OperationEnabled,
        Self::QuickStopActive,
        Self::FaultReactionActive,
        Self::Fault,
    ];

    /// Decodes the state from a statusword (bits 0–3, 5, 6; the other
    /// bits do not take part). Patterns outside the profile's table read as
    /// [`DriveState::NotReadyToSwitchOn`], the state that obeys nothing.
    pub const fn from_statusword(statusword: u16) -> Self {
        // Bit 5 (quick stop) only matters in the powered states, so two
        // masks as in the profile's table.
        match statusword & 0x004F {
            0x0000 => return Self::NotReadyToSwitchOn,
            0x0040 => return Self::SwitchOnDisabled,
            0x000F => return Self::FaultReactionActive,
            0x0008 => return Self::Fault,
            _ => {}
        }
        match statusword & 0x006F {
            0x0021 => Self::ReadyToSwitchOn,
            0x0023 => Self::SwitchedOn,
            0x0027 => Self::OperationEnabled,
            0x0007 => Self::QuickStopActive,
            _ => Self::NotReadyToSwitchOn,
        }
    }

    /// The state bits of the statusword a drive in this state reports
    /// (bits 0–3, 5, 6; callers add voltage, remote and mode bits).
    pub const fn statusword(self) -> u16 {
        match self {
            Self::NotReadyToSwitchOn => 0x0000,
            Self::SwitchOnDisabled => 0x0040,
            Self::ReadyToSwitchOn => 0x0021,
            Self::SwitchedOn => 0x0023,
            Self::OperationEnabled => 0x0027,
            Self::QuickStopActive => 0x0007,
            Self::FaultReactionActive => 0x000F,
            Self::Fault => 0x0008,
        }
    }

    /// The drive side: the state after a controlword, given the previous
    /// controlword (fault reset acts on the rising edge of bit 7).
    /// Transitions the drive makes by itself (0, 1, 13, 14) are not here:
    /// the drive model makes them.
    pub fn after(self, controlword: u16, previous_controlword: u16) -> Self {
        let reset_edge =
            controlword & CW_FAULT_RESET != 0 && previous_controlword & CW_FAULT_RESET == 0;
        if self == Self::Fault {
            // Transition 15.
            return if reset_edge {
                Self::SwitchOnDisabled
            } else {
                Self::Fault
            };
        }
        match (self, Command::decode(controlword)) {
            (Self::NotReadyToSwitchOn | Self::FaultReactionActive | Self::Fault, _) => self,
            // Transition 2.
            (Self::SwitchOnDisabled, Command::Shutdown) => Self::ReadyToSwitchOn,
            (Self::SwitchOnDisabled, _) => self,
            // Transition 3 (a drive may accept "enable operation" as switch
            // on as well; it then goes on with transition 4 next cycle).
            (Self::ReadyToSwitchOn, Command::SwitchOn | Command::EnableOperation) => {
                Self::SwitchedOn
            }
            // Transition 7.
            (Self::ReadyToSwitchOn, Command::DisableVoltage | Command::QuickStop) => {
                Self::SwitchOnDisabled
            }
            (Self::ReadyToSwitchOn, Command::Shutdown | Command::FaultReset) => self,
            // Transition 4.
            (Self::SwitchedOn, Command::EnableOperation) => Self::OperationEnabled,
            // Transition 6.
            (Self::SwitchedOn, Command::Shutdown) => Self::ReadyToSwitchOn,
            // Transition 10.
            (Self::SwitchedOn, Command::DisableVoltage | Command::QuickStop) => {
                Self::SwitchOnDisabled
            }
            (Self::SwitchedOn, Command::SwitchOn | Command::FaultReset) => self,
            // Transition 5.
            (Self::OperationEnabled, Command::SwitchOn) => Self::SwitchedOn,
            // Transition 8.
            (Self::OperationEnabled, Command::Shutdown) => Self::ReadyToSwitchOn,
            // Transition 9.
            (Self::OperationEnabled, Command::DisableVoltage) => Self::SwitchOnDisabled,
            // Transition 11.
            (Self::OperationEnabled, Command::QuickStop) => Self::QuickStopActive,
            (Self::OperationEnabled, Command::EnableOperation | Command::FaultReset) => self,
            // Transition 12.
            (Self::QuickStopActive, Command::DisableVoltage) => Self::SwitchOnDisabled,
            // Transition 16 (quick-stop option codes 5 to 8: hold in
            // quick stop, then allow going back to operation).
            (Self::QuickStopActive, Command::EnableOperation) => Self::OperationEnabled,
            (Self::QuickStopActive, _) => self,
        }
    }

    /// The drive applies the commanded position (CSP).
    pub const fn follows_target(self) -> bool {
        matches!(self, Self::OperationEnabled)
    }
}

impl core::fmt::Display for DriveState {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::NotReadyToSwitchOn => "not ready to switch on",
            Self::SwitchOnDisabled => "switch on disabled",
            Self::ReadyToSwitchOn => "ready to switch on",
            Self::SwitchedOn => "switched on",
            Self::OperationEnabled => "operation enabled",
            Self::QuickStopActive => "quick stop active",
            Self::FaultReactionActive => "fault reaction active",
            Self::Fault => "fault",
        })
    }
}

/// The device control commands of the profile.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Command {
    /// Power stage off, go to "ready to switch on" (transitions 2, 6, 8).
    Shutdown,
    /// Power the stage (transition 3); from "operation enabled" this is
    /// "disable operation" (transition 5): the same bits.
    SwitchOn,
    /// Remove voltage (transitions 7, 9, 10, 12).
    DisableVoltage,
    /// Quick stop (transitions 7, 10, 11).
    QuickStop,
    /// Follow the commanded position (transitions 4, 16).
    EnableOperation,
    /// Fault reset: bit 7 (its rising edge acts, transition 15).
    FaultReset,
}

impl Command {
    /// The controlword for this command.
    pub const fn controlword(self) -> u16 {
        match self {
            Self::Shutdown => CW_ENABLE_VOLTAGE | CW_QUICK_STOP,
            Self::SwitchOn => CW_SWITCH_ON | CW_ENABLE_VOLTAGE | CW_QUICK_STOP,
            Self::DisableVoltage => 0,
            Self::QuickStop => CW_ENABLE_VOLTAGE,
            Self::EnableOperation => {
                CW_SWITCH_ON | CW_ENABLE_VOLTAGE | CW_QUICK_STOP | CW_ENABLE_OPERATION
            }
            Self::FaultReset => CW_FAULT_RESET,
        }
    }

    /// Reads the command in a controlword. The profile's "x" bits are
    /// ignored, so every pattern is some command: bit 7 first, then the
    /// active-low bits (voltage, quick stop), then switch on and enable
    /// operation.
    pub const fn decode(controlword: u16) -> Self {
        if controlword & CW_FAULT_RESET != 0 {
            Self::FaultReset
        } else if controlword & CW_ENABLE_VOLTAGE == 0 {
            Self::DisableVoltage
        } else if controlword & CW_QUICK_STOP == 0 {
            Self::QuickStop
        } else if controlword & CW_SWITCH_ON == 0 {
            Self::Shutdown
        } else if controlword & CW_ENABLE_OPERATION == 0 {
            Self::SwitchOn
        } else {
            Self::EnableOperation
        }
    }
}

/// What the master wants from a drive.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Request {
    /// Power stage off (switch on disabled).
    #[default]
    Disabled,
    /// Operation enabled: follow the commanded position.
    Operate,
    /// Brake on the drive's quick-stop ramp and hold there.
    QuickStop,
    /// Clear a fault (one rising edge of bit 7), then stay disabled.
    ResetFault,
}

/// The master side: one controlword per cycle that walks a drive from its
/// present state towards the requested one, one transition per cycle.
///
/// A fault is never cleared by [`Request::Operate`]: clearing it is an
/// explicit [`Request::ResetFault`], as a motion engineer expects (a
/// machine must not restart by itself after a drive fault). The reset is
/// one rising edge of bit 7, then bit 7 held high until the drive leaves
/// "fault" (some drives take several cycles and look at the level, not
/// only the edge); a fault that comes back needs a new reset.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sequencer {
    last: u16,
    /// The rising edge of this reset has gone out; bit 7 stays high.
    edge_sent: bool,
}

impl Sequencer {
    /// A sequencer whose last controlword was 0.
    pub const fn new() -> Self {
        Self {
            last: 0,
            edge_sent: false,
        }
    }

    /// Starts a new fault reset: bit 7 goes low for a cycle (if it is
    /// high) so the next high is a new edge.
    pub fn restart_fault_reset(&mut self) {
        self.edge_sent = false;
    }

    /// The controlword to send this cycle, given the state the drive
    /// reports and the request.
    pub fn controlword(&mut self, state: DriveState, request: Request) -> u16 {
        if state != DriveState::Fault {
            // Out of the fault (or not in it yet): the next reset is a
            // new edge.
            self.edge_sent = false;
        }
        let controlword = match request {
            Request::Disabled => Command::DisableVoltage.controlword(),
            Request::QuickStop => match state {
                DriveState::OperationEnabled | DriveState::QuickStopActive => {
                    Command::QuickStop.controlword()
                }
                _ => Command::DisableVoltage.controlword(),
            },
            Request::ResetFault => match state {
                DriveState::Fault if self.edge_sent => Command::FaultReset.controlword(),
                // Bit 7 low first so the next cycle makes a rising edge.
                DriveState::Fault if self.last & CW_FAULT_RESET == 0 => {
                    self.edge_sent = true;
                    Command::FaultReset.controlword()
                }
                _ => Command::DisableVoltage.controlword(),
            },
            Request::Operate => match state {
                DriveState::SwitchOnDisabled => Command::Shutdown.controlword(),
                DriveState::ReadyToSwitchOn => Command::SwitchOn.controlword(),
                DriveState::SwitchedOn | DriveState::OperationEnabled => {
                    Command::EnableOperation.controlword()
                }
                // Leave the quick stop through "switch on disabled"
                // rather than jumping back into motion (transition 16).
                DriveState::QuickStopActive
                | DriveState::NotReadyToSwitchOn
                | DriveState::FaultReactionActive
                | DriveState::Fault => Command::DisableVoltage.controlword(),
            },
        };
        self.last = controlword;
        controlword
    }
}

/// A CiA 402 / CiA 301 error code (object 0x603F, emergency messages) in
/// words: the profile's codes ecam knows by name, else the class its
/// first digits give (CiA 301 table 21), else "device specific".
pub fn error_code_text(code: u16) -> &'static str {
    match code {
        0x0000 => "no error",
        0x2310 => "continuous over-current",
        0x2320 => "short circuit or earth leakage",
        0x3210 => "DC link over-voltage",
        0x3220 => "DC link under-voltage",
        0x4210 => "excess temperature of the device",
        0x4310 => "excess temperature of the drive",
        0x5441 | 0x5442 => "safe torque off or enable input open",
        0x7121 => "motor blocked",
        0x7305 => "incremental encoder fault",
        0x7500 => "communication error",
        0x8130 => "life guard or heartbeat error (communication watchdog)",
        0x8611 => "following error",
        0x8612 => "reference limit",
        0xFF00..=0xFFFF => "device specific",
        _ => match code >> 12 {
            0x1 => "generic error",
            0x2 => "current",
            0x3 => "voltage",
            0x4 => "temperature",
            0x5 => "device hardware",
            0x6 => "device software",
            0x7 => "additional modules",
            0x8 => "monitoring (communication or control)",
            0x9 => "external error",
            0xF => "additional functions",
            _ => "unknown error",
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The profile's statusword table, with the "x" bits set to show they
    /// do not matter.
    #[test]
    fn statusword_table() {
        let table: [(u16, u16, DriveState); 8] = [
            (0x0000, 0x4F, DriveState::NotReadyToSwitchOn),
            (0x0040, 0x4F, DriveState::SwitchOnDisabled),
            (0x0021, 0x6F, DriveState::ReadyToSwitchOn),
            (0x0023, 0x6F, DriveState::SwitchedOn),
            (0x0027, 0x6F, DriveState::OperationEnabled),
            (0x0007, 0x6F, DriveState::QuickStopActive),
            (0x000F, 0x4F, DriveState::FaultReactionActive),
            (0x0008, 0x4F, DriveState::Fault),
        ];
        for (value, mask, state) in table {
            // Every combination of the bits outside the mask.
            let free = !mask;
            let mut extra: u16 = 0;
            loop {
                let word = value | extra;
                assert_eq!(DriveState::from_statusword(word), state, "{word:#06x}");
                extra = extra.wrapping_sub(free) & free;
                if extra == 0 {
                    break;
                }
            }
            assert_eq!(DriveState::from_statusword(state.statusword()), state);
        }
        // Undefined patterns obey nothing.
        assert_eq!(
            DriveState::from_statusword(0x0001),
            DriveState::NotReadyToSwitchOn
        );
    }

    #[test]
    fn every_statusword_decodes_to_the_state_that_reports_it() {
        for word in 0..=u16::MAX {
            let state = DriveState::from_statusword(word);
            let mask = match state {
                DriveState::NotReadyToSwitchOn
                | DriveState::SwitchOnDisabled
                | DriveState::FaultReactionActive
                | DriveState::Fault => 0x4F,
                _ => 0x6F,
            };
            if word & mask == state.statusword() {
                continue;
            }
            // Only undefined patterns may fall back.
            assert_eq!(state, DriveState::NotReadyToSwitchOn, "{word:#06x}");
        }
    }

    #[test]
    fn controlword_patterns() {
        assert_eq!(Command::Shutdown.controlword(), 0x0006);
        assert_eq!(Command::SwitchOn.controlword(), 0x0007);
        assert_eq!(Command::DisableVoltage.controlword(), 0x0000);
        assert_eq!(Command::QuickStop.controlword(), 0x0002);
        assert_eq!(Command::EnableOperation.controlword(), 0x000F);
        assert_eq!(Command::FaultReset.controlword(), 0x0080);
        for command in [
            Command::Shutdown,
            Command::SwitchOn,
            Command::DisableVoltage,
            Command::QuickStop,
            Command::EnableOperation,
            Command::FaultReset,
        ] {
            assert_eq!(Command::decode(command.controlword()), command);
        }
        // The profile's "x" bits: quick stop ignores bits 0 and 3, disable
        // voltage ignores bits 0, 2, 3.
        assert_eq!(Command::decode(0x000B), Command::QuickStop);
        assert_eq!(Command::decode(0x000D), Command::DisableVoltage);
        assert_eq!(Command::decode(0x000E), Command::Shutdown);
    }

    /// The transition table, state by command (drive side).
    #[test]
    fn transition_table() {
        use Command::*;
        use DriveState::*;
        let expected: [(DriveState, [DriveState; 6]); 8] = [
            //             Shutdown,  SwitchOn,   DisableV,  QuickStop, EnableOp,  FaultReset
            (NotReadyToSwitchOn, [NotReadyToSwitchOn; 6]),
            (
                SwitchOnDisabled,
                [
                    ReadyToSwitchOn,
                    SwitchOnDisabled,
                    SwitchOnDisabled,
                    SwitchOnDisabled,
                    SwitchOnDisabled,
                    SwitchOnDisabled,
                ],
            ),
            (
                ReadyToSwitchOn,
                [
                    ReadyToSwitchOn,
                    SwitchedOn,
                    SwitchOnDisabled,
                    SwitchOnDisabled,
                    SwitchedOn,
                    ReadyToSwitchOn,
                ],
            ),
            (
                SwitchedOn,
                [
                    ReadyToSwitchOn,
                    SwitchedOn,
                    SwitchOnDisabled,
                    SwitchOnDisabled,
                    OperationEnabled,
                    SwitchedOn,
                ],
            ),
            (
                OperationEnabled,
                [
                    ReadyToSwitchOn,
                    SwitchedOn,
                    SwitchOnDisabled,
                    QuickStopActive,
                    OperationEnabled,
                    OperationEnabled,
                ],
            ),
            (
                QuickStopActive,
                [
                    QuickStopActive,
                    QuickStopActive,
                    SwitchOnDisabled,
                    QuickStopActive,
                    OperationEnabled,
                    QuickStopActive,
                ],
            ),
            (FaultReactionActive, [FaultReactionActive; 6]),
            // From fault only the reset edge leads out (previous word 0).
            (Fault, [Fault, Fault, Fault, Fault, Fault, SwitchOnDisabled]),
        ];
        let commands = [
            Shutdown,
            SwitchOn,
            DisableVoltage,
            QuickStop,
            EnableOperation,
            FaultReset,
        ];
        for (from, row) in expected {
            for (command, to) in commands.iter().zip(row) {
                assert_eq!(
                    from.after(command.controlword(), 0),
                    to,
                    "{from} + {command:?}"
                );
            }
        }
        // Holding bit 7 high is no new edge.
        assert_eq!(Fault.after(0x0080, 0x0080), Fault);
    }

    /// Walk the sequencer against the drive side from every state.
    #[test]
    fn sequencer_reaches_operation_enabled_from_reset_states() {
        for start in [
            DriveState::SwitchOnDisabled,
            DriveState::ReadyToSwitchOn,
            DriveState::SwitchedOn,
            DriveState::QuickStopActive,
        ] {
            let mut sequencer = Sequencer::new();
            let mut state = start;
            let mut previous = 0;
            let mut cycles = 0;
            while state != DriveState::OperationEnabled {
                let word = sequencer.controlword(state, Request::Operate);
                state = state.after(word, previous);
                previous = word;
                cycles += 1;
                assert!(cycles <= 4, "from {start}: stuck in {state}");
            }
        }
    }

    #[test]
    fn operate_never_clears_a_fault_but_reset_does() {
        let mut sequencer = Sequencer::new();
        let mut state = DriveState::Fault;
        let mut previous = 0;
        for _ in 0..10 {
            let word = sequencer.controlword(state, Request::Operate);
            state = state.after(word, previous);
            previous = word;
        }
        assert_eq!(state, DriveState::Fault);
        let word = sequencer.controlword(state, Request::ResetFault);
        assert_eq!(word, 0x0080);
        state = state.after(word, previous);
        assert_eq!(state, DriveState::SwitchOnDisabled);
    }

    /// Fault 7 of issue 24: the reset bit was high for one cycle and
    /// repeated every second cycle; it is one edge, then held.
    #[test]
    fn fault_reset_is_one_edge_held_until_the_drive_answers() {
        let mut sequencer = Sequencer::new();
        // Quick stop was the last command (bit 7 low): the edge comes at once.
        let words: Vec<u16> = (0..6)
            .map(|_| sequencer.controlword(DriveState::Fault, Request::ResetFault))
            .collect();
        assert_eq!(words, vec![0x80; 6], "held, never dropped");
        // The drive answers: bit 7 goes low.
        assert_eq!(
            sequencer.controlword(DriveState::SwitchOnDisabled, Request::ResetFault),
            0
        );
        // A fault that comes back gets a new edge.
        assert_eq!(
            sequencer.controlword(DriveState::Fault, Request::ResetFault),
            0x80
        );
        // A second reset while the bit is held: low one cycle, then a new edge.
        sequencer.restart_fault_reset();
        assert_eq!(
            sequencer.controlword(DriveState::Fault, Request::ResetFault),
            0
        );
        assert_eq!(
            sequencer.controlword(DriveState::Fault, Request::ResetFault),
            0x80
        );
        // During the fault reaction the bit stays low.
        let mut fresh = Sequencer::new();
        assert_eq!(
            fresh.controlword(DriveState::FaultReactionActive, Request::ResetFault),
            0
        );
    }

    #[test]
    fn error_codes_in_words() {
        assert_eq!(error_code_text(0x8611), "following error");
        assert_eq!(error_code_text(0x2310), "continuous over-current");
        assert_eq!(error_code_text(0x3330), "voltage");
        assert_eq!(error_code_text(0xFF12), "device specific");
        assert_eq!(error_code_text(0), "no error");
    }

    #[test]
    fn quick_stop_and_disable() {
        let mut sequencer = Sequencer::new();
        let state = DriveState::OperationEnabled;
        let word = sequencer.controlword(state, Request::QuickStop);
        assert_eq!(state.after(word, 0x0F), DriveState::QuickStopActive);
        let word = sequencer.controlword(DriveState::QuickStopActive, Request::Disabled);
        assert_eq!(
            DriveState::QuickStopActive.after(word, 0x02),
            DriveState::SwitchOnDisabled
        );
    }
}
