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

use crate::follow::{Follower, Scale, ScaleError};
use crate::line::Master;
use crate::rt::RtConfig;
use crate::segment::{MAX_DRIVES, SegmentConfig};
use crate::startup::{DriveSetup, SdoValue, SdoWrite};
use crate::supervisor::default_max_lost_cycles;

/// Stop time when the file gives none, ms.
pub const DEFAULT_STOP_MS: u32 = 500;

/// The timing keys both file kinds share, checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Timing {
    /// Cycle time, µs.
    pub cycle_us: u32,
    /// How long a cycle waits for its reply, µs (omitted: 80 % of the
    /// cycle).
    pub reply_timeout_us: Option<u32>,
    /// How long before SYNC0 the frame is due, µs (omitted: half a
    /// cycle).
    pub sync0_shift_us: Option<u32>,
    /// Lost cycles in a row that fault the line (omitted: 100 ms worth).
    pub max_lost_cycles: Option<u32>,
    /// Deceleration time of a stop, ms.
    pub stop_ms: Option<u32>,
}

impl Timing {
    fn check(&self) -> Result<(), ConfigError> {
        if !(MIN_CYCLE_US..=MAX_CYCLE_US).contains(&self.cycle_us) {
            return Err(ConfigError::Cycle(self.cycle_us));
        }
        for (key, value) in [
            ("reply_timeout_us", self.reply_timeout_us),
            ("sync0_shift_us", self.sync0_shift_us),
        ] {
            if let Some(v) = value {
                if v == 0 || v >= self.cycle_us {
                    return Err(ConfigError::WithinCycle {
                        key,
                        value: v,
                        cycle_us: self.cycle_us,
                    });
                }
            }
        }
        if self.max_lost_cycles == Some(0) {
            return Err(ConfigError::MaxLost);
        }
        Ok(())
    }

    /// The segment's timing.
    pub fn segment(&self) -> SegmentConfig {
        let cycle = Duration::from_micros(u64::from(self.cycle_us));
        let mut config = SegmentConfig::for_cycle(cycle);
        if let Some(us) = self.reply_timeout_us {
            config.reply_timeout = Duration::from_micros(u64::from(us));
        }
        if let Some(us) = self.sync0_shift_us {
            config.sync0_shift = Duration::from_micros(u64::from(us));
        }
        config
    }

    /// Lost cycles in a row that fault the line.
    pub fn max_lost_cycles(&self) -> u32 {
        self.max_lost_cycles.unwrap_or_else(|| {
            default_max_lost_cycles(Duration::from_micros(u64::from(self.cycle_us)))
        })
    }

    /// Deceleration time of a stop.
    pub fn stop(&self) -> Duration {
        Duration::from_millis(u64::from(self.stop_ms.unwrap_or(DEFAULT_STOP_MS)))
    }
}

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

/// The CoE type of a start-up SDO's value.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SdoType {
    /// UNSIGNED8.
    U8,
    /// INTEGER8.
    I8,
    /// UNSIGNED16.
    U16,
    /// INTEGER16.
    I16,
    /// UNSIGNED32.
    U32,
    /// INTEGER32.
    I32,
}

/// One `[[drive.sdo]]`: an object the master writes in PRE-OP.
#[derive(Clone, Debug, Deserialize, PartialEq, Eq)]
#[serde(deny_unknown_fields)]
pub struct SdoSpec {
    /// Object index (e.g. `0x6065`).
    pub index: u16,
    /// Sub-index (omit: 0).
    #[serde(default)]
    pub sub_index: u8,
    /// The CoE type the object has.
    #[serde(rename = "type")]
    pub kind: SdoType,
    /// The value.
    pub value: i64,
}

/// Objects ecam writes itself at start-up (the PDO assignment and
/// mapping, the mode): a start-up list may not write them.
fn reserved(index: u16) -> bool {
    matches!(index, 0x1600..=0x17FF | 0x1A00..=0x1BFF | 0x1C12 | 0x1C13 | 0x6060)
}

impl SdoSpec {
    /// The write, its value checked against the type.
    ///
    /// # Errors
    /// [`ConfigError::SdoValue`] or [`ConfigError::SdoReserved`].
    pub fn write(&self) -> Result<SdoWrite, ConfigError> {
        if reserved(self.index) {
            return Err(ConfigError::SdoReserved(self.index));
        }
        let v = self.value;
        let bad = || ConfigError::SdoValue {
            index: self.index,
            sub_index: self.sub_index,
            value: v,
            kind: self.kind,
        };
        let value = match self.kind {
            SdoType::U8 => SdoValue::U8(u8::try_from(v).map_err(|_| bad())?),
            SdoType::I8 => SdoValue::I8(i8::try_from(v).map_err(|_| bad())?),
            SdoType::U16 => SdoValue::U16(u16::try_from(v).map_err(|_| bad())?),
            SdoType::I16 => SdoValue::I16(i16::try_from(v).map_err(|_| bad())?),
            SdoType::U32 => SdoValue::U32(u32::try_from(v).map_err(|_| bad())?),
            SdoType::I32 => SdoValue::I32(i32::try_from(v).map_err(|_| bad())?),
        };
        Ok(SdoWrite {
            index: self.index,
            sub_index: self.sub_index,
            value,
        })
    }
}

/// One `[[drive]]`: what a drive must be and what it gets at start-up.
#[derive(Clone, Debug, Deserialize, PartialEq, Eq)]
#[serde(deny_unknown_fields)]
pub struct DriveSpec {
    /// Position in the line.
    pub drive: usize,
    /// Vendor id it must report (SII; omit: any).
    pub vendor_id: Option<u32>,
    /// Product code it must report (omit: any).
    pub product_code: Option<u32>,
    /// Revision it must report (omit: any).
    pub revision: Option<u32>,
    /// Objects written in PRE-OP, in order.
    #[serde(default)]
    pub sdo: Vec<SdoSpec>,
}

/// Checks the `[[drive]]` entries and turns them into set-ups.
fn setups(drives: &[DriveSpec]) -> Result<Vec<DriveSetup>, ConfigError> {
    let mut out: Vec<DriveSetup> = Vec::with_capacity(drives.len());
    for d in drives {
        if d.drive >= MAX_DRIVES {
            return Err(ConfigError::Drive(d.drive));
        }
        if out.iter().any(|s| s.position == d.drive) {
            return Err(ConfigError::DescribedTwice(d.drive));
        }
        out.push(DriveSetup {
            position: d.drive,
            vendor_id: d.vendor_id,
            product_code: d.product_code,
            revision: d.revision,
            sdo: d.sdo.iter().map(SdoSpec::write).collect::<Result<_, _>>()?,
        });
    }
    Ok(out)
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
    /// How long a cycle waits for its reply, µs.
    pub reply_timeout_us: Option<u32>,
    /// How long before SYNC0 the frame is due, µs.
    pub sync0_shift_us: Option<u32>,
    /// Lost cycles in a row that fault the line.
    pub max_lost_cycles: Option<u32>,
    /// Deceleration time of a stop, ms.
    pub stop_ms: Option<u32>,
    /// The cams.
    #[serde(rename = "axis")]
    pub axes: Vec<AxisSpec>,
    /// What the drives must be and what they get at start-up.
    #[serde(rename = "drive", default)]
    pub drives: Vec<DriveSpec>,
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
    /// Two entries on one drive.
    DriveTwice(usize),
    /// No `[[output]]`.
    NoOutputs,
    /// A pulse output other than Y0–Y3.
    Output(String),
    /// A scale that cannot be.
    Scale(ScaleError),
    /// A time that must lie within the cycle does not.
    WithinCycle {
        /// The key.
        key: &'static str,
        /// Its value, µs.
        value: u32,
        /// The cycle, µs.
        cycle_us: u32,
    },
    /// `max_lost_cycles = 0`.
    MaxLost,
    /// Two `[[drive]]` entries for one drive.
    DescribedTwice(usize),
    /// A start-up SDO value outside its type.
    SdoValue {
        /// Object index.
        index: u16,
        /// Sub-index.
        sub_index: u8,
        /// The value given.
        value: i64,
        /// The type given.
        kind: SdoType,
    },
    /// A start-up SDO on an object ecam writes itself.
    SdoReserved(u16),
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
            Self::DriveTwice(d) => write!(f, "two entries command drive {d}"),
            Self::NoOutputs => {
                f.write_str("no [[output]]: map at least one pulse output to a drive")
            }
            Self::Output(y) => write!(
                f,
                "pulse = \"{y}\": the pulse outputs are Y0, Y1, Y2 and Y3"
            ),
            Self::Scale(e) => e.fmt(f),
            Self::WithinCycle {
                key,
                value,
                cycle_us,
            } => write!(
                f,
                "{key} = {value} must be above 0 and below the cycle ({cycle_us} µs)"
            ),
            Self::MaxLost => f.write_str("max_lost_cycles = 0: at least one cycle must be allowed"),
            Self::DescribedTwice(d) => write!(f, "two [[drive]] entries describe drive {d}"),
            Self::SdoValue {
                index,
                sub_index,
                value,
                kind,
            } => write!(
                f,
                "[[drive.sdo]] {index:#06x}:{sub_index:02x}: value {value} does not fit type \"{}\"",
                format!("{kind:?}").to_lowercase()
            ),
            Self::SdoReserved(index) => write!(
                f,
                "[[drive.sdo]] {index:#06x}: ecam writes the PDO assignment and mapping and the mode itself"
            ),
        }
    }
}

impl std::error::Error for ConfigError {}

/// Checks the timing and the priority both file kinds carry.
fn check_timing(timing: Timing, fifo_priority: Option<u8>) -> Result<(), ConfigError> {
    timing.check()?;
    match fifo_priority {
        Some(p) if !(1..=99).contains(&p) => Err(ConfigError::Priority(p)),
        _ => Ok(()),
    }
}

fn rt_config(cycle_us: u32, fifo_priority: Option<u8>, cpu: Option<usize>) -> RtConfig {
    RtConfig {
        period: Duration::from_micros(u64::from(cycle_us)),
        fifo_priority,
        cpu,
    }
}

impl LineConfig {
    /// The timing keys.
    pub fn timing(&self) -> Timing {
        Timing {
            cycle_us: self.cycle_us,
            reply_timeout_us: self.reply_timeout_us,
            sync0_shift_us: self.sync0_shift_us,
            max_lost_cycles: self.max_lost_cycles,
            stop_ms: self.stop_ms,
        }
    }

    /// Parses and checks a configuration.
    pub fn parse(text: &str) -> Result<Self, ConfigError> {
        let config: Self = toml::from_str(text).map_err(|e| ConfigError::Syntax(e.to_string()))?;
        check_timing(config.timing(), config.fifo_priority)?;
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
        setups(&config.drives)?;
        Ok(config)
    }

    /// The `[[drive]]` entries as start-up set-ups (checked by
    /// [`LineConfig::parse`]; an entry that fails here was not parsed).
    pub fn setups(&self) -> Vec<DriveSetup> {
        setups(&self.drives).unwrap_or_default()
    }

    /// The cycle time.
    pub fn cycle(&self) -> Duration {
        Duration::from_micros(u64::from(self.cycle_us))
    }

    /// The real-time settings.
    pub fn rt(&self) -> RtConfig {
        rt_config(self.cycle_us, self.fifo_priority, self.cpu)
    }
}

/// One `[[output]]` of an `ecam serve --ethercat` file: a PLC pulse
/// output and the drive that follows it.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// The pulse output, `"Y0"` … `"Y3"`.
    pub pulse: String,
    /// Drive position that follows it.
    pub drive: usize,
    /// Drive counts per pulse as `[num, den]` (omit: `[1, 1]`).
    pub scale: Option<[i64; 2]>,
}

impl OutputSpec {
    /// The follower this entry describes.
    ///
    /// # Errors
    /// [`ConfigError::Output`] or [`ConfigError::Scale`].
    pub fn follower(&self) -> Result<Follower, ConfigError> {
        let output = match self.pulse.trim() {
            "Y0" | "y0" => 0,
            "Y1" | "y1" => 1,
            "Y2" | "y2" => 2,
            "Y3" | "y3" => 3,
            other => return Err(ConfigError::Output(other.to_string())),
        };
        let scale = match self.scale {
            Some([num, den]) => Scale::new(num, den).map_err(ConfigError::Scale)?,
            None => Scale::ONE,
        };
        Ok(Follower {
            output,
            drive: self.drive,
            scale,
        })
    }
}

/// An `ecam serve --ethercat` file: the segment, and which drive follows
/// which of the PLC's pulse outputs.
///
/// ```toml
/// interface = "enp3s0"
/// cycle_us = 1000
/// fault_relay = "M100"     # on while a drive fault holds the line
/// running_relay = "M101"   # on while every drive follows its output
///
/// [[output]]
/// pulse = "Y0"
/// drive = 0
/// scale = [25, 9]          # drive counts per pulse
/// ```
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FollowConfig {
    /// Network interface (omit when the command line emulates drives).
    pub interface: Option<String>,
    /// Cycle time, µs: also the PLC's step (a whole number of scans).
    pub cycle_us: u32,
    /// `SCHED_FIFO` priority 1–99.
    pub fifo_priority: Option<u8>,
    /// CPU to pin the cycle thread to.
    pub cpu: Option<usize>,
    /// How long a cycle waits for its reply, µs.
    pub reply_timeout_us: Option<u32>,
    /// How long before SYNC0 the frame is due, µs.
    pub sync0_shift_us: Option<u32>,
    /// Lost cycles in a row that fault the line.
    pub max_lost_cycles: Option<u32>,
    /// Deceleration time of a stop, ms.
    pub stop_ms: Option<u32>,
    /// Enable the drives when the server starts (default); with `false`
    /// they wait for the enable coil or `POST /api/ethercat/enable`.
    #[serde(default = "yes")]
    pub enable_at_start: bool,
    /// An M relay the server holds on while the line is faulted, so the
    /// program can react (stop its cams, raise an alarm).
    pub fault_relay: Option<String>,
    /// An M relay the server holds on while every drive follows.
    pub running_relay: Option<String>,
    /// The outputs and their drives.
    #[serde(rename = "output", default)]
    pub outputs: Vec<OutputSpec>,
    /// What the drives must be and what they get at start-up.
    #[serde(rename = "drive", default)]
    pub drives: Vec<DriveSpec>,
}

fn yes() -> bool {
    true
}

impl FollowConfig {
    /// The timing keys.
    pub fn timing(&self) -> Timing {
        Timing {
            cycle_us: self.cycle_us,
            reply_timeout_us: self.reply_timeout_us,
            sync0_shift_us: self.sync0_shift_us,
            max_lost_cycles: self.max_lost_cycles,
            stop_ms: self.stop_ms,
        }
    }

    /// Parses and checks a configuration.
    ///
    /// # Errors
    /// [`ConfigError`] for bad syntax, timing, outputs, scales or drives.
    pub fn parse(text: &str) -> Result<Self, ConfigError> {
        let config: Self = toml::from_str(text).map_err(|e| ConfigError::Syntax(e.to_string()))?;
        check_timing(config.timing(), config.fifo_priority)?;
        if config.outputs.is_empty() {
            return Err(ConfigError::NoOutputs);
        }
        let mut used = Vec::new();
        for o in &config.outputs {
            let follower = o.follower()?;
            if follower.drive >= MAX_DRIVES {
                return Err(ConfigError::Drive(follower.drive));
            }
            if used.contains(&follower.drive) {
                return Err(ConfigError::DriveTwice(follower.drive));
            }
            used.push(follower.drive);
        }
        setups(&config.drives)?;
        Ok(config)
    }

    /// The `[[drive]]` entries as start-up set-ups.
    pub fn setups(&self) -> Vec<DriveSetup> {
        setups(&self.drives).unwrap_or_default()
    }

    /// The followers, in file order (each checked by [`FollowConfig::parse`]).
    ///
    /// # Errors
    /// As [`OutputSpec::follower`].
    pub fn followers(&self) -> Result<Vec<Follower>, ConfigError> {
        self.outputs.iter().map(OutputSpec::follower).collect()
    }

    /// The cycle time.
    pub fn cycle(&self) -> Duration {
        Duration::from_micros(u64::from(self.cycle_us))
    }

    /// The real-time settings.
    pub fn rt(&self) -> RtConfig {
        rt_config(self.cycle_us, self.fifo_priority, self.cpu)
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
        // Lost-cycle limit: 100 ms worth by default.
        assert_eq!(c.timing().max_lost_cycles(), 100);
        assert_eq!(c.timing().segment().sync0_shift, Duration::from_micros(500));
        assert_eq!(c.timing().stop(), Duration::from_millis(500));
    }

    const FOLLOW: &str = r#"
cycle_us = 500
fault_relay = "M100"
[[output]]
pulse = "Y0"
drive = 1
scale = [25, 9]
[[output]]
pulse = "Y0"
drive = 0
"#;

    #[test]
    fn parses_a_following_line() {
        let c = FollowConfig::parse(FOLLOW).unwrap();
        assert!(c.enable_at_start);
        assert_eq!(c.fault_relay.as_deref(), Some("M100"));
        let f = c.followers().unwrap();
        assert_eq!(f[0].drive, 1);
        assert_eq!(f[0].scale, Scale::new(25, 9).unwrap());
        assert_eq!(f[1].output, 0);
        assert_eq!(f[1].scale, Scale::ONE);
        assert_eq!(c.rt().period, Duration::from_micros(500));
    }

    #[test]
    fn refuses_a_bad_following_line() {
        let bad =
            |from: &str, to: &str| FollowConfig::parse(&FOLLOW.replace(from, to)).unwrap_err();
        assert_eq!(
            bad("\"Y0\"\ndrive = 1", "\"Y4\"\ndrive = 1"),
            ConfigError::Output("Y4".into())
        );
        assert_eq!(
            bad("[25, 9]", "[25, 0]"),
            ConfigError::Scale(ScaleError::Denominator(0))
        );
        assert_eq!(
            bad("[25, 9]", "[0, 9]"),
            ConfigError::Scale(ScaleError::Zero)
        );
        assert_eq!(bad("drive = 1", "drive = 0"), ConfigError::DriveTwice(0));
        assert_eq!(bad("drive = 1", "drive = 99"), ConfigError::Drive(99));
        assert_eq!(bad("cycle_us = 500", "cycle_us = 1"), ConfigError::Cycle(1));
        assert_eq!(
            bad("cycle_us = 500", "cycle_us = 500\nsync0_shift_us = 500"),
            ConfigError::WithinCycle {
                key: "sync0_shift_us",
                value: 500,
                cycle_us: 500
            }
        );
        assert_eq!(
            bad("cycle_us = 500", "cycle_us = 500\nmax_lost_cycles = 0"),
            ConfigError::MaxLost
        );
        assert!(matches!(bad("scale", "scales"), ConfigError::Syntax(_)));
        assert_eq!(
            FollowConfig::parse("cycle_us = 1000").unwrap_err(),
            ConfigError::NoOutputs
        );
        assert!(
            ConfigError::Output("Y7".into())
                .to_string()
                .contains("Y0, Y1, Y2 and Y3")
        );
    }

    #[test]
    fn drives_are_described_with_identity_and_start_up_sdos() {
        let text = format!(
            "{EXAMPLE}
[[drive]]
drive = 1
vendor_id = 0x00000002
product_code = 0x4543414D
revision = 1
sdo = [
    {{ index = 0x6065, type = \"u32\", value = 2000 }},
    {{ index = 0x60C2, sub_index = 2, type = \"i8\", value = -3 }},
]
"
        );
        let c = LineConfig::parse(&text).unwrap();
        let setups = c.setups();
        assert_eq!(setups.len(), 1);
        assert_eq!(setups[0].position, 1);
        assert_eq!(setups[0].vendor_id, Some(2));
        assert_eq!(setups[0].product_code, Some(0x4543_414D));
        assert_eq!(
            setups[0].sdo[1],
            SdoWrite {
                index: 0x60C2,
                sub_index: 2,
                value: SdoValue::I8(-3)
            }
        );
        let bad = |from: &str, to: &str| LineConfig::parse(&text.replace(from, to)).unwrap_err();
        assert_eq!(
            bad("value = 2000", "value = -1"),
            ConfigError::SdoValue {
                index: 0x6065,
                sub_index: 0,
                value: -1,
                kind: SdoType::U32
            }
        );
        assert!(
            bad("value = 2000", "value = -1")
                .to_string()
                .contains("does not fit type \"u32\"")
        );
        assert_eq!(
            bad("index = 0x6065", "index = 0x1C12"),
            ConfigError::SdoReserved(0x1C12)
        );
        assert!(matches!(bad("\"u32\"", "\"f32\""), ConfigError::Syntax(_)));
        assert!(matches!(
            bad("revision", "revisions"),
            ConfigError::Syntax(_)
        ));
        let twice = format!("{text}[[drive]]\ndrive = 1\n");
        assert_eq!(
            LineConfig::parse(&twice).unwrap_err(),
            ConfigError::DescribedTwice(1)
        );
        assert_eq!(
            FollowConfig::parse(&format!("{FOLLOW}[[drive]]\ndrive = 0\nproduct_code = 7\n"))
                .unwrap()
                .setups()[0]
                .product_code,
            Some(7)
        );
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
