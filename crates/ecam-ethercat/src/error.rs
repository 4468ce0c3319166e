//! What can go wrong on the fieldbus side.

use std::time::Duration;

use crate::pdo::PdoSizeError;
use crate::startup::StartupError;

/// Errors of the EtherCAT layer.
#[derive(Debug)]
pub enum EthercatError {
    /// ethercrab reported an error (bring-up or exchange).
    Bus(ethercrab::error::Error),
    /// The network interface could not be opened.
    Interface {
        /// Interface name as given.
        name: String,
        /// Why.
        source: std::io::Error,
    },
    /// A thread could not be started.
    Io(std::io::Error),
    /// No drive answered on the segment.
    NoDrives,
    /// A drive's process data is not the CSP mapping.
    NotCsp {
        /// Position in the line (0 = next to the master).
        position: usize,
        /// The name the drive reports.
        name: String,
        /// Input bytes it maps.
        inputs: usize,
        /// Output bytes it maps.
        outputs: usize,
    },
    /// Process data of the wrong size.
    Pdo(PdoSizeError),
    /// The drives did not all reach OP in time.
    NotOp,
    /// Bringing the segment up again found another number of drives.
    DriveCount {
        /// Drives the line was built for.
        expected: usize,
        /// Drives that answered now.
        found: usize,
    },
    /// The cycle time is zero or longer than a second.
    CycleTime(Duration),
    /// Frame storage could not be set up.
    Storage,
    /// A drive was refused at start-up (PRE-OP configuration over CoE).
    Startup {
        /// Position in the line.
        position: usize,
        /// The name it reports.
        name: String,
        /// Why.
        error: StartupError,
    },
    /// The bring-up stopped on a panic in ethercrab (it panics on an
    /// emergency message in the middle of one of its SDO transfers).
    MailboxInterrupted,
}

impl core::fmt::Display for EthercatError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Bus(e) => write!(f, "EtherCAT: {e}"),
            Self::Interface { name, source } => write!(
                f,
                "cannot open network interface {name:?}: {source} (raw sockets need root or CAP_NET_RAW)"
            ),
            Self::Io(e) => write!(f, "cannot start the EtherCAT thread: {e}"),
            Self::NoDrives => {
                f.write_str("no EtherCAT drive answered (check the cable and the interface)")
            }
            Self::NotCsp {
                position,
                name,
                inputs,
                outputs,
            } => write!(
                f,
                "drive {position} ({name}) maps {outputs} output and {inputs} input bytes; CSP needs {} and {}",
                crate::pdo::OUTPUTS_LEN,
                crate::pdo::INPUTS_LEN
            ),
            Self::Pdo(e) => e.fmt(f),
            Self::NotOp => f.write_str("not every drive reached OP in time"),
            Self::DriveCount { expected, found } => write!(
                f,
                "bringing the segment up again found {found} drives, the line has {expected}"
            ),
            Self::CycleTime(c) => write!(f, "cycle time {c:?} out of range (above 0, at most 1 s)"),
            Self::Storage => f.write_str("EtherCAT frame storage could not be set up"),
            Self::Startup {
                position,
                name,
                error,
            } => {
                if name.is_empty() {
                    write!(f, "drive {position} {error}")
                } else {
                    write!(f, "drive {position} ({name}) {error}")
                }
            }
            Self::MailboxInterrupted => f.write_str(
                "the bring-up stopped on a panic in ethercrab (a drive's emergency message in the middle of an SDO transfer does that); try again",
            ),
        }
    }
}

impl std::error::Error for EthercatError {}

impl From<ethercrab::error::Error> for EthercatError {
    fn from(e: ethercrab::error::Error) -> Self {
        Self::Bus(e)
    }
}

impl From<std::io::Error> for EthercatError {
    fn from(e: std::io::Error) -> Self {
        Self::Io(e)
    }
}

impl From<PdoSizeError> for EthercatError {
    fn from(e: PdoSizeError) -> Self {
        Self::Pdo(e)
    }
}
