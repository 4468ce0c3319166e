//! The state of a line of drives, kept apart from what commands them:
//! enabling, running, stopping, the fault reaction, the fault reset and
//! the recovery of drives that left OP. Cams on drives
//! ([`crate::line::CamLine`]) and drives following a PLC's pulse outputs
//! ([`crate::follow::FollowLine`]) share it, so both react alike.
//!
//! Work per cycle is bounded: one pass over the drives after the
//! exchange, and at most one acyclic register step (one frame) per cycle
//! while a fault is diagnosed or a reset recovers drives. Nothing here
//! allocates after construction.

use std::time::Duration;

use crate::cia402::{DriveState, Request, error_code_text};
use crate::coe::Emergency;
use crate::segment::{AcyclicAnswer, AcyclicStep, AlState, CycleReport, Segment, al_status_text};

/// Where the line is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineState {
    /// Drives disabled, cams idle.
    Stopped,
    /// Drives being enabled; the cams arm once all are enabled.
    Enabling,
    /// Cams running.
    Running,
    /// A stop was asked: the motion decelerates to rest, then the drives
    /// are disabled.
    Stopping,
    /// A fault stopped the line; a reset clears it.
    Faulted,
    /// A reset is under way: drives that left OP are brought back, faults
    /// are reset; the line is stopped when all answer.
    Recovering,
}

impl LineState {
    /// The state's name in status lines and JSON.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Stopped => "stopped",
            Self::Enabling => "enabling",
            Self::Running => "running",
            Self::Stopping => "stopping",
            Self::Faulted => "faulted",
            Self::Recovering => "recovering",
        }
    }

    /// The state's code in registers (0 stopped, 1 enabling, 2 running,
    /// 3 faulted, 4 stopping, 5 recovering).
    pub const fn code(self) -> u16 {
        match self {
            Self::Stopped => 0,
            Self::Enabling => 1,
            Self::Running => 2,
            Self::Faulted => 3,
            Self::Stopping => 4,
            Self::Recovering => 5,
        }
    }
}

/// Why the line stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaultCause {
    /// The drive reports a CiA 402 fault with this error code (0x603F).
    Drive {
        /// The error code.
        code: u16,
    },
    /// No answer for more cycles in a row than the line allows.
    Lost {
        /// Cycles without an answer.
        cycles: u32,
    },
    /// The drive answers from an EtherCAT state other than OP (it ignores
    /// its outputs); `code` is its AL status code once read.
    LeftOp {
        /// The state it answered from.
        state: AlState,
        /// AL status code (register 0x0134), once the master read it.
        code: Option<u16>,
    },
    /// Asked to enable, the drive did not reach "operation enabled" in
    /// time.
    EnableTimeout,
    /// A reset did not bring the drive back to OP and out of its fault in
    /// time.
    RecoveryFailed,
}

impl core::fmt::Display for FaultCause {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Self::Drive { code } => write!(
                f,
                "drive fault, error code {code:#06x} ({})",
                error_code_text(code)
            ),
            Self::Lost { cycles } => write!(
                f,
                "drive not reachable: no answer for {cycles} cycles in a row"
            ),
            Self::LeftOp { state, code: None } => write!(
                f,
                "drive left OP (now {}); reading its AL status code",
                state.name()
            ),
            Self::LeftOp {
                state,
                code: Some(code),
            } => write!(
                f,
                "drive left OP (now {}), AL status code {code:#06x}: {}",
                state.name(),
                al_status_text(code)
            ),
            Self::EnableTimeout => f.write_str("drive did not enable in time"),
            Self::RecoveryFailed => {
                f.write_str("reset did not bring the drive back to OP and out of its fault in time")
            }
        }
    }
}

/// A fault that stopped the line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LineFault {
    /// Drive position in the line; `None` when the working counter was
    /// short but every drive answered in OP (a device the line does not
    /// know is gone).
    pub drive: Option<usize>,
    /// What happened.
    pub cause: FaultCause,
    /// The emergency the drive sent about it, once the master read it
    /// from the drive's mailbox.
    pub emergency: Option<Emergency>,
}

impl LineFault {
    /// A fault without an emergency (yet).
    pub const fn new(drive: Option<usize>, cause: FaultCause) -> Self {
        Self {
            drive,
            cause,
            emergency: None,
        }
    }
}

impl core::fmt::Display for LineFault {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self.drive {
            Some(drive) => write!(f, "drive {drive}: {}", self.cause)?,
            None => f.write_str("working counter short: a device on the segment did not answer")?,
        }
        if let Some(emergency) = &self.emergency {
            write!(f, "; {emergency}")?;
        }
        Ok(())
    }
}

/// What the supervisor saw after an exchange.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Supervision {
    /// Faults first seen this cycle ([`Supervisor::new_faults`]); the line
    /// is faulted and its drives brake on their quick-stop ramps.
    pub new_faults: usize,
    /// Every drive of the line reports "operation enabled" for the first
    /// time since the start: the line is running from now on.
    pub now_running: bool,
    /// A reset finished: every drive is back in OP and out of its fault.
    pub recovered: bool,
}

/// Longest a line may take to enable before the drives that have not are
/// reported ([`FaultCause::EnableTimeout`]).
pub const ENABLE_TIMEOUT: Duration = Duration::from_secs(3);
/// Longest a reset may take to bring drives back to OP.
pub const RECOVERY_TIMEOUT: Duration = Duration::from_secs(5);
/// The default lost-cycle limit spans this long: the process-data
/// watchdog an ESC starts with (ETG1000.4: divider 2498, 1000 ticks).
pub const DEFAULT_LOST_SPAN: Duration = Duration::from_millis(100);
/// Times a faulted drive's mailbox is looked at for its emergency (one
/// look per cycle with time to spare) before the master gives up.
const EMERGENCY_LOOKS: u8 = 20;

/// The lost-cycle limit sized to [`DEFAULT_LOST_SPAN`] for a cycle.
pub fn default_max_lost_cycles(cycle: Duration) -> u32 {
    let cycles = DEFAULT_LOST_SPAN.as_nanos() / cycle.as_nanos().max(1);
    u32::try_from(cycles).unwrap_or(u32::MAX).max(1)
}

/// How a drive is being brought back by a reset (or diagnosed after it
/// left OP).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum Recovery {
    /// Nothing to do.
    #[default]
    Idle,
    /// Read its AL status code (after it left OP).
    Diagnose,
    /// Read its emergency (after a fault), the looks so far.
    ReadEmergency(u8),
    /// Acknowledge the error and ask for SAFE-OP.
    AckSafeOp,
    /// Ask for OP.
    RequestOp,
    /// Wait for OP.
    WaitOp,
}

/// The state machine of a line of drives (the drives at `drives`).
#[derive(Clone, Debug)]
pub struct Supervisor {
    drives: Vec<usize>,
    state: LineState,
    faults: Vec<LineFault>,
    new_faults: Vec<LineFault>,
    recovery: Vec<Recovery>,
    /// Cycles spent in the present state (enabling, recovering).
    cycles_in_state: u64,
    enable_limit: u64,
    recovery_limit: u64,
    max_lost: u32,
    /// Round-robin position of the acyclic steps.
    next_step: usize,
    /// An enable asked for during a recovery: enabling follows it.
    start_after_recovery: bool,
    /// Codes and emergencies added to faults already reported.
    annotations: u64,
}

/// The AL state code in registers (0 none, 1 INIT, 2 PRE-OP, 3 BOOT,
/// 4 SAFE-OP, 8 OP).
pub const fn al_state_code(state: AlState) -> u16 {
    match state {
        AlState::Unknown => 0,
        AlState::Init => 1,
        AlState::PreOp => 2,
        AlState::Boot => 3,
        AlState::SafeOp => 4,
        AlState::Op => 8,
    }
}

fn cycles_for(span: Duration, cycle: Duration) -> u64 {
    let n = span.as_nanos() / cycle.as_nanos().max(1);
    u64::try_from(n).unwrap_or(u64::MAX).max(1)
}

impl Supervisor {
    /// A stopped line of the drives at these positions on a segment of
    /// `segment_drives`, cycled every `cycle`; more than `max_lost`
    /// cycles in a row without a drive's answer fault the line.
    pub fn new(drives: Vec<usize>, segment_drives: usize, cycle: Duration, max_lost: u32) -> Self {
        let bound = segment_drives + 2;
        Self {
            drives,
            state: LineState::Stopped,
            faults: Vec::with_capacity(bound),
            new_faults: Vec::with_capacity(bound),
            recovery: vec![Recovery::Idle; segment_drives],
            cycles_in_state: 0,
            enable_limit: cycles_for(ENABLE_TIMEOUT, cycle),
            recovery_limit: cycles_for(RECOVERY_TIMEOUT, cycle),
            max_lost: max_lost.max(1),
            next_step: 0,
            start_after_recovery: false,
            annotations: 0,
        }
    }

    /// How many times an AL status code or an emergency was added to a
    /// fault already reported (a reader whose copy of the faults is older
    /// than this number copies them again).
    pub fn annotations(&self) -> u64 {
        self.annotations
    }

    /// Where the line is.
    pub fn state(&self) -> LineState {
        self.state
    }

    /// The drives the line commands.
    pub fn drives(&self) -> &[usize] {
        &self.drives
    }

    /// The faults that stopped the line (until a reset has recovered it).
    pub fn faults(&self) -> &[LineFault] {
        &self.faults
    }

    /// The faults first seen in the last cycle.
    pub fn new_faults(&self) -> &[LineFault] {
        &self.new_faults
    }

    /// The lost-cycle limit.
    pub fn max_lost_cycles(&self) -> u32 {
        self.max_lost
    }

    fn enter(&mut self, state: LineState) {
        self.state = state;
        self.cycles_in_state = 0;
    }

    /// Asks the line's drives to enable. During a recovery the enable
    /// waits for it to finish (so "reset, then enable" may be sent back to
    /// back).
    ///
    /// # Errors
    /// The state, when the line is neither stopped nor recovering (a
    /// faulted line needs a reset first: it never restarts by itself).
    pub fn start(&mut self, segment: &mut Segment) -> Result<(), LineState> {
        if self.state == LineState::Recovering {
            self.start_after_recovery = true;
            return Ok(());
        }
        if self.state != LineState::Stopped {
            return Err(self.state);
        }
        for &position in &self.drives {
            if let Some(d) = segment.drives_mut().get_mut(position) {
                d.set_request(Request::Operate);
            }
        }
        self.enter(LineState::Enabling);
        Ok(())
    }

    /// A stop was asked: a running line decelerates (the line's motion
    /// ramps down, then [`Supervisor::disable`]); an enabling one is
    /// disabled at once.
    pub fn begin_stop(&mut self, segment: &mut Segment) {
        match self.state {
            LineState::Running => self.enter(LineState::Stopping),
            LineState::Enabling => self.disable(segment),
            _ => {}
        }
    }

    /// Disables every drive on the segment; a faulted line stays faulted.
    pub fn disable(&mut self, segment: &mut Segment) {
        self.start_after_recovery = false;
        for d in segment.drives_mut() {
            d.set_request(Request::Disabled);
        }
        if matches!(
            self.state,
            LineState::Enabling | LineState::Running | LineState::Stopping
        ) {
            self.enter(LineState::Stopped);
        }
    }

    /// Clears the faults: a fault reset to each faulted drive, drives that
    /// left OP are brought back to OP, the others are disabled; the line
    /// is recovering until all answer, then stopped. True when a drive
    /// does not answer at all and the segment must be brought up again
    /// first ([`Segment::reinitialise`]).
    ///
    /// # Errors
    /// The state, when the line is not faulted.
    pub fn reset(&mut self, segment: &mut Segment) -> Result<bool, LineState> {
        if self.state != LineState::Faulted {
            return Err(self.state);
        }
        let mut reinitialise = false;
        for (slot, al) in self.recovery.iter_mut().zip(segment.al_states()) {
            *slot = match al {
                AlState::Op => Recovery::Idle,
                AlState::Unknown => {
                    reinitialise = true;
                    Recovery::Idle
                }
                _ => Recovery::AckSafeOp,
            };
        }
        for d in segment.drives_mut() {
            d.set_request(
                if matches!(
                    d.state(),
                    DriveState::Fault | DriveState::FaultReactionActive
                ) {
                    Request::ResetFault
                } else {
                    Request::Disabled
                },
            );
        }
        self.faults.clear();
        self.start_after_recovery = false;
        self.enter(LineState::Recovering);
        Ok(reinitialise)
    }

    /// After the segment was brought up again: every drive is in OP and
    /// disabled; the recovery goes on with the fault resets.
    pub fn reinitialised(&mut self) {
        for slot in &mut self.recovery {
            *slot = Recovery::Idle;
        }
    }

    fn fault(&mut self, drive: Option<usize>, cause: FaultCause) {
        let fault = LineFault::new(drive, cause);
        // Bounded: one entry per drive and cause at most.
        if self.new_faults.len() < self.new_faults.capacity() && !self.new_faults.contains(&fault) {
            self.new_faults.push(fault);
        }
    }

    /// Looks at the drives after an exchange: a CiA 402 fault, a drive out
    /// of OP, or a drive that has not answered for more than the limit
    /// stops the line (every drive brakes on its quick-stop ramp); all
    /// drives enabled moves an enabling line to running; all drives back
    /// in OP and out of their faults ends a recovery.
    pub fn after_exchange(&mut self, segment: &mut Segment, bus: &CycleReport) -> Supervision {
        self.new_faults.clear();
        self.cycles_in_state = self.cycles_in_state.saturating_add(1);
        let mut seen = Supervision::default();
        match self.state {
            LineState::Stopped | LineState::Faulted => return seen,
            LineState::Recovering => {
                seen.recovered = self.check_recovery(segment);
                return seen;
            }
            LineState::Enabling | LineState::Running | LineState::Stopping => {}
        }
        let enabling = self.state == LineState::Enabling;
        let late = enabling && self.cycles_in_state > self.enable_limit;
        for position in 0..segment.len() {
            let al = segment
                .al_states()
                .get(position)
                .copied()
                .unwrap_or_default();
            let ours = self.drives.contains(&position);
            let Some(d) = segment.drives().get(position) else {
                continue;
            };
            if d.missed_cycles() > self.max_lost {
                self.fault(
                    Some(position),
                    FaultCause::Lost {
                        cycles: d.missed_cycles(),
                    },
                );
            } else if !bus.frame_lost && !matches!(al, AlState::Op | AlState::Unknown) {
                self.fault(
                    Some(position),
                    FaultCause::LeftOp {
                        state: al,
                        code: None,
                    },
                );
                if let Some(slot) = self.recovery.get_mut(position) {
                    *slot = Recovery::Diagnose;
                }
            } else if ours && d.reachable() {
                match d.state() {
                    DriveState::Fault | DriveState::FaultReactionActive => {
                        self.fault(
                            Some(position),
                            FaultCause::Drive {
                                code: d.inputs().error_code,
                            },
                        );
                        if let Some(slot @ Recovery::Idle) = self.recovery.get_mut(position) {
                            *slot = Recovery::ReadEmergency(0);
                        }
                    }
                    state if late && state != DriveState::OperationEnabled => {
                        self.fault(Some(position), FaultCause::EnableTimeout);
                    }
                    _ => {}
                }
            }
        }
        if !self.new_faults.is_empty() {
            for d in segment.drives_mut() {
                d.set_request(Request::QuickStop);
            }
            for &fault in &self.new_faults {
                if self.faults.len() < self.faults.capacity() {
                    self.faults.push(fault);
                }
            }
            self.enter(LineState::Faulted);
            seen.new_faults = self.new_faults.len();
        } else if enabling && self.all_enabled(segment) {
            self.enter(LineState::Running);
            seen.now_running = true;
        }
        seen
    }

    fn check_recovery(&mut self, segment: &mut Segment) -> bool {
        let mut done = true;
        for position in 0..segment.len() {
            let al = segment
                .al_states()
                .get(position)
                .copied()
                .unwrap_or_default();
            let Some(d) = segment.drives_mut().get_mut(position) else {
                continue;
            };
            let faulted = matches!(
                d.state(),
                DriveState::Fault | DriveState::FaultReactionActive
            );
            if faulted && d.request() != Request::ResetFault && al == AlState::Op {
                // It faulted again (or its fault shows only now that it
                // is back in OP).
                d.set_request(Request::ResetFault);
            }
            if al != AlState::Op || faulted || !d.reachable() {
                done = false;
            } else if d.request() == Request::ResetFault {
                d.set_request(Request::Disabled);
            }
        }
        if done {
            self.enter(LineState::Stopped);
            if std::mem::take(&mut self.start_after_recovery) {
                let _ = self.start(segment);
            }
            return true;
        }
        if self.cycles_in_state > self.recovery_limit {
            for position in 0..segment.len() {
                let al = segment
                    .al_states()
                    .get(position)
                    .copied()
                    .unwrap_or_default();
                let d = &segment.drives()[position];
                let faulted = matches!(
                    d.state(),
                    DriveState::Fault | DriveState::FaultReactionActive
                );
                if al != AlState::Op || faulted || !d.reachable() {
                    self.fault(Some(position), FaultCause::RecoveryFailed);
                }
            }
            for &fault in &self.new_faults {
                if self.faults.len() < self.faults.capacity() {
                    self.faults.push(fault);
                }
            }
            self.enter(LineState::Faulted);
        }
        false
    }

    /// Whether an acyclic step is waiting (a drive to diagnose or bring
    /// back to OP).
    pub fn has_acyclic_work(&self) -> bool {
        self.recovery.iter().any(|r| *r != Recovery::Idle)
    }

    /// Runs at most one acyclic step (one drive, one register) within
    /// `budget`: reading the AL status code of a drive that left OP, or
    /// the next step of bringing it back after a reset.
    pub fn acyclic_step(&mut self, segment: &mut Segment, budget: Duration) {
        let n = self.recovery.len();
        let Some(position) = (0..n)
            .map(|k| (self.next_step + k) % n)
            .find(|&p| self.recovery[p] != Recovery::Idle)
        else {
            return;
        };
        self.next_step = (position + 1) % n.max(1);
        let al = segment
            .al_states()
            .get(position)
            .copied()
            .unwrap_or_default();
        let phase = self.recovery[position];
        let step = match phase {
            Recovery::Idle => return,
            Recovery::Diagnose => AcyclicStep::ReadAlStatus,
            Recovery::ReadEmergency(_) => AcyclicStep::ReadMailbox,
            Recovery::AckSafeOp => AcyclicStep::RequestState(4),
            Recovery::RequestOp => AcyclicStep::RequestState(8),
            Recovery::WaitOp => {
                if al == AlState::Op {
                    self.recovery[position] = Recovery::Idle;
                } else if al == AlState::SafeOp && self.cycles_in_state.is_multiple_of(50) {
                    // Ask again now and then: a drive may refuse OP while
                    // its outputs are not yet valid.
                    self.recovery[position] = Recovery::RequestOp;
                }
                return;
            }
        };
        let Some(answer) = segment.acyclic_step(position, step, budget) else {
            return;
        };
        self.recovery[position] = match (phase, answer) {
            (Recovery::Diagnose, AcyclicAnswer::AlStatus { code, .. }) => {
                for fault in self.faults.iter_mut().filter(|f| f.drive == Some(position)) {
                    if let FaultCause::LeftOp { code: slot, .. } = &mut fault.cause {
                        *slot = Some(code);
                    }
                }
                self.annotations += 1;
                // A drive that left OP on a watchdog often faulted too.
                Recovery::ReadEmergency(0)
            }
            (Recovery::ReadEmergency(_), AcyclicAnswer::Emergency(e)) if e.code != 0 => {
                for fault in self
                    .faults
                    .iter_mut()
                    .filter(|f| f.drive == Some(position) && f.emergency.is_none())
                {
                    fault.emergency = Some(e);
                }
                self.annotations += 1;
                Recovery::Idle
            }
            (Recovery::ReadEmergency(looks), _) if looks + 1 < EMERGENCY_LOOKS => {
                Recovery::ReadEmergency(looks + 1)
            }
            (Recovery::ReadEmergency(_), _) => Recovery::Idle,
            (Recovery::AckSafeOp, _) => Recovery::RequestOp,
            (Recovery::RequestOp, _) => Recovery::WaitOp,
            (other, _) => other,
        };
    }

    fn all_enabled(&self, segment: &Segment) -> bool {
        self.drives.iter().all(|&position| {
            segment
                .drives()
                .get(position)
                .is_some_and(|d| d.state() == DriveState::OperationEnabled && d.reachable())
        })
    }
}

/// Checks that every drive position exists on a segment of `drives`.
///
/// # Errors
/// The first position that does not.
pub fn check_positions(
    positions: impl IntoIterator<Item = usize>,
    drives: usize,
) -> Result<(), usize> {
    positions
        .into_iter()
        .find(|&p| p >= drives)
        .map_or(Ok(()), Err)
}
