//! Cams on drives: each cycle, every cam axis ticks against its master
//! (a virtual master or a drive's actual position on the bus), its
//! commanded position goes to its drive, and the process data is
//! exchanged. A drive fault or a lost drive stops the whole line.

use ecam_core::CamCurve;
use ecam_engine::drive::AxisDrive;
use ecam_engine::{CamAxis, EngineError, StopKind, TickInput, TickOutput};

use crate::error::EthercatError;
use crate::segment::{CycleReport, Segment};
pub use crate::supervisor::{LineFault, LineState};
use crate::supervisor::{Supervisor, check_positions};

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

/// What one cycle of the line did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LineReport {
    /// The bus exchange.
    pub bus: CycleReport,
    /// Virtual master position this cycle.
    pub virtual_master: i64,
    /// Each axis' tick output, in axis order.
    pub axes: Vec<TickOutput>,
    /// Faults first seen this cycle (they stopped the line).
    pub new_faults: Vec<LineFault>,
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
            Self::State(s) => write!(f, "not possible while the line is {s:?}"),
        }
    }
}

impl std::error::Error for LineError {}

impl From<EthercatError> for LineError {
    fn from(e: EthercatError) -> Self {
        Self::Bus(e)
    }
}

/// Cam axes running on a segment's drives.
#[derive(Debug)]
pub struct CamLine<C> {
    segment: Segment,
    axes: Vec<CamDrive<C>>,
    supervisor: Supervisor,
    virtual_master: i64,
    /// Virtual master counts per cycle while running.
    pub virtual_speed: i64,
    dt_us: u32,
}

impl<C: CamCurve> CamLine<C> {
    /// Binds axes to drives. Every drive an axis names must exist, once;
    /// a master drive must exist too.
    pub fn new(segment: Segment, axes: Vec<CamDrive<C>>) -> Result<Self, LineError> {
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
        let dt_us = u32::try_from(segment.config().cycle.as_micros()).unwrap_or(u32::MAX);
        Ok(Self {
            supervisor: Supervisor::new(
                axes.iter().map(|a| a.drive).collect(),
                segment.config().cycle,
            ),
            segment,
            axes,
            virtual_master: 0,
            virtual_speed: 0,
            dt_us,
        })
    }

    /// The segment (drive status).
    pub fn segment(&self) -> &Segment {
        &self.segment
    }

    /// The segment, to command drives that no cam uses (e.g. a master
    /// drive on its own).
    pub fn segment_mut(&mut self) -> &mut Segment {
        &mut self.segment
    }

    /// The axes.
    pub fn axes(&self) -> &[CamDrive<C>] {
        &self.axes
    }

    /// Where the line is.
    pub fn state(&self) -> LineState {
        self.supervisor.state()
    }

    /// The faults that stopped the line (until [`CamLine::reset`]).
    pub fn faults(&self) -> &[LineFault] {
        self.supervisor.faults()
    }

    /// Virtual master position.
    pub fn virtual_master(&self) -> i64 {
        self.virtual_master
    }

    /// Enables every cam drive; once all report "operation enabled" each
    /// cam takes its drive's actual position as its slave position and
    /// arms.
    pub fn start(&mut self) -> Result<(), LineError> {
        self.supervisor
            .start(&mut self.segment)
            .map_err(LineError::State)
    }

    /// Stops the cams at once and disables the drives.
    pub fn stop(&mut self) {
        for a in &mut self.axes {
            a.axis.stop(StopKind::Immediate);
        }
        self.supervisor.stop(&mut self.segment);
    }

    /// Clears the faults: a fault reset to each faulted drive; the line is
    /// stopped afterwards ([`CamLine::start`] to run again).
    pub fn reset(&mut self) -> Result<(), LineError> {
        self.supervisor
            .reset(&mut self.segment)
            .map_err(LineError::State)
    }

    /// One cycle: master, cams, outputs, exchange, inputs, fault check.
    pub fn cycle(&mut self) -> Result<LineReport, LineError> {
        let running = self.state() == LineState::Running;
        if running {
            self.virtual_master = self.virtual_master.saturating_add(self.virtual_speed);
        }
        let mut outputs = Vec::with_capacity(self.axes.len());
        for a in &mut self.axes {
            let drives = self.segment.drives();
            let master = match a.master {
                Master::Virtual => self.virtual_master,
                Master::DriveActual { position } => drives.get(position).map_or(0, |d| d.actual()),
            };
            let enabled = drives.get(a.drive).is_some_and(|d| d.status().enabled);
            let out = a.axis.tick(&TickInput {
                master,
                dt_us: self.dt_us,
                output_enabled: running && enabled,
                ..TickInput::default()
            });
            if let Some(d) = self.segment.drives_mut().get_mut(a.drive) {
                d.command(out.slave, self.dt_us);
            }
            outputs.push(out);
        }
        let bus = self.segment.exchange()?;
        let seen = self.supervisor.after_exchange(&mut self.segment, &bus);
        if !seen.new_faults.is_empty() {
            // Every cam stops where it is; the drives brake on their own.
            for a in &mut self.axes {
                a.axis.stop(StopKind::Immediate);
            }
        } else if seen.now_running {
            self.arm_all()?;
        }
        Ok(LineReport {
            bus,
            virtual_master: self.virtual_master,
            axes: outputs,
            new_faults: seen.new_faults,
        })
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
    /// The line must move into the real-time cycle thread.
    #[test]
    fn line_is_send() {
        fn assert_send<T: Send>() {}
        assert_send::<super::CamLine<ecam_core::PointTable>>();
    }
}
