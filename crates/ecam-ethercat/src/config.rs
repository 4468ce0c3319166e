//! The segment configuration file (TOML): the interface, the cycle, the
//! real-time wishes and which cam drives which drive from which master.
//!
//! ```toml
//! interface = "enp3s0"   # the NIC the drives hang on
//! cycle_us = 1000        # process-data cycle = SYNC0 period
//! fifo_priority = 80     # SCHED_FIFO priority (omit: normal scheduling)
//! cpu = 1                # pin the cycle to this CPU (omit: any)
//! master_speed = 7       # virtual master counts per cycle
//!
//! [[axis]]
//! drive = 0              # position in the line, 0 = next to the master
//! coupling = "repeat"    # repeat | periodic | normal
//! [axis.table]
//! generator = "rotary-cut"
//!
//! [[axis]]
//! drive = 1
//! master_drive = 0       # master = drive 0's actual position
//! [axis.table]
//! points = [[0, 0], [1000, 4000]]
//! ```
//!
//! The `[axis.table]` keys are those of a scenario's `[table]` (points,
//! uniform, file, expr or generator); the command line resolves them.

use std::time::Duration;

use ecam_engine::{AxisConfig, Coupling, SlaveAlign};
use serde::Deserialize;

use crate::line::Master;
use crate::rt::RtConfig;
use crate::segment::MAX_DRIVES;

/// Shortest cycle accepted, µs.
pub const MIN_CYCLE_US: u32 = 50;
/// Longest cycle accepted, µs.
pub const MAX_CYCLE_US: u32 = 100_000;

/// How a cam repeats.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum CouplingKind {
    /// Each cycle adds the table's stroke (a rotary knife).
    #[default]
    Repeat,
    /// The table repeats on the same slave range.
    Periodic,
    /// One pass over the table, held at its ends.
    Normal,
}

/// One `[[axis]]`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AxisSpec {
    /// Drive position the cam commands.
    pub drive: usize,
    /// Drive whose actual position is the master (omit: virtual master).
    pub master_drive: Option<usize>,
    /// How the cam repeats.
    #[serde(default)]
    pub coupling: CouplingKind,
    /// Where the cam table comes from.
    pub table: toml::Table,
}

impl AxisSpec {
    /// The master this axis follows.
    pub fn master(&self) -> Master {
        match self.master_drive {
            Some(position) => Master::DriveActual { position },
            None => Master::Virtual,
        }
    }

    /// The engine configuration: the chosen coupling, and the slave
    /// aligned to where the drive stands when the cam starts (a drive is
    /// never asked to jump).
    pub fn axis_config(&self) -> AxisConfig {
        AxisConfig {
            coupling: match self.coupling {
                CouplingKind::Repeat => Coupling::Repeat { min_stroke: 1 },
                CouplingKind::Periodic => Coupling::Periodic,
                CouplingKind::Normal => Coupling::Normal,
            },
            slave_align: SlaveAlign::Relative,
            ..AxisConfig::default()
        }
    }
}

/// A whole configuration file.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LineConfig {
    /// Network interface (omit when the command line emulates drives).
    pub interface: Option<String>,
    /// Cycle time, µs.
    pub cycle_us: u32,
    /// `SCHED_FIFO` priority 1–99.
    pub fifo_priority: Option<u8>,
    /// CPU to pin the cycle thread to.
    pub cpu: Option<usize>,
    /// Virtual master counts per cycle.
    #[serde(default)]
    pub master_speed: i64,
    /// The cams.
    #[serde(rename = "axis")]
    pub axes: Vec<AxisSpec>,
}

/// A configuration that cannot run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ConfigError {
    /// Not valid TOML or a key of the wrong type or unknown.
    Syntax(String),
    /// Cycle time out of range.
    Cycle(u32),
    /// Priority out of 1..=99.
    Priority(u8),
    /// No `[[axis]]`.
    NoAxes,
    /// A drive position beyond what a segment carries.
    Drive(usize),
    /// Two axes on one drive.
    DriveTwice(usize),
}

impl core::fmt::Display for ConfigError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Syntax(e) => write!(f, "{e}"),
            Self::Cycle(c) => {
                write!(
                    f,
                    "cycle_us = {c} is out of range ({MIN_CYCLE_US}..={MAX_CYCLE_US})"
                )
            }
            Self::Priority(p) => write!(f, "fifo_priority = {p} is out of range (1..=99)"),
            Self::NoAxes => f.write_str("no [[axis]]: name at least one cam and its drive"),
            Self::Drive(d) => write!(
                f,
                "drive {d} is beyond the {MAX_DRIVES} drives a segment carries"
            ),
            Self::DriveTwice(d) => write!(f, "two [[axis]] entries command drive {d}"),
        }
    }
}

impl std::error::Error for ConfigError {}

impl LineConfig {
    /// Parses and checks a configuration.
    pub fn parse(text: &str) -> Result<Self, ConfigError> {
        let config: Self = toml::from_str(text).map_err(|e| ConfigError::Syntax(e.to_string()))?;
        if !(MIN_CYCLE_US..=MAX_CYCLE_US).contains(&config.cycle_us) {
            return Err(ConfigError::Cycle(config.cycle_us));
        }
        if let Some(p) = config.fifo_priority {
            if !(1..=99).contains(&p) {
                return Err(ConfigError::Priority(p));
            }
        }
        if config.axes.is_empty() {
            return Err(ConfigError::NoAxes);
        }
        let mut used = Vec::new();
        for a in &config.axes {
            for d in [Some(a.drive), a.master_drive].into_iter().flatten() {
                if d >= MAX_DRIVES {
                    return Err(ConfigError::Drive(d));
                }
            }
            if used.contains(&a.drive) {
                return Err(ConfigError::DriveTwice(a.drive));
            }
            used.push(a.drive);
        }
        Ok(config)
    }

    /// The cycle time.
    pub fn cycle(&self) -> Duration {
        Duration::from_micros(u64::from(self.cycle_us))
    }

    /// The real-time settings.
    pub fn rt(&self) -> RtConfig {
        RtConfig {
            period: self.cycle(),
            fifo_priority: self.fifo_priority,
            cpu: self.cpu,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const EXAMPLE: &str = r#"
interface = "eth1"
cycle_us = 1000
master_speed = 7
[[axis]]
drive = 0
[axis.table]
generator = "rotary-cut"
[[axis]]
drive = 1
master_drive = 0
coupling = "periodic"
[axis.table]
points = [[0, 0], [1000, 4000]]
"#;

    #[test]
    fn parses_the_example() {
        let c = LineConfig::parse(EXAMPLE).unwrap();
        assert_eq!(c.interface.as_deref(), Some("eth1"));
        assert_eq!(c.cycle(), Duration::from_millis(1));
        assert_eq!(c.axes.len(), 2);
        assert_eq!(c.axes[0].master(), Master::Virtual);
        assert_eq!(c.axes[1].master(), Master::DriveActual { position: 0 });
        assert_eq!(c.axes[1].axis_config().coupling, Coupling::Periodic);
        assert_eq!(c.rt().fifo_priority, None);
    }

    #[test]
    fn refuses_bad_input() {
        let bad = |from: &str, to: &str| LineConfig::parse(&EXAMPLE.replace(from, to)).unwrap_err();
        assert_eq!(
            bad("cycle_us = 1000", "cycle_us = 10"),
            ConfigError::Cycle(10)
        );
        assert_eq!(
            bad("drive = 1\n", "drive = 0\n"),
            ConfigError::DriveTwice(0)
        );
        assert_eq!(
            bad("master_drive = 0", "master_drive = 64"),
            ConfigError::Drive(64)
        );
        assert!(matches!(
            bad("cycle_us", "cycle_usx"),
            ConfigError::Syntax(_)
        ));
        assert!(matches!(
            bad("\"periodic\"", "\"sideways\""),
            ConfigError::Syntax(_)
        ));
        assert_eq!(
            bad("master_speed = 7", "fifo_priority = 0"),
            ConfigError::Priority(0)
        );
        assert_eq!(
            LineConfig::parse("cycle_us = 1000\naxis = []").unwrap_err(),
            ConfigError::NoAxes
        );
    }
}
