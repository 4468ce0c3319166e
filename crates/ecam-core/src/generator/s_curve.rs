//! S-type acceleration/deceleration table (ECAMTBX K0/K1): a point-to-point
//! move of `P1` pulses at up to `P2` Hz with given ramp times.
//!
//! # The master is time
//! The table's master is a time base: **one master count is one millisecond
//! when the master axis runs at 1 kHz** ([`MASTER_HZ`]). This is the LX3VE
//! manual's own reading of its example ("when master axis's frequency is 1k,
//! it takes 100 ms for 100 pulse acceleration"), and it makes the ramp times
//! (ms) and the "uniform time" output (documented in pulses) the same
//! number. Driving the master faster or slower plays the move faster or
//! slower in proportion. A slave velocity ratio of `k` pulses per master count
//! is `k·1000` Hz at the nominal master rate.
//!
//! # Geometry
//! Accelerate from rest to the top speed in `P4` ms, cruise, decelerate to
//! rest in `P5` ms; the ramps follow an [`AccelCurve`] (S-type by default).
//! A ramp covers half its top speed times its duration, so the cruise time is
//! `(P1 − V·(P4 + P5)/2) / V`. When the move is too short for that, the
//! acceleration *rates* are kept (`P4`/`P5` are the times from rest to full
//! speed) and the peak is lowered to `√(2·P1·V/(P4 + P5))`: a triangular S
//! move, whose reached speed is reported in `P11`. The total time is rounded
//! up to whole master counts by slowing the whole move down slightly, so the
//! table ends exactly at `P1` pulses on a whole master count.
//!
//! # Outputs
//! - `P8` ([`Generated::last_section_master`]): master counts of the last
//!   section *of the move*, the deceleration phase;
//! - `P9` ([`Generated::last_section_slave`]): pulses covered in it;
//! - `P10` ([`Generated::uniform_time`]): master counts at constant speed;
//! - `P11` ([`Generated::max_speed_hz`]): the highest speed the sampled table
//!   actually commands (its steepest section, at the 1 kHz master).
//!
//! ```
//! use ecam_core::CamCurve;
//! use ecam_core::generator::s_curve::{Params, generate};
//!
//! // The manual's worked example: 10000 pulses, 50 kHz, 100 ms / 100 ms, resolution 200.
//! let g = generate(&Params::default())?;
//! assert_eq!(g.table.slave_last(), 10000);
//! assert_eq!(g.table.master_last(), 300); // 100 ms up, 100 ms cruise, 100 ms down
//! assert_eq!((g.uniform_time, g.max_speed_hz), (100, 50000));
//! # Ok::<(), ecam_core::TableError>(())
//! ```

use super::accel_curve::AccelCurve;
use super::design_curve::DesignCurve;
use super::motion_path::{Path, Ramp};
use super::sampling::{peak_ratio, sample};
use crate::{CamPoint, PointTable, TableError};

/// Master rate at which one master count is one millisecond.
pub const MASTER_HZ: u32 = 1000;
/// Highest `P2` the manual allows, in Hz.
pub const MAX_SPEED_HZ: u32 = 150_000;
/// Longest ramp time the manual allows (`P4`, `P5`), in ms.
pub const MAX_RAMP_MS: u16 = 32_767;
/// Fewest points (`P6`).
pub const MIN_RESOLUTION: u16 = 51;
/// Most points (`P6`).
pub const MAX_RESOLUTION: u16 = 512;

/// ECAMTBX K0/K1 parameters. `Default` is the manual's calculation case
/// (the register table gives no defaults). The serde form uses the keys of
/// [`schema::S_CURVE`](super::schema::S_CURVE); what it leaves out keeps
/// the default.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Params {
    /// `P1`: pulses to move; negative moves backwards. At most ±2³¹−1 (a 32-bit register).
    #[serde(rename = "pulses")]
    pub total_pulses: i64,
    /// `P2`: top speed in Hz, 1 to 150000.
    #[serde(rename = "max_speed")]
    pub max_speed_hz: u32,
    /// `P4`: time from rest to top speed, ms, 0 to 32767.
    pub accel_ms: u16,
    /// `P5`: time from top speed to rest, ms, 0 to 32767.
    pub decel_ms: u16,
    /// `P6`: points in the table, 51 to 512 (fewer when the move lasts fewer master counts).
    pub resolution: u16,
    /// Ramp shape; the register interface always means S-type
    /// ([`AccelCurve::UniformAcceleration`]).
    pub curve: AccelCurve,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            total_pulses: 10_000,
            max_speed_hz: 50_000,
            accel_ms: 100,
            decel_ms: 100,
            resolution: 200,
            curve: AccelCurve::UniformAcceleration,
        }
    }
}

/// An S-curve table and the instruction's outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct Generated {
    /// The table: master in ms at 1 kHz, slave in pulses, from (0, 0) to (duration, P1).
    pub table: PointTable,
    /// Always `None`: a point-to-point move has no synchronised zone.
    pub sync: Option<(i64, i64)>,
    /// Master counts of the whole move (ms at 1 kHz).
    pub duration: i64,
    /// `P8`: master counts of the deceleration phase.
    pub last_section_master: i64,
    /// `P9`: pulses covered while decelerating (signed like `P1`).
    pub last_section_slave: i64,
    /// `P10`: master counts at constant speed.
    pub uniform_time: i64,
    /// `P11`: highest speed the table commands, Hz at 1 kHz master.
    pub max_speed_hz: i64,
    /// The exact move the table samples (master in ms at 1 kHz; mirrored
    /// for a negative `P1`; every point within ½ pulse of it).
    pub design: DesignCurve,
}

fn check(params: &Params) -> Result<(), TableError> {
    let bad = |name, reason| Err(TableError::Parameter { name, reason });
    if params.total_pulses == 0 || params.total_pulses.unsigned_abs() > i32::MAX as u64 {
        return bad(
            "total pulses (P1)",
            "must be non-zero and fit a 32-bit register",
        );
    }
    if params.max_speed_hz == 0 || params.max_speed_hz > MAX_SPEED_HZ {
        return bad("max speed (P2)", "must be between 1 and 150000 Hz");
    }
    if params.accel_ms > MAX_RAMP_MS {
        return bad("acceleration time (P4)", "must be between 0 and 32767 ms");
    }
    if params.decel_ms > MAX_RAMP_MS {
        return bad("deceleration time (P5)", "must be between 0 and 32767 ms");
    }
    if !(MIN_RESOLUTION..=MAX_RESOLUTION).contains(&params.resolution) {
        return bad("resolution (P6)", "must be between 51 and 512");
    }
    Ok(())
}

/// The planned move at one speed limit.
struct Plan {
    path: Path,
    duration: i64,
    decel: f64,
    decel_distance: f64,
    uniform: f64,
}

fn plan(params: &Params, distance: f64, speed: f64) -> Plan {
    let (ta, td) = (f64::from(params.accel_ms), f64::from(params.decel_ms));
    let ramps_distance = 0.5 * speed * (ta + td);
    let (peak, ta, td, tu) = if distance >= ramps_distance {
        (speed, ta, td, (distance - ramps_distance) / speed)
    } else {
        // Keep the rates: shorter ramps to a lower peak (triangular S).
        let peak = libm::sqrt(2.0 * distance * speed / (ta + td));
        let k = peak / speed;
        (peak, ta * k, td * k, 0.0)
    };
    let total = ta + tu + td;
    let duration = libm::ceil(total).max(1.0);
    // Stretch the move onto whole master counts: times grow, speeds drop.
    let stretch = duration / total;
    let (ta, tu, td, peak) = (ta * stretch, tu * stretch, td * stretch, peak / stretch);
    let mut path = Path::starting_at(0.0, 0.0);
    path.push(
        Ramp {
            v0: 0.0,
            v1: peak,
            len: ta,
        },
        params.curve,
    );
    path.push_constant(peak, tu);
    path.push(
        Ramp {
            v0: peak,
            v1: 0.0,
            len: td,
        },
        params.curve,
    );
    Plan {
        path,
        // `total` ≤ 2·2³¹ ms (P1 ≤ 2³¹ at ≥ 1 Hz plus two ramps): the cast is exact.
        duration: duration as i64,
        decel: td,
        decel_distance: 0.5 * peak * td,
        uniform: tu,
    }
}

/// Generates the S-curve table.
///
/// # Errors
/// [`TableError::Parameter`] (6781) for a parameter out of its range.
pub fn generate(params: &Params) -> Result<Generated, TableError> {
    check(params)?;
    let distance = params.total_pulses.unsigned_abs() as f64;
    let limit = f64::from(params.max_speed_hz) / f64::from(MASTER_HZ);
    let mut speed = limit;
    let mut attempt = 0;
    loop {
        let plan = plan(params, distance, speed);
        let points = usize::from(params.resolution).min(
            usize::try_from(plan.duration)
                .unwrap_or(usize::MAX)
                .saturating_add(1),
        );
        let end = CamPoint::new(plan.duration, params.total_pulses.unsigned_abs() as i64);
        let table = sample(
            &plan.path,
            plan.duration,
            points,
            &[CamPoint::new(0, 0), end],
        )?;
        let peak = peak_ratio(&table);
        // Rounding to whole pulses can make a section a little steeper than
        // the smooth move; plan again a little slower (a few times at most:
        // a very slow move cannot avoid whole-pulse steps).
        attempt += 1;
        if peak > limit + 1e-9 && attempt < 4 && speed - (peak - limit) > 0.0 {
            speed -= peak - limit + 1e-9 * limit;
            continue;
        }
        let sign = params.total_pulses.signum();
        let table = if sign < 0 { mirrored(&table)? } else { table };
        let design = DesignCurve::new(plan.path, plan.duration);
        let design = if sign < 0 { design.mirrored() } else { design };
        return Ok(Generated {
            table,
            sync: None,
            duration: plan.duration,
            last_section_master: libm::round(plan.decel) as i64,
            last_section_slave: sign * libm::round(plan.decel_distance) as i64,
            uniform_time: libm::round(plan.uniform) as i64,
            max_speed_hz: libm::round(peak * f64::from(MASTER_HZ)) as i64,
            design,
        });
    }
}

fn mirrored(table: &PointTable) -> Result<PointTable, TableError> {
    PointTable::new(
        table
            .points()
            .iter()
            .map(|p| CamPoint::new(p.master, -p.slave))
            .collect(),
    )
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::CamCurve;

    #[test]
    fn manual_example_phases() {
        let g = generate(&Params::default()).unwrap();
        assert_eq!(g.duration, 300);
        assert_eq!((g.last_section_master, g.last_section_slave), (100, 2500));
        assert_eq!(g.table.slave_last(), 10000);
        assert!(g.table.points().len() <= 200);
    }

    #[test]
    fn short_move_lowers_the_peak() {
        let p = Params {
            total_pulses: 1000,
            ..Params::default()
        };
        let g = generate(&p).unwrap();
        // √(2·1000·50/200) = 22.36 pulses/ms.
        assert_eq!(g.uniform_time, 0);
        assert!(
            (g.max_speed_hz - 22_360).abs() < 1_000,
            "{}",
            g.max_speed_hz
        );
        assert_eq!(g.table.slave_last(), 1000);
    }

    #[test]
    fn negative_move_mirrors() {
        let g = generate(&Params {
            total_pulses: -10_000,
            ..Params::default()
        })
        .unwrap();
        assert_eq!(g.table.slave_last(), -10_000);
        assert_eq!(g.last_section_slave, -2500);
    }
}
