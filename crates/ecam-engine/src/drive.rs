//! The drive interface: where an axis' commanded position goes each cycle
//! and what comes back.
//!
//! A [`CamAxis`](crate::CamAxis) computes the commanded slave position; an
//! [`AxisDrive`] carries it to the motor. Today's step/direction output is
//! one ([`PulseDrive`]); a CiA 402 servo drive in cyclic synchronous
//! position mode is another (crate `ecam-ethercat`). The split is the one a
//! fieldbus imposes: outputs are written before the bus exchange
//! ([`AxisDrive::command`]) and inputs are read after it
//! ([`AxisDrive::status`]), so the two are separate calls.

use crate::pulse::PulseOutput;

/// A fault a drive reports, with the drive's own code where it has one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DriveFault {
    /// The drive stopped with a fault; `code` is its error code (CiA 402
    /// object 0x603F, 0 when the drive gives none).
    Drive {
        /// The drive's error code.
        code: u16,
    },
    /// The drive cannot be reached or its data did not arrive this cycle
    /// (a fieldbus working-counter error, a cable pulled).
    Communication,
    /// The drive was asked to enable and did not reach "operation
    /// enabled" in time (a fault that a reset did not clear, a power stage
    /// without mains, a safe-torque-off input open).
    EnableTimeout,
}

impl core::fmt::Display for DriveFault {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Drive { code } => write!(f, "drive fault, error code {code:#06x}"),
            Self::Communication => f.write_str("drive not reachable (communication lost)"),
            Self::EnableTimeout => f.write_str("drive did not enable in time"),
        }
    }
}

/// What a drive reports after a cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DriveStatus {
    /// Position the motor is at, in the axis' counts.
    pub actual: i64,
    /// Commanded minus actual, in counts (for a pulse output: pulses still
    /// owed; for a servo drive: its following error).
    pub following_error: i64,
    /// The drive accepts commands and moves (CiA 402 "operation enabled";
    /// a pulse output is always enabled).
    pub enabled: bool,
    /// The fault the drive reports, if any.
    pub fault: Option<DriveFault>,
}

/// One axis' output: a commanded position per cycle in, status back.
pub trait AxisDrive {
    /// Hands over this cycle's commanded position (counts, absolute).
    /// `dt_us` is the time since the last cycle.
    fn command(&mut self, commanded: i64, dt_us: u32);

    /// The drive's status after the last exchange.
    fn status(&self) -> DriveStatus;
}

/// Today's step/direction output as a drive: emits the change of the
/// commanded position under a frequency ceiling, carrying what cannot go
/// out as a backlog (the same generator [`CamAxis`](crate::CamAxis) uses).
/// Its "actual position" is what has been emitted; it never faults.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PulseDrive {
    output: PulseOutput,
    commanded: i64,
    max_frequency_hz: u32,
    last_pulses: i64,
}

impl PulseDrive {
    /// A pulse output standing at `position`, at most `max_frequency_hz`
    /// pulses per second.
    pub fn new(position: i64, max_frequency_hz: u32) -> Self {
        Self {
            output: PulseOutput::at(position),
            commanded: position,
            max_frequency_hz,
            last_pulses: 0,
        }
    }

    /// Pulses emitted by the last [`AxisDrive::command`], signed.
    pub fn last_pulses(&self) -> i64 {
        self.last_pulses
    }
}

impl AxisDrive for PulseDrive {
    fn command(&mut self, commanded: i64, dt_us: u32) {
        self.commanded = commanded;
        self.last_pulses = self
            .output
            .step(commanded, true, self.max_frequency_hz, dt_us);
    }

    fn status(&self) -> DriveStatus {
        DriveStatus {
            actual: self.output.emitted,
            following_error: self.output.backlog(self.commanded),
            enabled: true,
            fault: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pulse_drive_reports_backlog_as_following_error() {
        // 10 kHz at 1 ms cycles: 10 pulses per cycle.
        let mut drive = PulseDrive::new(100, 10_000);
        assert_eq!(drive.status().actual, 100);
        drive.command(125, 1000);
        let status = drive.status();
        assert_eq!(drive.last_pulses(), 10);
        assert_eq!(status.actual, 110);
        assert_eq!(status.following_error, 15);
        assert!(status.enabled);
        assert_eq!(status.fault, None);
        drive.command(125, 1000);
        drive.command(125, 1000);
        assert_eq!(drive.status().actual, 125);
        assert_eq!(drive.status().following_error, 0);
        drive.command(120, 1000);
        assert_eq!(drive.last_pulses(), -5);
    }

    #[test]
    fn pulse_drive_through_the_trait() {
        fn run(drive: &mut dyn AxisDrive, targets: &[i64]) -> i64 {
            for &t in targets {
                drive.command(t, 100);
            }
            drive.status().actual
        }
        let mut drive = PulseDrive::new(0, 200_000);
        // 200 kHz at 100 µs: 20 pulses per cycle at most.
        assert_eq!(run(&mut drive, &[5, 30, 30]), 30);
    }

    #[test]
    fn fault_messages() {
        use std::string::ToString;
        assert_eq!(
            DriveFault::Drive { code: 0x7500 }.to_string(),
            "drive fault, error code 0x7500"
        );
        assert!(
            DriveFault::Communication
                .to_string()
                .contains("communication")
        );
    }
}
