//! Cams on drives: each cycle, every cam axis ticks against its master
//! (a virtual master or a drive's actual position on the bus), its
//! commanded position goes to its drive, and the process data is
//! exchanged. A drive fault, a drive out of OP or a drive lost for longer
//! than the line allows stops the whole line.
//!
//! Rules kept here (issue 24):
//! - until the whole line is armed, every drive is commanded to its own
//!   actual position, whatever its cam says (a drive that enables before
//!   the others holds still);
//! - a cycle whose reply was lost does not advance the virtual master: the
//!   next frame carries the same targets again, so a drive never sees a
//!   step made of the motion of the lost cycles;
//! - a stop decelerates the virtual master to rest over the configured
//!   stop time, waits for the drives to settle, then disables them.

use std::time::Duration;

use ecam_core::CamCurve;
use ecam_engine::drive::AxisDrive;
use ecam_engine::{CamAxis, EngineError, StopKind, TickInput, TickOutput};

use crate::cia402::DriveState;
use crate::error::EthercatError;
use crate::segment::{CycleReport, Segment};
pub use crate::supervisor::{FaultCause, LineFault, LineState};
use crate::supervisor::{Supervision, Supervisor, check_positions};

/// Where an axis takes its master position from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Master {
    /// The line's virtual master (advances while the line runs).
    Virtual,
    /// The actual position of drive `position` on the segment: a line
    /// shaft or web-feed drive as the master of a knife.
    DriveActual {
        /// Position of the master drive in the line.
        position: usize,
    },
}

/// A cam axis bound to a drive.
#[derive(Debug)]
pub struct CamDrive<C> {
    /// The cam.
    pub axis: CamAxis<C>,
    /// Position of the drive it commands.
    pub drive: usize,
    /// Its master.
    pub master: Master,
}

/// What one cycle of a line did (the axes' outputs and the faults are in
/// [`CamLine::outputs`] and [`CamLine::new_faults`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LineReport {
    /// The bus exchange.
    pub bus: CycleReport,
    /// Virtual master position this cycle.
    pub virtual_master: i64,
    /// What the supervisor saw.
    pub seen: Supervision,
}

/// Errors setting up or commanding a line.
#[derive(Debug)]
pub enum LineError {
    /// An axis names a drive the segment does not have.
    NoSuchDrive {
        /// The position named.
        drive: usize,
        /// Drives on the segment.
        drives: usize,
    },
    /// Two axes command the same drive.
    DriveTwice(usize),
    /// The engine refused (arming, positioning).
    Engine(EngineError),
    /// The bus failed.
    Bus(EthercatError),
    /// The request is not possible in this state.
    State(LineState),
}

impl core::fmt::Display for LineError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NoSuchDrive { drive, drives } => {
                write!(f, "drive {drive} does not exist (the segment has {drives})")
            }
            Self::DriveTwice(d) => write!(f, "two axes command drive {d}"),
            Self::Engine(e) => write!(f, "cam: {e}"),
            Self::Bus(e) => e.fmt(f),
            Self::State(s) => write!(f, "not possible while the line is {}", s.name()),
        }
    }
}

impl std::error::Error for LineError {}

impl From<EthercatError> for LineError {
    fn from(e: EthercatError) -> Self {
        Self::Bus(e)
    }
}

/// The virtual master's deceleration to rest.
#[derive(Clone, Copy, Debug)]
struct StopRamp {
    from: i64,
    speed: i64,
    cycles: u32,
    done: u32,
}

impl StopRamp {
    /// Position after `k` cycles of a linear ramp from `speed` to rest
    /// over `cycles`: exact integers, monotonic.
    fn position(&self, k: u32) -> i64 {
        let n = i128::from(self.cycles.max(1));
        let k = i128::from(k.min(self.cycles));
        let travelled = i128::from(self.speed) * (k * n - k * (k + 1) / 2);
        let travelled = travelled.div_euclid(n);
        self.from
            .saturating_add(i64::try_from(travelled).unwrap_or(if travelled < 0 {
                i64::MIN
            } else {
                i64::MAX
            }))
    }
}

/// Longest the drives are given to settle after the master stopped.
const SETTLE_LIMIT: Duration = Duration::from_secs(1);

/// Cam axes running on a segment's drives.
#[derive(Debug)]
pub struct CamLine<C> {
    segment: Segment,
    axes: Vec<CamDrive<C>>,
    outputs: Vec<TickOutput>,
    supervisor: Supervisor,
    virtual_master: i64,
    /// Virtual master counts per cycle while running.
    pub virtual_speed: i64,
    dt_us: u32,
    stop_cycles: u32,
    ramp: Option<StopRamp>,
    settling: u64,
    settle_limit: u64,
    /// The last exchange came back: the master may advance.
    advance: bool,
}

impl<C: CamCurve> CamLine<C> {
    /// Binds axes to drives. Every drive an axis names must exist, once;
    /// a master drive must exist too. More than `max_lost_cycles` cycles in
    /// a row without a drive's answer fault the line; a stop decelerates
    /// over `stop`.
    pub fn new(
        segment: Segment,
        axes: Vec<CamDrive<C>>,
        max_lost_cycles: u32,
        stop: Duration,
    ) -> Result<Self, LineError> {
        let drives = segment.len();
        let masters = axes.iter().filter_map(|a| match a.master {
            Master::DriveActual { position } => Some(position),
            Master::Virtual => None,
        });
        check_positions(axes.iter().map(|a| a.drive).chain(masters), drives)
            .map_err(|drive| LineError::NoSuchDrive { drive, drives })?;
        let mut used = vec![false; drives];
        for a in &axes {
            if used[a.drive] {
                return Err(LineError::DriveTwice(a.drive));
            }
            used[a.drive] = true;
        }
        let cycle = segment.config().cycle;
        let dt_us = u32::try_from(cycle.as_micros()).unwrap_or(u32::MAX);
        let per_cycle = cycle.as_nanos().max(1);
        let stop_cycles = u32::try_from(stop.as_nanos() / per_cycle).unwrap_or(u32::MAX);
        let settle_limit = u64::try_from(SETTLE_LIMIT.as_nanos() / per_cycle).unwrap_or(u64::MAX);
        Ok(Self {
            supervisor: Supervisor::new(
                axes.iter().map(|a| a.drive).collect(),
                drives,
                cycle,
                max_lost_cycles,
            ),
            outputs: vec![TickOutput::default(); axes.len()],
            segment,
            axes,
            virtual_master: 0,
            virtual_speed: 0,
            dt_us,
            stop_cycles,
            ramp: None,
            settling: 0,
            settle_limit,
            advance: true,
        })
    }

    /// The segment (drive status).
    pub fn segment(&self) -> &Segment {
        &self.segment
    }

    /// The segment, to command drives that no cam uses.
    pub fn segment_mut(&mut self) -> &mut Segment {
        &mut self.segment
    }

    /// The axes.
    pub fn axes(&self) -> &[CamDrive<C>] {
        &self.axes
    }

    /// Each axis' tick output of the last cycle, in axis order.
    pub fn outputs(&self) -> &[TickOutput] {
        &self.outputs
    }

    /// Where the line is.
    pub fn state(&self) -> LineState {
        self.supervisor.state()
    }

    /// The faults that stopped the line (until a reset has recovered it).
    pub fn faults(&self) -> &[LineFault] {
        self.supervisor.faults()
    }

    /// The faults first seen in the last cycle.
    pub fn new_faults(&self) -> &[LineFault] {
        self.supervisor.new_faults()
    }

    /// The supervisor (limits, drives).
    pub fn supervisor(&self) -> &Supervisor {
        &self.supervisor
    }

    /// Virtual master position.
    pub fn virtual_master(&self) -> i64 {
        self.virtual_master
    }

    /// Enables every cam drive; once all report "operation enabled" each
    /// cam takes its drive's actual position as its slave position and
    /// arms. Until then every drive holds where it stands.
    pub fn start(&mut self) -> Result<(), LineError> {
        self.supervisor
            .start(&mut self.segment)
            .map_err(LineError::State)
    }

    /// Stops the line: a running line decelerates its virtual master to
    /// rest over the stop time, the drives settle, then they are
    /// disabled ([`CamLine::at_rest`] tells when).
    pub fn stop(&mut self) {
        if self.state() == LineState::Running {
            self.ramp = Some(StopRamp {
                from: self.virtual_master,
                speed: self.virtual_speed,
                cycles: self.stop_cycles,
                done: 0,
            });
            self.settling = 0;
        } else {
            self.stop_axes();
        }
        self.supervisor.begin_stop(&mut self.segment);
    }

    /// The line is not moving and its drives are not enabled (stopped,
    /// faulted or recovering).
    pub fn at_rest(&self) -> bool {
        !matches!(
            self.state(),
            LineState::Running | LineState::Stopping | LineState::Enabling
        )
    }

    /// Clears the faults: a fault reset to each faulted drive, drives
    /// that left OP brought back (the whole segment brought up again when
    /// a drive does not answer at all). The line is recovering, then
    /// stopped ([`CamLine::start`] to run again, from where the drives
    /// stand).
    pub fn reset(&mut self) -> Result<(), LineError> {
        let reinitialise = self
            .supervisor
            .reset(&mut self.segment)
            .map_err(LineError::State)?;
        if reinitialise {
            self.segment.reinitialise()?;
            self.supervisor.reinitialised();
        }
        Ok(())
    }

    fn stop_axes(&mut self) {
        for a in &mut self.axes {
            a.axis.stop(StopKind::Immediate);
        }
        self.ramp = None;
    }

    /// One cycle: master, cams, outputs, exchange, inputs, supervision.
    pub fn cycle(&mut self) -> Result<LineReport, LineError> {
        let state = self.state();
        let moving = matches!(state, LineState::Running | LineState::Stopping);
        if moving && self.advance {
            match &mut self.ramp {
                Some(ramp) => {
                    ramp.done = ramp.done.saturating_add(1).min(ramp.cycles);
                    self.virtual_master = ramp.position(ramp.done);
                }
                None => {
                    self.virtual_master = self.virtual_master.saturating_add(self.virtual_speed);
                }
            }
        }
        for (a, out) in self.axes.iter_mut().zip(&mut self.outputs) {
            let drives = self.segment.drives();
            let master = match a.master {
                Master::Virtual => self.virtual_master,
                Master::DriveActual { position } => drives.get(position).map_or(0, |d| d.actual()),
            };
            let Some(drive) = drives.get(a.drive) else {
                continue;
            };
            // The state last heard: a lost cycle does not disable the cam.
            let enabled = drive.state() == DriveState::OperationEnabled;
            let actual = drive.actual();
            *out = a.axis.tick(&TickInput {
                master,
                dt_us: self.dt_us,
                output_enabled: moving && enabled,
                ..TickInput::default()
            });
            // Until the whole line is armed every drive holds where it
            // stands.
            let target = if moving { out.slave } else { actual };
            if let Some(d) = self.segment.drives_mut().get_mut(a.drive) {
                d.command(target, self.dt_us);
            }
        }
        let bus = self.segment.exchange()?;
        self.advance = !bus.frame_lost;
        let seen = self.supervisor.after_exchange(&mut self.segment, &bus);
        if seen.new_faults > 0 {
            // Every cam stops where it is; the drives brake on their own.
            self.stop_axes();
        } else if seen.now_running {
            self.arm_all()?;
        } else if self.state() == LineState::Stopping && self.settled() {
            self.stop_axes();
            self.supervisor.disable(&mut self.segment);
        }
        Ok(LineReport {
            bus,
            virtual_master: self.virtual_master,
            seen,
        })
    }

    /// Runs the pending acyclic step (diagnosis of a drive that left OP,
    /// a step of a reset's recovery), waiting at most `budget`.
    pub fn acyclic_step(&mut self, budget: Duration) {
        if self.supervisor.has_acyclic_work() {
            self.supervisor.acyclic_step(&mut self.segment, budget);
        }
    }

    /// The stop ramp is over and every cam drive stands at its target (or
    /// has had a second to get there).
    fn settled(&mut self) -> bool {
        let ramp_over = self.ramp.is_none_or(|r| r.done >= r.cycles);
        if !ramp_over {
            return false;
        }
        self.settling = self.settling.saturating_add(1);
        let still = self.axes.iter().zip(&self.outputs).all(|(a, out)| {
            self.segment
                .drives()
                .get(a.drive)
                .is_some_and(|d| d.actual() == out.slave)
        });
        still || self.settling > self.settle_limit
    }

    fn arm_all(&mut self) -> Result<(), LineError> {
        for a in &mut self.axes {
            let actual = self.segment.drives().get(a.drive).map_or(0, |d| d.actual());
            a.axis
                .set_slave_position(actual)
                .map_err(LineError::Engine)?;
            a.axis.arm().map_err(LineError::Engine)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The line must move into the real-time cycle thread.
    #[test]
    fn line_is_send() {
        fn assert_send<T: Send>() {}
        assert_send::<CamLine<ecam_core::PointTable>>();
    }

    #[test]
    fn stop_ramp_is_exact_and_reaches_rest() {
        let ramp = StopRamp {
            from: 100,
            speed: 7,
            cycles: 10,
            done: 0,
        };
        let positions: Vec<i64> = (0..=12).map(|k| ramp.position(k)).collect();
        assert!(positions.windows(2).all(|w| w[1] >= w[0]), "{positions:?}");
        // 7 · (10·10 − 55) / 10 = 31.5 → 31 counts of braking distance.
        assert_eq!(positions[10], 131);
        assert_eq!(positions[12], 131, "at rest after the ramp");
        // The first step is nearly the running speed.
        assert_eq!(positions[1] - positions[0], 6);
        let back = StopRamp { speed: -7, ..ramp };
        assert_eq!(back.position(10), 100 - 32);
    }
}
