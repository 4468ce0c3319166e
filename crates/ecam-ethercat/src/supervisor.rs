//! The state of a line of drives, kept apart from what commands them:
//! enabling, running, the fault reaction and the fault reset. Cams on
//! drives ([`crate::line::CamLine`]) and drives following a PLC's pulse
//! outputs ([`crate::follow::FollowLine`]) share it, so both react to a
//! fault the same way.

use std::time::Duration;

use ecam_engine::drive::{AxisDrive, DriveFault};

use crate::cia402::{DriveState, Request};
use crate::segment::{CycleReport, Segment};

/// Where the line is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineState {
    /// Drives disabled, cams idle.
    Stopped,
    /// Drives being enabled; the cams arm once all are enabled.
    Enabling,
    /// Cams running.
    Running,
    /// A fault stopped the line; a reset clears it.
    Faulted,
}

impl LineState {
    /// The state's name in status lines and JSON.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Stopped => "stopped",
            Self::Enabling => "enabling",
            Self::Running => "running",
            Self::Faulted => "faulted",
        }
    }
}

/// A fault that stopped the line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LineFault {
    /// Drive position in the line; `None` when the working counter was
    /// short but every drive of the line answered (a drive the line does
    /// not use is gone).
    pub drive: Option<usize>,
    /// What it reported.
    pub fault: DriveFault,
}

impl core::fmt::Display for LineFault {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self.drive {
            Some(drive) => write!(f, "drive {drive}: {}", self.fault),
            None => write!(f, "working counter short: {}", self.fault),
        }
    }
}

/// What the supervisor saw after an exchange.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Supervision {
    /// Faults first seen this cycle; the line is faulted and its drives
    /// brake on their quick-stop ramps.
    pub new_faults: Vec<LineFault>,
    /// Every drive of the line reports "operation enabled" for the first
    /// time since the start: the line is running from now on.
    pub now_running: bool,
}

/// Longest a line may take to enable before the drives that have not are
/// reported ([`DriveFault::EnableTimeout`]).
pub const ENABLE_TIMEOUT: Duration = Duration::from_secs(3);

/// The state machine of a line of drives (the drives at `drives`).
#[derive(Clone, Debug)]
pub struct Supervisor {
    drives: Vec<usize>,
    state: LineState,
    faults: Vec<LineFault>,
    /// Cycles spent enabling, and the most allowed.
    enabling: u64,
    enable_limit: u64,
}

impl Supervisor {
    /// A stopped line of the drives at these positions, cycled every
    /// `cycle`.
    pub fn new(drives: Vec<usize>, cycle: Duration) -> Self {
        let limit = ENABLE_TIMEOUT.as_nanos() / cycle.as_nanos().max(1);
        Self {
            drives,
            state: LineState::Stopped,
            faults: Vec::new(),
            enabling: 0,
            enable_limit: u64::try_from(limit).unwrap_or(u64::MAX).max(1),
        }
    }

    /// Where the line is.
    pub fn state(&self) -> LineState {
        self.state
    }

    /// The faults that stopped the line (until [`Supervisor::reset`]).
    pub fn faults(&self) -> &[LineFault] {
        &self.faults
    }

    /// Asks the line's drives to enable. A drive whose fault reset is
    /// still under way finishes it first, so "reset, then enable" may be
    /// sent back to back.
    ///
    /// # Errors
    /// The state, when the line is not stopped (a faulted line needs a
    /// reset first: it never restarts by itself).
    pub fn start(&mut self, segment: &mut Segment) -> Result<(), LineState> {
        if self.state != LineState::Stopped {
            return Err(self.state);
        }
        for &position in &self.drives {
            if let Some(d) = segment.drives_mut().get_mut(position) {
                if !resetting(d) {
                    d.set_request(Request::Operate);
                }
            }
        }
        self.state = LineState::Enabling;
        self.enabling = 0;
        Ok(())
    }

    /// Disables every drive on the segment; a faulted line stays faulted.
    pub fn stop(&mut self, segment: &mut Segment) {
        for d in segment.drives_mut() {
            d.set_request(Request::Disabled);
        }
        if self.state != LineState::Faulted {
            self.state = LineState::Stopped;
        }
    }

    /// Clears the faults: a fault reset to each faulted drive, the others
    /// disabled; the line is stopped afterwards.
    ///
    /// # Errors
    /// The state, when the line is not faulted.
    pub fn reset(&mut self, segment: &mut Segment) -> Result<(), LineState> {
        if self.state != LineState::Faulted {
            return Err(self.state);
        }
        for d in segment.drives_mut() {
            d.set_request(if d.state() == DriveState::Fault {
                Request::ResetFault
            } else {
                Request::Disabled
            });
        }
        self.faults.clear();
        self.state = LineState::Stopped;
        Ok(())
    }

    /// Looks at the drives after an exchange: a fault or a short working
    /// counter while enabling or running stops the line (every drive brakes
    /// on its quick-stop ramp); all drives enabled moves it to running.
    pub fn after_exchange(&mut self, segment: &mut Segment, bus: &CycleReport) -> Supervision {
        let mut seen = Supervision::default();
        if !matches!(self.state, LineState::Running | LineState::Enabling) {
            return seen;
        }
        let enabling = self.state == LineState::Enabling;
        if enabling {
            self.enabling = self.enabling.saturating_add(1);
        }
        for &position in &self.drives {
            let Some(d) = segment.drives_mut().get_mut(position) else {
                continue;
            };
            if enabling && d.request() == Request::ResetFault {
                if resetting(d) {
                    // Still in its fault: the reset edge is on its way,
                    // unless the fault outlives the enable timeout.
                    if self.enabling > self.enable_limit {
                        seen.new_faults.push(LineFault {
                            drive: Some(position),
                            fault: DriveFault::EnableTimeout,
                        });
                    }
                    continue;
                }
                d.set_request(Request::Operate);
            }
            let status = d.status();
            if let Some(fault) = status.fault {
                seen.new_faults.push(LineFault {
                    drive: Some(position),
                    fault,
                });
            } else if enabling && !status.enabled && self.enabling > self.enable_limit {
                seen.new_faults.push(LineFault {
                    drive: Some(position),
                    fault: DriveFault::EnableTimeout,
                });
            }
        }
        if bus.working_counter_error() && seen.new_faults.is_empty() {
            // Short working counter but every drive of the line answered:
            // a drive the line does not use is gone; still a stop.
            seen.new_faults.push(LineFault {
                drive: None,
                fault: DriveFault::Communication,
            });
        }
        if !seen.new_faults.is_empty() {
            for d in segment.drives_mut() {
                d.set_request(Request::QuickStop);
            }
            self.faults.extend_from_slice(&seen.new_faults);
            self.state = LineState::Faulted;
        } else if self.state == LineState::Enabling && self.all_enabled(segment) {
            self.state = LineState::Running;
            seen.now_running = true;
        }
        seen
    }

    fn all_enabled(&self, segment: &Segment) -> bool {
        self.drives.iter().all(|&position| {
            segment
                .drives()
                .get(position)
                .is_some_and(|d| d.status().enabled)
        })
    }
}

/// A drive still in its fault with a fault reset requested.
fn resetting(d: &crate::Cia402Drive) -> bool {
    d.request() == Request::ResetFault
        && matches!(
            d.state(),
            DriveState::Fault | DriveState::FaultReactionActive
        )
        && d.reachable()
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
