//! A table's peaks in machine units: what `ecam table show --master-speed`
//! adds, and which curve each figure is of.
//!
//! A point table is run as straight sections between whole-pulse points,
//! so its acceleration is estimated at the joints, and rounding each point
//! moves that estimate by up to
//! [`rounding_ripple`](ecam_core::table::derivatives::rounding_ripple): on
//! short sections this ripple dwarfs the design's acceleration. Both
//! figures are true, of different things: the design's is what the motion
//! law asks of the drive, the table's what its points command. Each is
//! labelled with its [`Source`].

use serde::Serialize;

/// Peak velocity and acceleration of one curve, in pulses per count (²).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Peaks {
    /// Peak |slave velocity / master velocity|, pulses/count.
    pub peak_velocity: f64,
    /// Peak |d²slave/dmaster²|, pulses/count².
    pub peak_acceleration: f64,
}

/// Whose peaks a figure reports, as the user reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The design values a generator wrote next to each point.
    DesignColumns,
    /// The straight sections between a point table's points.
    SampledTable,
    /// A segment profile's motion laws, evaluated exactly.
    ProfileLaws,
    /// An evenly spaced table's straight pieces.
    UniformPieces,
}

impl Source {
    /// What the velocity figure is, in words.
    pub fn velocity(self) -> &'static str {
        match self {
            Self::DesignColumns => "design: the file's velocity column",
            Self::SampledTable => "table as sampled: steepest section",
            Self::ProfileLaws => "the motion laws, exact",
            Self::UniformPieces => "steepest piece",
        }
    }

    /// What the acceleration figure is, in words.
    pub fn acceleration(self) -> &'static str {
        match self {
            Self::DesignColumns => "design: the file's acceleration column",
            Self::SampledTable => {
                "table as sampled: velocity change at a joint over the mean section length"
            }
            Self::ProfileLaws => "the motion laws, exact",
            Self::UniformPieces => {
                "straight pieces: velocity change at a joint over the piece length"
            }
        }
    }

    /// `design` or `table as sampled`.
    pub fn short(self) -> &'static str {
        match self {
            Self::DesignColumns | Self::ProfileLaws => "design",
            Self::SampledTable | Self::UniformPieces => "table as sampled",
        }
    }
}

/// A slave length unit for speeds in unit/s.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Unit {
    /// Millimetres (a linear slave: a flying saw, a feed).
    Mm,
    /// Degrees (a rotary slave: a knife drum).
    Deg,
}

impl Unit {
    /// Every unit's name, as flags and forms spell them.
    pub const NAMES: [&'static str; 2] = ["mm", "deg"];

    /// How the unit is written: `mm`, `deg`.
    pub fn symbol(self) -> &'static str {
        match self {
            Self::Mm => "mm",
            Self::Deg => "deg",
        }
    }

    /// The unit called `name` ([`Unit::NAMES`]).
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "mm" => Some(Self::Mm),
            "deg" => Some(Self::Deg),
            _ => None,
        }
    }
}

/// The machine a table runs on, for figures in physical units: the
/// master's speed and, optionally, the slave's unit and its size per pulse.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Machine {
    /// Master speed, counts per second (the master encoder's frequency).
    pub master_speed: Option<f64>,
    /// The slave's unit and slave units per slave pulse.
    pub unit: Option<(Unit, f64)>,
}

/// The peaks of one curve at a master speed, in physical units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AtSpeed {
    /// Whose peaks: `design` or `table as sampled`.
    pub of: &'static str,
    /// Master speed, counts/s.
    pub master_hz: f64,
    /// Peak slave speed, pulses/s (Hz).
    pub slave_hz: f64,
    /// Peak slave acceleration, pulses/s² (Hz/s).
    pub slave_hz_per_s: f64,
    /// The slave unit, when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit: Option<Unit>,
    /// Slave units per pulse, when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit_per_pulse: Option<f64>,
    /// Peak slave speed in unit/s, when a unit is given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slave_speed: Option<f64>,
    /// Peak slave acceleration in unit/s², when a unit is given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slave_acceleration: Option<f64>,
}

impl Machine {
    /// `peaks` at this master speed; `None` without one.
    ///
    /// A constant master speed `f` turns a ratio `v` (pulses/count) into
    /// `v · f` pulses/s and a curvature `a` (pulses/count²) into `a · f²`
    /// pulses/s² (the chain rule with dm/dt = f, d²m/dt² = 0).
    ///
    /// ```
    /// use ecam_design::{Machine, Peaks, Source, Unit};
    ///
    /// let machine = Machine { master_speed: Some(1000.0), unit: Some((Unit::Mm, 0.01)) };
    /// let peaks = Peaks { peak_velocity: 2.0, peak_acceleration: 0.001 };
    /// let at = machine.at_speed(&peaks, Source::ProfileLaws).unwrap();
    /// assert_eq!((at.slave_hz, at.slave_hz_per_s), (2000.0, 1000.0));
    /// assert_eq!((at.slave_speed, at.slave_acceleration), (Some(20.0), Some(10.0)));
    /// ```
    pub fn at_speed(&self, peaks: &Peaks, source: Source) -> Option<AtSpeed> {
        let f = self.master_speed?;
        let slave_hz = peaks.peak_velocity * f;
        let slave_hz_per_s = peaks.peak_acceleration * f * f;
        let per = self.unit.map(|(_, per)| per);
        Some(AtSpeed {
            of: source.short(),
            master_hz: f,
            slave_hz,
            slave_hz_per_s,
            unit: self.unit.map(|(unit, _)| unit),
            unit_per_pulse: per,
            slave_speed: per.map(|p| slave_hz * p),
            slave_acceleration: per.map(|p| slave_hz_per_s * p),
        })
    }
}

/// A number with at most six decimals, trailing zeros dropped (`-0` is 0).
pub fn short(v: f64) -> String {
    let text = format!("{v:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}
