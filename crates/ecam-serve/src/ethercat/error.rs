//! Why `serve --ethercat` could not bring its segment up or start its
//! threads, in the words the operator sees.

use std::fmt;

use ecam_ethercat::EthercatError;
use ecam_ethercat::config::ConfigError;
use ecam_ethercat::follow::FollowError;
use ecam_ethercat::link::NoTransport;

/// A failed bring-up of the server's fieldbus.
#[derive(Debug)]
pub enum BusError {
    /// The configuration file could not be read.
    Read {
        /// The file, as given.
        file: String,
        /// Why.
        error: std::io::Error,
    },
    /// The configuration is invalid.
    Config {
        /// The file.
        file: String,
        /// What is wrong in it.
        error: ConfigError,
    },
    /// The bus cycle is not a whole number of PLC scan periods.
    CycleNotWholeScans {
        /// The file.
        file: String,
        /// Its `cycle_us`.
        cycle_us: u32,
        /// The PLC's scan period (`--scan-us`).
        scan_us: u32,
    },
    /// `fault_relay` or `running_relay` names no M relay below M8000.
    Relay {
        /// The file.
        file: String,
        /// The key (`fault_relay`, `running_relay`).
        key: &'static str,
        /// The name given.
        name: String,
    },
    /// Neither an interface nor `--emulated` is given.
    NoInterface {
        /// The file.
        file: String,
        /// The transport's own words.
        error: NoTransport,
    },
    /// The segment did not come up.
    Segment(EthercatError),
    /// The followers do not fit the segment.
    Follow {
        /// The file.
        file: String,
        /// What does not fit.
        error: FollowError,
    },
    /// A thread could not be started.
    Thread {
        /// Which one.
        what: &'static str,
        /// Why.
        error: std::io::Error,
    },
}

impl fmt::Display for BusError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read { file, error } => write!(f, "cannot read {file}: {error}"),
            Self::Config { file, error } => write!(f, "{file}: {error}"),
            Self::CycleNotWholeScans {
                file,
                cycle_us,
                scan_us,
            } => write!(
                f,
                "{file}: cycle_us = {cycle_us} is not a whole number of scan periods \
                 (--scan-us {scan_us}): each bus cycle runs the PLC for exactly one cycle time"
            ),
            Self::Relay { file, key, name } => write!(
                f,
                "{file}: {key} = \"{name}\": name an M relay below M8000 (e.g. \"M100\")"
            ),
            Self::NoInterface { file, error } => write!(f, "{file}: {error}"),
            Self::Segment(error) => write!(f, "{error}"),
            Self::Follow { file, error } => write!(f, "{file}: {error}"),
            Self::Thread { what, error } => write!(f, "cannot start {what}: {error}"),
        }
    }
}

// The message already carries the cause's words (as the binary printed
// them before), so no `source`: a chain would say them twice.
impl std::error::Error for BusError {}

impl From<EthercatError> for BusError {
    fn from(error: EthercatError) -> Self {
        Self::Segment(error)
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    #[test]
    fn a_missing_file_is_named_with_its_cause_once() {
        let Some(error) =
            super::super::bring_up(Path::new("/nonexistent/line.toml"), Some(1), 1000).err()
        else {
            panic!("a missing file brought a bus up");
        };
        let text = error.to_string();
        assert!(
            text.starts_with("cannot read /nonexistent/line.toml: "),
            "{text}"
        );
        assert!(std::error::Error::source(&error).is_none());
    }
}
