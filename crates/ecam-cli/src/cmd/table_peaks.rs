//! The peaks `ecam table show` reports: the design's and the sampled
//! table's, each labelled, and the same in machine units when the user gives
//! a master speed (and a slave unit).
//!
//! A point table is run as straight sections between whole-pulse points, so
//! its acceleration is estimated at the joints, and rounding each point to a
//! whole pulse moves that estimate by up to `2/L²` (`L` the section length in
//! counts): on short sections this ripple dwarfs the design's acceleration.
//! Both figures are true, of different things: the design's is what the
//! motion law asks of the drive, the table's what its points command.

use std::io::Write;

use serde::Serialize;

/// Peak velocity and acceleration of one curve, in pulses per count (²).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Peaks {
    /// Peak |slave velocity / master velocity|, pulses/count.
    pub peak_velocity: f64,
    /// Peak |d²slave/dmaster²|, pulses/count².
    pub peak_acceleration: f64,
}

/// Whose peaks a line reports, as the user reads it.
#[derive(Clone, Copy, Debug)]
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
    fn velocity(self) -> &'static str {
        match self {
            Self::DesignColumns => "design: the file's velocity column",
            Self::SampledTable => "table as sampled: steepest section",
            Self::ProfileLaws => "the motion laws, exact",
            Self::UniformPieces => "steepest piece",
        }
    }

    fn acceleration(self) -> &'static str {
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

    fn short(self) -> &'static str {
        match self {
            Self::DesignColumns | Self::ProfileLaws => "design",
            Self::SampledTable | Self::UniformPieces => "table as sampled",
        }
    }
}

/// A slave length unit for speeds in unit/s.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Unit {
    /// Millimetres (a linear slave: a flying saw, a feed).
    Mm,
    /// Degrees (a rotary slave: a knife drum).
    Deg,
}

impl Unit {
    /// How the unit is written: `mm`, `deg`.
    pub fn symbol(self) -> &'static str {
        match self {
            Self::Mm => "mm",
            Self::Deg => "deg",
        }
    }
}

/// `--master-speed`, `--units`, `--unit-per-pulse`: the machine the table
/// runs on, for peaks in physical units.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct MachineArgs {
    /// Master speed in counts per second (the master encoder's frequency,
    /// Hz): adds the slave's peak speed in Hz (pulses/s) and acceleration in
    /// Hz/s.
    #[arg(long, value_name = "COUNTS_PER_S", value_parser = positive)]
    pub master_speed: Option<f64>,
    /// The slave's length unit, for speeds in mm/s or deg/s (needs
    /// --unit-per-pulse and --master-speed).
    #[arg(
        long,
        value_enum,
        value_name = "UNIT",
        requires = "unit_per_pulse",
        requires = "master_speed"
    )]
    pub units: Option<Unit>,
    /// Slave units per slave pulse: 0.01 for 100 pulses per mm, 0.036 for
    /// 10000 pulses per turn in degrees (needs --units).
    #[arg(long, value_name = "UNITS", value_parser = positive, requires = "units")]
    pub unit_per_pulse: Option<f64>,
}

fn positive(text: &str) -> Result<f64, String> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|e| format!("{text:?} is not a number: {e}"))?;
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(format!("{text} must be a number above 0"))
    }
}

/// The peaks of one curve at a master speed, in physical units.
#[derive(Clone, Copy, Debug, Serialize)]
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

impl MachineArgs {
    /// `peaks` at this master speed; `None` without `--master-speed`.
    ///
    /// A constant master speed `f` turns a ratio `v` (pulses/count) into
    /// `v · f` pulses/s and a curvature `a` (pulses/count²) into `a · f²`
    /// pulses/s² (the chain rule with dm/dt = f, d²m/dt² = 0).
    pub fn at_speed(&self, peaks: &Peaks, source: Source) -> Option<AtSpeed> {
        let f = self.master_speed?;
        let slave_hz = peaks.peak_velocity * f;
        let slave_hz_per_s = peaks.peak_acceleration * f * f;
        let per = self.unit_per_pulse.filter(|_| self.units.is_some());
        Some(AtSpeed {
            of: source.short(),
            master_hz: f,
            slave_hz,
            slave_hz_per_s,
            unit: self.units,
            unit_per_pulse: per,
            slave_speed: per.map(|p| slave_hz * p),
            slave_acceleration: per.map(|p| slave_hz_per_s * p),
        })
    }
}

/// The peak lines of `ecam table show`: `design` (when one is known) first,
/// then the table's; a note when rounding makes the table's acceleration
/// much larger than the design's; the physical lines when asked for.
pub fn write(
    out: &mut impl Write,
    design: Option<(&Peaks, Source)>,
    table: (&Peaks, Source),
    shortest_section: Option<i64>,
    machine: &MachineArgs,
) -> std::io::Result<()> {
    let rows: Vec<(&Peaks, Source)> = design.into_iter().chain([table]).collect();
    for (k, (peaks, source)) in rows.iter().enumerate() {
        let label = if k == 0 { "peak velocity:" } else { "" };
        writeln!(
            out,
            "{label:<19}{} pulses/count ({})",
            short(peaks.peak_velocity),
            source.velocity()
        )?;
    }
    for (k, (peaks, source)) in rows.iter().enumerate() {
        let label = if k == 0 { "peak acceleration:" } else { "" };
        writeln!(
            out,
            "{label:<19}{} pulses/count² ({})",
            short(peaks.peak_acceleration),
            source.acceleration()
        )?;
    }
    if let (Some((design, _)), Some(length)) = (design, shortest_section) {
        let ratio = table.0.peak_acceleration / design.peak_acceleration;
        if design.peak_acceleration > 0.0 && ratio > RIPPLE_NOTE_RATIO {
            let length = length.max(1) as f64;
            writeln!(
                out,
                "note:              the table's acceleration is {ratio:.1} times the design's: its points are \
                 rounded to whole pulses, which moves a joint's estimate by up to 2/L² (L: section \
                 length; {} for the shortest, {} counts). The drive follows the table, the motion \
                 law asks for the design's value.",
                short(2.0 / (length * length)),
                short(length),
            )?;
        }
    }
    for (peaks, source) in &rows {
        let Some(at) = machine.at_speed(peaks, *source) else {
            break;
        };
        let unit = at.unit.map(Unit::symbol).unwrap_or_default();
        let speed = at
            .slave_speed
            .map(|s| format!(" = {} {unit}/s", short(s)))
            .unwrap_or_default();
        let accel = at
            .slave_acceleration
            .map(|a| format!(" = {} {unit}/s²", short(a)))
            .unwrap_or_default();
        writeln!(
            out,
            "slave speed:       {} Hz{speed} ({} at master {} counts/s)",
            short(at.slave_hz),
            at.of,
            short(at.master_hz)
        )?;
        writeln!(
            out,
            "slave accel.:      {} Hz/s{accel} ({})",
            short(at.slave_hz_per_s),
            at.of
        )?;
    }
    Ok(())
}

/// The table's acceleration above this multiple of the design's gets the
/// rounding note.
const RIPPLE_NOTE_RATIO: f64 = 1.5;

/// A number with at most six decimals, trailing zeros dropped.
pub fn short(v: f64) -> String {
    format!("{v:.6}")
        .trim_end_matches('0')
        .trim_end_matches('.')
        .to_string()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn text(design: Option<Peaks>, table: Peaks, machine: MachineArgs) -> String {
        let mut out = Vec::new();
        write(
            &mut out,
            design.as_ref().map(|d| (d, Source::DesignColumns)),
            (&table, Source::SampledTable),
            Some(8),
            &machine,
        )
        .unwrap();
        String::from_utf8(out).unwrap()
    }

    const NONE: MachineArgs = MachineArgs {
        master_speed: None,
        units: None,
        unit_per_pulse: None,
    };

    #[test]
    fn the_ripple_is_labelled_as_the_tables_and_explained() {
        let design = Peaks {
            peak_velocity: 1.666667,
            peak_acceleration: 0.004177,
        };
        let table = Peaks {
            peak_velocity: 1.666667,
            peak_acceleration: 0.03125,
        };
        let t = text(Some(design), table, NONE);
        assert!(
            t.contains("peak acceleration: 0.004177 pulses/count² (design"),
            "{t}"
        );
        assert!(t.contains("0.03125 pulses/count² (table as sampled"), "{t}");
        assert!(
            t.contains("note:") && t.contains("2/L²") && t.contains("8 counts"),
            "{t}"
        );
        assert!(!t.contains("slave speed"), "{t}");
    }

    #[test]
    fn machine_units_follow_the_chain_rule() {
        let peaks = Peaks {
            peak_velocity: 2.0,
            peak_acceleration: 0.001,
        };
        let machine = MachineArgs {
            master_speed: Some(1000.0),
            units: Some(Unit::Mm),
            unit_per_pulse: Some(0.01),
        };
        let at = machine.at_speed(&peaks, Source::ProfileLaws).unwrap();
        assert_eq!(at.slave_hz, 2000.0);
        assert_eq!(at.slave_hz_per_s, 1000.0);
        assert_eq!(at.slave_speed, Some(20.0));
        assert_eq!(at.slave_acceleration, Some(10.0));
        let t = text(None, peaks, machine);
        assert!(t.contains("slave speed:       2000 Hz = 20 mm/s"), "{t}");
        assert!(t.contains("slave accel.:      1000 Hz/s = 10 mm/s²"), "{t}");
    }

    #[test]
    fn speeds_are_positive_numbers() {
        assert!(positive("0").is_err());
        assert!(positive("-3").is_err());
        assert!(positive("inf").is_err());
        assert_eq!(positive("1e3").unwrap(), 1000.0);
    }
}
