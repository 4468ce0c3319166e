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

use ecam_engine::drive::AxisDrive;

use crate::error::EthercatError;
use crate::segment::{CycleReport, Segment};
use crate::supervisor::{LineFault, LineState, Supervisor, check_positions};

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

/// What one cycle of a following line did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FollowReport {
    /// The bus exchange.
    pub bus: CycleReport,
    /// The target position each follower was sent, in follower order.
    pub targets: Vec<i64>,
    /// Faults first seen this cycle (they stopped the line).
    pub new_faults: Vec<LineFault>,
}

#[derive(Clone, Copy, Debug)]
struct Following {
    spec: Follower,
    /// Target minus scaled pulses; re-set while the drive is not enabled.
    origin: i64,
    target: i64,
}

/// Drives on a segment following pulse outputs.
#[derive(Debug)]
pub struct FollowLine {
    segment: Segment,
    followers: Vec<Following>,
    supervisor: Supervisor,
    dt_us: u32,
}

impl FollowLine {
    /// Binds outputs to drives: every drive must exist and be named once;
    /// one output may drive several drives (a gantry).
    ///
    /// # Errors
    /// [`FollowError`] for a missing drive or output, a drive named twice,
    /// or no follower.
    pub fn new(segment: Segment, followers: Vec<Follower>) -> Result<Self, FollowError> {
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
        let dt_us = u32::try_from(segment.config().cycle.as_micros()).unwrap_or(u32::MAX);
        Ok(Self {
            supervisor: Supervisor::new(
                followers.iter().map(|f| f.drive).collect(),
                segment.config().cycle,
            ),
            followers: followers
                .into_iter()
                .map(|spec| Following {
                    spec,
                    origin: 0,
                    target: 0,
                })
                .collect(),
            segment,
            dt_us,
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

    /// The faults that stopped the line (until [`FollowLine::reset`]).
    pub fn faults(&self) -> &[LineFault] {
        self.supervisor.faults()
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

    /// Disables the drives.
    pub fn stop(&mut self) {
        self.supervisor.stop(&mut self.segment);
    }

    /// Clears the faults; the line is stopped afterwards.
    ///
    /// # Errors
    /// [`FollowError::State`] unless the line is faulted.
    pub fn reset(&mut self) -> Result<(), FollowError> {
        self.supervisor
            .reset(&mut self.segment)
            .map_err(FollowError::State)
    }

    /// One cycle: `emitted[y]` is the total of signed pulses output `y`
    /// has emitted since power-up (ecam-plc's `Hardware::emitted`);
    /// targets out, exchange, status in, fault check.
    ///
    /// # Errors
    /// [`FollowError::Bus`] when the exchange itself fails.
    pub fn cycle(
        &mut self,
        emitted: &[i64; PULSE_OUTPUTS as usize],
    ) -> Result<FollowReport, FollowError> {
        let mut targets = Vec::with_capacity(self.followers.len());
        for f in &mut self.followers {
            let pulses = emitted
                .get(usize::from(f.spec.output))
                .copied()
                .unwrap_or(0);
            let counts = f.spec.scale.counts(pulses);
            let Some(drive) = self.segment.drives_mut().get_mut(f.spec.drive) else {
                continue;
            };
            if !drive.status().enabled {
                // Not following yet: the target is where the drive stands.
                f.origin = drive.actual().saturating_sub(counts);
            }
            f.target = f.origin.saturating_add(counts);
            drive.command(f.target, self.dt_us);
            targets.push(f.target);
        }
        let bus = self.segment.exchange()?;
        let seen = self.supervisor.after_exchange(&mut self.segment, &bus);
        Ok(FollowReport {
            bus,
            targets,
            new_faults: seen.new_faults,
        })
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
