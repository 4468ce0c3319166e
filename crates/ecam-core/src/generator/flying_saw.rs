//! Flying saw table, ECAMTBX K101.
//!
//! The saw carriage (the slave) rides along a rail beside material fed at
//! constant speed (the master). Each cut it starts from rest, catches up with
//! the material, moves with it while cutting (the sync zone), stops, and runs
//! back to where it started. The manual builds one cut cycle from two tables
//! of half the cut length each: a *forward* table (`P2 > 0`) and a *return*
//! table (`P2 < 0`, marked with `H1000` in `P6`'s high word). The return
//! stroke covers exactly the forward stroke backwards — the manual's
//! "positive area equals negative area" — so the saw ends where it started.
//!
//! # Parameters
//! As the rotary cut: `P1` master counts of the table, `P2` stroke in slave
//! pulses (negative: return), `P3` sync length in slave pulses, `P4` slave
//! pulses per master pulse in the sync zone (the demo's "slave pulses per mm
//! over master pulses per mm" = 3π), `P5` the ratio cap, `P6` low word the
//! [`AccelCurve`](super::AccelCurve), high word the [`CamPlacement`] (plus `H1000` for return),
//! `P7` points in the table.
//!
//! # Geometry
//! From rest, one ramp up to the sync ratio `r`, the sync zone (one straight
//! section, a pulse or two longer than `P3` if needed to make the ratio exact
//! on the integer grid), one ramp down to rest, and a dwell for the rest of
//! `P1`. Each ramp from or to rest covers `r/2` times its length, so the
//! stroke left after the sync zone, split evenly between the two ramps, fixes
//! their lengths: `2·(|P2| − Δs)/(2r)` each. If ramps plus sync zone do not
//! fit in `P1`, the table is [`TableError::Infeasible`]. Placement moves the
//! motion inside the table: leftCAM starts it at once (the dwell is at the
//! end), rightCAM ends it at the table's end, midCAMall centres it.
//! midCAMbegin/midCAMend only mean something for a rotary knife and are
//! refused here.
//!
//! The return table is the forward table mirrored (`P3` and `P4` "same" in
//! the manual): the saw runs back at the same profile; its constant-speed
//! part is not a sync zone, so its [`Generated::sync`] is `None`.
//!
//! ```
//! use ecam_core::CamCurve;
//! use ecam_core::generator::flying_saw::{Params, generate_pair};
//!
//! // The manual's demo: 1750 master, ±2000 slave, 667 sync at 3π, max 10.
//! let p = Params { master_length: 1750, slave_length: 2000, sync_length: 667,
//!                  sync_ratio: 3.0 * std::f64::consts::PI, max_ratio: 10.0, ..Params::default() };
//! let (forward, back) = generate_pair(&p)?;
//! assert_eq!(forward.table.slave_last(), 2000);
//! assert_eq!(back.table.slave_last(), -2000);
//! # Ok::<(), ecam_core::TableError>(())
//! ```

use super::design_curve::DesignCurve;
use super::motion_path::{Path, Ramp};
use super::placement::CamPlacement;
use super::sampling::{peak_ratio, sample};
use super::sync_zone::choose;
use crate::{CamPoint, PointTable, TableError};

pub use super::cut_params::{MAX_RESOLUTION, MIN_RESOLUTION};
/// `P6` high-word flag of the return table (the manual's `H1000`).
pub const RETURN_FLAG: u16 = 0x1000;

/// Which half of the cut cycle a table is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Stroke {
    /// Following the material (`P2 > 0`).
    #[default]
    Forward,
    /// Running back (`P2 < 0`, `H1000`).
    Return,
}

/// The words a user reads (`ecam table gen fly-saw` prints them).
impl core::fmt::Display for Stroke {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::Forward => "forward (following the material)",
            Self::Return => "return (running back)",
        })
    }
}

/// Splits a `P6` high word into the placement and the stroke flag.
///
/// # Errors
/// [`TableError::Parameter`] (6781) for an unknown placement code or other flag bits.
pub fn decode_cam_word(high_word: u16) -> Result<(CamPlacement, Stroke), TableError> {
    let stroke = if high_word & RETURN_FLAG != 0 {
        Stroke::Return
    } else {
        Stroke::Forward
    };
    Ok((CamPlacement::from_code(high_word & !RETURN_FLAG)?, stroke))
}

/// ECAMTBX K101 parameters: the block both cut generators share.
pub type Params = super::cut_params::CutParams;

/// A flying-saw table and what was made of the parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Generated {
    /// From (0, 0) to (`P1`, `P2`), starting and ending at rest.
    pub table: PointTable,
    /// Master range of the sync zone; `None` for the return stroke.
    pub sync: Option<(i64, i64)>,
    /// Master range at constant speed (the sync zone, or its mirror on return).
    pub constant_zone: (i64, i64),
    /// Slave range of that zone.
    pub constant_slave: (i64, i64),
    /// Ratio in that zone as sampled (negative on return).
    pub sync_ratio: f64,
    /// Forward or return.
    pub stroke: Stroke,
    /// Steepest section of the table, in absolute value (≤ `P5`).
    pub peak_ratio: f64,
    /// The exact motion the table samples (mirrored on return, like the
    /// table; every point within ½ pulse of it).
    pub design: DesignCurve,
}

fn check(p: &Params) -> Result<(), TableError> {
    let bad = |name, reason| Err(TableError::Parameter { name, reason });
    let max = i64::from(i32::MAX);
    p.check_common()?;
    if p.slave_length == 0 || p.slave_length.unsigned_abs() > max as u64 {
        return bad(
            "slave length (P2)",
            "must be non-zero and fit a 32-bit register",
        );
    }
    if !(1..p.slave_length.abs() - 1).contains(&p.sync_length) {
        return bad(
            "sync length (P3)",
            "must be at least 1 pulse and at least 2 less than the stroke",
        );
    }
    if matches!(
        p.placement,
        CamPlacement::MidCamBegin | CamPlacement::MidCamEnd
    ) {
        return bad(
            "cam curve (P6 high word)",
            "must be leftCAM, midCAMall or rightCAM for a flying saw",
        );
    }
    p.check_ratio_order()
}

/// Generates one flying-saw table (forward for `P2 > 0`, return for `P2 < 0`).
///
/// # Errors
/// [`TableError::Parameter`] (6781) for a parameter out of range;
/// [`TableError::Infeasible`] (6781) when ramps and sync zone do not fit in
/// `P1` or the table would exceed `P5`; [`TableError::SectionCount`] (6783)
/// when the resolution is too low for the pieces of the motion.
pub fn generate(p: &Params) -> Result<Generated, TableError> {
    check(p)?;
    let stroke = p.slave_length.abs();
    let zone = choose(p.sync_length, p.sync_ratio, p.master_length)?;
    let r = zone.ratio();
    if r > p.max_ratio {
        return Err(TableError::Infeasible {
            reason: "the sync ratio rounded onto whole pulses is above the max ratio (P5)",
        });
    }
    let ramps_slave = stroke - zone.slave;
    if ramps_slave < 2 {
        return Err(TableError::Infeasible {
            reason: "the sync zone leaves no stroke to accelerate and decelerate in",
        });
    }
    let accel_slave = ramps_slave / 2;
    let decel_slave = ramps_slave - accel_slave;
    let accel = 2.0 * accel_slave as f64 / r;
    let decel = 2.0 * decel_slave as f64 / r;
    // The sync zone must start on a whole master count.
    let earliest = libm::ceil(accel);
    let latest = libm::floor((p.master_length - zone.master) as f64 - decel);
    if earliest > latest {
        return Err(TableError::Infeasible {
            reason: "ramps and sync zone do not fit in the master length: lengthen P1 or raise the sync ratio",
        });
    }
    let sync_master = match p.placement {
        CamPlacement::RightCam => latest,
        CamPlacement::MidCamAll => {
            libm::round(0.5 * ((p.master_length - zone.master) as f64 - decel + accel))
                .clamp(earliest, latest)
        }
        _ => earliest,
    };
    let mut path = Path::starting_at(0.0, 0.0);
    path.push_constant(0.0, sync_master - accel);
    path.push(
        Ramp {
            v0: 0.0,
            v1: r,
            len: accel,
        },
        p.accel_curve,
    );
    path.push_constant(r, zone.master as f64);
    path.push(
        Ramp {
            v0: r,
            v1: 0.0,
            len: decel,
        },
        p.accel_curve,
    );
    path.push_constant(
        0.0,
        p.master_length as f64 - (sync_master + zone.master as f64 + decel),
    );

    // `sync_master` lies in [0, P1], so the cast is exact.
    let start = CamPoint::new(sync_master as i64, accel_slave);
    let end = CamPoint::new(start.master + zone.master, start.slave + zone.slave);
    let pinned = [
        CamPoint::new(0, 0),
        CamPoint::new(p.master_length, stroke),
        start,
        end,
    ];
    let table = sample(&path, p.master_length, usize::from(p.resolution), &pinned)?;
    let peak = peak_ratio(&table);
    if peak > p.max_ratio {
        return Err(TableError::Infeasible {
            reason: "the table rounded onto whole pulses exceeds the max ratio (P5): raise it or lower the resolution",
        });
    }
    let design = DesignCurve::new(path, p.master_length);
    let (table, design, direction, sign) = if p.slave_length < 0 {
        let mirrored = table
            .points()
            .iter()
            .map(|q| CamPoint::new(q.master, -q.slave))
            .collect();
        (
            PointTable::new(mirrored)?,
            design.mirrored(),
            Stroke::Return,
            -1,
        )
    } else {
        (table, design, Stroke::Forward, 1)
    };
    Ok(Generated {
        table,
        sync: (direction == Stroke::Forward).then_some((start.master, end.master)),
        constant_zone: (start.master, end.master),
        constant_slave: (sign * start.slave, sign * end.slave),
        sync_ratio: sign as f64 * r,
        stroke: direction,
        peak_ratio: peak,
        design,
    })
}

/// The forward and return tables of one cut cycle: `params` with `P2`
/// positive, then with `P2` negated (the manual's two ECAMTBX calls).
///
/// # Errors
/// As [`generate`].
pub fn generate_pair(params: &Params) -> Result<(Generated, Generated), TableError> {
    let forward = Params {
        slave_length: params.slave_length.abs(),
        ..*params
    };
    let back = Params {
        slave_length: -params.slave_length.abs(),
        ..*params
    };
    Ok((generate(&forward)?, generate(&back)?))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::CamCurve;

    #[test]
    fn decodes_the_return_flag() {
        assert_eq!(
            decode_cam_word(0x1000).unwrap(),
            (CamPlacement::LeftCam, Stroke::Return)
        );
        assert_eq!(
            decode_cam_word(0).unwrap(),
            (CamPlacement::LeftCam, Stroke::Forward)
        );
        assert_eq!(
            decode_cam_word(0x1005).unwrap(),
            (CamPlacement::RightCam, Stroke::Return)
        );
        assert!(decode_cam_word(0x2000).is_err());
    }

    #[test]
    fn placements_move_the_motion() {
        let left = generate(&Params::default()).unwrap();
        let right = generate(&Params {
            placement: CamPlacement::RightCam,
            ..Params::default()
        })
        .unwrap();
        let mid = generate(&Params {
            placement: CamPlacement::MidCamAll,
            ..Params::default()
        })
        .unwrap();
        let (l, r, m) = (
            left.sync.unwrap().0,
            right.sync.unwrap().0,
            mid.sync.unwrap().0,
        );
        assert!(l < m && m < r, "{l} {m} {r}");
        for g in [left, right, mid] {
            assert_eq!(g.table.slave_last(), 1000);
            assert_eq!(g.table.master_last(), 3000);
        }
        let bad = Params {
            placement: CamPlacement::MidCamEnd,
            ..Params::default()
        };
        assert_eq!(generate(&bad).unwrap_err().code(), 6781);
    }

    #[test]
    fn too_short_master_is_infeasible() {
        let p = Params {
            master_length: 500,
            ..Params::default()
        };
        assert!(matches!(generate(&p), Err(TableError::Infeasible { .. })));
    }
}
