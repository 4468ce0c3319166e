//! Drives that follow a PLC's pulse outputs: the bus side of `ecam serve
//! --ethercat`. The PLC's DECAM, PLSY and DPLSY instructions keep driving
//! Y0–Y3 as they always do; each cycle, every drive mapped to an output
//! gets the pulses that output has emitted, scaled to drive counts, as its
//! CSP target position.
//!
//! The target is computed from the total the output has emitted since
//! power-up (not from the previous target), so a non-integer scale never
//! drifts: after any number of cycles the target is exactly
//! `origin + floor(emitted · num / den)`. The origin is set while the
//! drive is not enabled so that the target equals the drive's actual
//! position: enabling never jumps, and neither does re-enabling after a
//! fault, wherever the PLC moved the output meanwhile.

use std::time::Duration;

use ecam_engine::drive::AxisDrive;

use crate::error::EthercatError;
use crate::segment::{CycleReport, Segment};
use crate::supervisor::{LineFault, LineState, Supervision, Supervisor, check_positions};

/// Pulse outputs a PLC has (Y0–Y3).
pub const PULSE_OUTPUTS: u8 = 4;

/// Drive counts per pulse, as a rational `num / den` (exact, never a
/// float: 10000 counts per revolution over 3600 pulses is `[25, 9]`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Scale {
    num: i64,
    den: i64,
}

impl Scale {
    /// One count per pulse.
    pub const ONE: Self = Self { num: 1, den: 1 };

    /// `num / den` counts per pulse. A negative `num` turns the drive the
    /// other way.
    ///
    /// # Errors
    /// [`ScaleError`] when `den` is not positive or `num` is zero.
    pub fn new(num: i64, den: i64) -> Result<Self, ScaleError> {
        if den <= 0 {
            return Err(ScaleError::Denominator(den));
        }
        if num == 0 {
            return Err(ScaleError::Zero);
        }
        Ok(Self { num, den })
    }

    /// Counts for `pulses`: `floor(pulses · num / den)`, saturated to i64.
    pub fn counts(self, pulses: i64) -> i64 {
        let product = i128::from(pulses) * i128::from(self.num);
        let counts = product.div_euclid(i128::from(self.den));
        i64::try_from(counts).unwrap_or(if counts < 0 { i64::MIN } else { i64::MAX })
    }

    /// The numerator.
    pub fn num(self) -> i64 {
        self.num
    }

    /// The denominator (positive).
    pub fn den(self) -> i64 {
        self.den
    }
}

impl Default for Scale {
    fn default() -> Self {
        Self::ONE
    }
}

/// A scale that cannot be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScaleError {
    /// The denominator is zero or negative.
    Denominator(i64),
    /// Zero counts per pulse: the drive would never move.
    Zero,
}

impl core::fmt::Display for ScaleError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Denominator(d) => write!(f, "scale denominator {d} must be positive"),
            Self::Zero => f.write_str("scale 0: the drive would never move"),
        }
    }
}

impl std::error::Error for ScaleError {}

/// One drive following one pulse output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Follower {
    /// The pulse output, 0–3 for Y0–Y3.
    pub output: u8,
    /// Position of the drive in the line.
    pub drive: usize,
    /// Drive counts per pulse.
    pub scale: Scale,
}

/// Errors setting up or commanding a following line.
#[derive(Debug)]
pub enum FollowError {
    /// A follower names a drive the segment does not have.
    NoSuchDrive {
        /// The position named.
        drive: usize,
        /// Drives on the segment.
        drives: usize,
    },
    /// A follower names an output beyond Y3.
    NoSuchOutput(u8),
    /// Two followers command the same drive.
    DriveTwice(usize),
    /// No follower at all.
    Empty,
    /// The request is not possible in this state.
    State(LineState),
    /// The bus failed.
    Bus(EthercatError),
}

impl core::fmt::Display for FollowError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NoSuchDrive { drive, drives } => {
                write!(f, "drive {drive} does not exist (the segment has {drives})")
            }
            Self::NoSuchOutput(y) => write!(f, "Y{y} is not a pulse output (Y0–Y3)"),
            Self::DriveTwice(d) => write!(f, "two outputs command drive {d}"),
            Self::Empty => f.write_str("no output is mapped to a drive"),
            Self::State(s) => write!(f, "not possible while the line is {}", s.name()),
            Self::Bus(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for FollowError {}

impl From<EthercatError> for FollowError {
    fn from(e: EthercatError) -> Self {
        Self::Bus(e)
    }
}

/// What one cycle of a following line did (the targets and faults are in
/// [`FollowLine::target_of`] and [`FollowLine::new_faults`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FollowReport {
    /// The bus exchange.
    pub bus: CycleReport,
    /// What the supervisor saw.
    pub seen: Supervision,
}

#[derive(Clone, Copy, Debug)]
struct Following {
    spec: Follower,
    /// Target minus scaled pulses; re-set while the drive is not enabled.
    origin: i64,
    target: i64,
    /// Target change of the last cycle (the drive's velocity, counts per
    /// cycle).
    velocity: i64,
    /// The velocity when a stop began, and where.
    stop_from: (i64, i64),
}

/// Drives on a segment following pulse outputs.
#[derive(Debug)]
pub struct FollowLine {
    segment: Segment,
    followers: Vec<Following>,
    supervisor: Supervisor,
    dt_us: u32,
    stop_cycles: u32,
    /// Cycles into the stop ramp (`None`: not stopping).
    stopping: Option<u32>,
    settling: u32,
    /// The last exchange came back.
    advanced: bool,
}

impl FollowLine {
    /// Binds outputs to drives: every drive must exist and be named once;
    /// one output may drive several drives (a gantry). More than
    /// `max_lost_cycles` cycles in a row without a drive's answer fault the
    /// line; a stop decelerates each drive to rest over `stop`.
    ///
    /// # Errors
    /// [`FollowError`] for a missing drive or output, a drive named twice,
    /// or no follower.
    pub fn new(
        segment: Segment,
        followers: Vec<Follower>,
        max_lost_cycles: u32,
        stop: Duration,
    ) -> Result<Self, FollowError> {
        if followers.is_empty() {
            return Err(FollowError::Empty);
        }
        let drives = segment.len();
        check_positions(followers.iter().map(|f| f.drive), drives)
            .map_err(|drive| FollowError::NoSuchDrive { drive, drives })?;
        let mut used = vec![false; drives];
        for f in &followers {
            if f.output >= PULSE_OUTPUTS {
                return Err(FollowError::NoSuchOutput(f.output));
            }
            if used[f.drive] {
                return Err(FollowError::DriveTwice(f.drive));
            }
            used[f.drive] = true;
        }
        let cycle = segment.config().cycle;
        let dt_us = u32::try_from(cycle.as_micros()).unwrap_or(u32::MAX);
        let stop_cycles =
            u32::try_from(stop.as_nanos() / cycle.as_nanos().max(1)).unwrap_or(u32::MAX);
        Ok(Self {
            supervisor: Supervisor::new(
                followers.iter().map(|f| f.drive).collect(),
                drives,
                cycle,
                max_lost_cycles,
            ),
            followers: followers
                .into_iter()
                .map(|spec| Following {
                    spec,
                    origin: 0,
                    target: 0,
                    velocity: 0,
                    stop_from: (0, 0),
                })
                .collect(),
            segment,
            dt_us,
            stop_cycles,
            stopping: None,
            settling: 0,
            advanced: true,
        })
    }

    /// The segment (drive status).
    pub fn segment(&self) -> &Segment {
        &self.segment
    }

    /// The followers, in configuration order.
    pub fn followers(&self) -> impl ExactSizeIterator<Item = Follower> + '_ {
        self.followers.iter().map(|f| f.spec)
    }

    /// The output drive `position` follows, if any.
    pub fn output_of(&self, position: usize) -> Option<u8> {
        self.followers
            .iter()
            .find(|f| f.spec.drive == position)
            .map(|f| f.spec.output)
    }

    /// The target last sent to drive `position`, if it follows an output.
    pub fn target_of(&self, position: usize) -> Option<i64> {
        self.followers
            .iter()
            .find(|f| f.spec.drive == position)
            .map(|f| f.target)
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

    /// The last exchange came back (a PLC paced by the bus steps only then,
    /// so no drive gets the motion of a lost cycle in one step).
    pub fn advanced(&self) -> bool {
        self.advanced
    }

    /// Enables the drives; each follows its output from the cycle it
    /// reports "operation enabled", starting where it stands.
    ///
    /// # Errors
    /// [`FollowError::State`] unless the line is stopped.
    pub fn start(&mut self) -> Result<(), FollowError> {
        self.supervisor
            .start(&mut self.segment)
            .map_err(FollowError::State)
    }

    /// Stops the line: each drive decelerates from its present velocity to
    /// rest over the stop time (its output is no longer followed), then
    /// the drives are disabled.
    pub fn stop(&mut self) {
        if self.state() == LineState::Running {
            for f in &mut self.followers {
                f.stop_from = (f.target, f.velocity);
            }
            self.stopping = Some(0);
            self.settling = 0;
        }
        self.supervisor.begin_stop(&mut self.segment);
    }

    /// Disables the drives at once (no deceleration).
    pub fn disable(&mut self) {
        self.stopping = None;
        self.supervisor.disable(&mut self.segment);
    }

    /// The drives are not enabled (stopped, faulted or recovering).
    pub fn at_rest(&self) -> bool {
        !matches!(
            self.state(),
            LineState::Running | LineState::Stopping | LineState::Enabling
        )
    }

    /// Clears the faults (see [`crate::line::CamLine::reset`]); the line is
    /// recovering, then stopped.
    ///
    /// # Errors
    /// [`FollowError::State`] unless the line is faulted; the bus error
    /// when the segment could not be brought up again.
    pub fn reset(&mut self) -> Result<(), FollowError> {
        let reinitialise = self
            .supervisor
            .reset(&mut self.segment)
            .map_err(FollowError::State)?;
        if reinitialise {
            self.segment.reinitialise()?;
            self.supervisor.reinitialised();
        }
        Ok(())
    }

    /// Runs the pending acyclic step (diagnosis, recovery), waiting at
    /// most `budget`.
    pub fn acyclic_step(&mut self, budget: Duration) {
        if self.supervisor.has_acyclic_work() {
            self.supervisor.acyclic_step(&mut self.segment, budget);
        }
    }

    /// One cycle: `emitted[y]` is the total of signed pulses output `y`
    /// has emitted since power-up (ecam-plc's `Hardware::emitted`);
    /// targets out, exchange, status in, supervision.
    ///
    /// # Errors
    /// [`FollowError::Bus`] when the exchange itself fails.
    pub fn cycle(
        &mut self,
        emitted: &[i64; PULSE_OUTPUTS as usize],
    ) -> Result<FollowReport, FollowError> {
        let stopping = self.stopping;
        let n = i128::from(self.stop_cycles.max(1));
        for f in &mut self.followers {
            let pulses = emitted
                .get(usize::from(f.spec.output))
                .copied()
                .unwrap_or(0);
            let counts = f.spec.scale.counts(pulses);
            let Some(drive) = self.segment.drives_mut().get_mut(f.spec.drive) else {
                continue;
            };
            let before = f.target;
            if let Some(k) = stopping {
                // A linear ramp from the velocity the stop began with.
                let (from, v) = f.stop_from;
                let k = i128::from(k.min(self.stop_cycles));
                let travelled = (i128::from(v) * (k * n - k * (k + 1) / 2)).div_euclid(n);
                f.target = from.saturating_add(i64::try_from(travelled).unwrap_or(0));
            } else {
                // The state last heard: a lost cycle does not re-origin.
                if drive.state() != crate::cia402::DriveState::OperationEnabled {
                    // Not following yet: the target is where the drive
                    // stands.
                    f.origin = drive.actual().saturating_sub(counts);
                }
                f.target = f.origin.saturating_add(counts);
            }
            f.velocity = f.target.saturating_sub(before);
            drive.command(f.target, self.dt_us);
        }
        let bus = self.segment.exchange()?;
        self.advanced = !bus.frame_lost;
        let seen = self.supervisor.after_exchange(&mut self.segment, &bus);
        if let Some(k) = &mut self.stopping {
            if self.advanced {
                *k = k.saturating_add(1);
            }
            if *k > self.stop_cycles {
                self.settling = self.settling.saturating_add(1);
                let still = self.followers.iter().all(|f| {
                    self.segment
                        .drives()
                        .get(f.spec.drive)
                        .is_some_and(|d| d.actual() == f.target)
                });
                if still || self.settling > 1000 {
                    self.stopping = None;
                    self.supervisor.disable(&mut self.segment);
                }
            }
            if self.state() != LineState::Stopping {
                self.stopping = None;
            }
        }
        Ok(FollowReport { bus, seen })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_is_exact_and_floors() {
        let s = Scale::new(25, 9).unwrap();
        assert_eq!(s.counts(9), 25);
        assert_eq!(s.counts(10), 27);
        assert_eq!(s.counts(-1), -3);
        assert_eq!(s.counts(3_600_000_000), 10_000_000_000);
        assert_eq!(Scale::new(i64::MAX, 1).unwrap().counts(i64::MAX), i64::MAX);
        assert_eq!(Scale::new(-2, 1).unwrap().counts(5), -10);
        assert_eq!(Scale::new(1, 0), Err(ScaleError::Denominator(0)));
        assert_eq!(Scale::new(0, 3), Err(ScaleError::Zero));
        assert_eq!(Scale::default(), Scale::ONE);
    }
}
