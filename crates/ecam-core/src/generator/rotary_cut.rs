//! Rotary cut (rotary knife) table, ECAMTBX K100.
//!
//! A feed roll (the master) moves the material at constant speed; a knife
//! drum (the slave) turns one revolution per cut. While the blade is in the
//! material (the sync zone) the blade's surface speed must equal the
//! material's; the rest of the revolution is free to speed up or slow down so
//! that the next cut lands one cut length later.
//!
//! # Parameters and the ratio convention
//! `P1` master length: the cut length in feed pulses. `P2` slave length: knife
//! pulses per revolution. `P3` sync length in *slave* pulses. `P4` the sync
//! ratio, slave pulses per master pulse (`F2/F1`). The manual's demo writes
//! the formula as "F1/F2" but evaluates `(R2/D2)/(R1/D1) = 5/3`; with its
//! numbers (feed roll 100π mm and knife 60π mm per 1000 pulses) one master
//! pulse moves 0.1π mm of material and one slave pulse 0.06π mm of blade, so
//! equal surface speeds need 5/3 slave pulses per master pulse: the value is
//! slave/master, and that is how `P4` is used. `P5` caps the ratio anywhere in
//! the table. `P6` low word: [`AccelCurve`](super::AccelCurve); high word: [`CamPlacement`].
//! `P7` resolution: points in the table (10 to 512, see
//! [`MIN_RESOLUTION`]).
//!
//! # Geometry
//! One table cycle is `P1` master counts during which the slave turns
//! exactly `P2` pulses. The sync zone is a single straight section at the
//! sync ratio (see `docs/generators.md`: it may be a pulse or two longer
//! than `P3` so that the ratio is exact on the integer grid). The remaining
//! `P1 − Δm` counts must cover `P2 − Δs` pulses starting and ending at the
//! sync ratio `r`. With the mean ratio `r̄ = (P2 − Δs)/(P1 − Δm)`:
//! - `r̄ > r` (cut shorter than the circumference): speed up to
//!   `2r̄ − r` and back; if that exceeds `P5`, cruise at `P5` with steeper ramps;
//!   if even `r̄ ≥ P5`, [`TableError::Infeasible`];
//! - `r̄ = r` (cut equals the circumference): constant speed all round;
//! - `r/2 ≤ r̄ < r` (cut between one and about two circumferences): slow down
//!   to `2r̄ − r` and speed up again;
//! - `r̄ < r/2` (longer cuts): decelerate to a stop, dwell, and start again in
//!   time for the next sync zone. The manual puts this boundary at "two
//!   circumferences"; exactly, it is at a cut of `2·P2 − P3` slave pulses.
//!
//! Velocity stays continuous everywhere (ramps follow the chosen curve).
//!
//! # Placements
//! - leftCAM: the table starts at the sync start; rightCAM: it ends at the sync end;
//! - midCAMall: the sync zone is in the middle, the table starts and ends
//!   halfway through the free motion (a repeating table);
//! - midCAMbegin: as midCAMall but the first half starts from standstill
//!   (run once, then midCAMall); midCAMend: the last half ends at standstill
//!   (run once after midCAMall; the cam stops when it completes).
//!
//! ```
//! use ecam_core::CamCurve;
//! use ecam_core::generator::rotary_cut::{CutRegime, Params, generate};
//!
//! // The manual's demo: 3183 / 1000 / 333 / 5:3, max 50:3, leftCAM.
//! let g = generate(&Params { master_length: 3183, sync_length: 333, ..Params::default() })?;
//! assert_eq!(g.regime, CutRegime::StopAndDwell); // 1000 mm cut, 188 mm knife
//! assert_eq!((g.table.master_last(), g.table.slave_last()), (3183, 1000));
//! assert_eq!(g.sync, Some((0, 201)));
//! assert_eq!(g.sync_slave, (0, 335)); // 335/201 = 5/3 exactly
//! # Ok::<(), ecam_core::TableError>(())
//! ```

use super::design_curve::DesignCurve;
use super::motion_path::{Bend, Path, transition};
use super::placement::CamPlacement;
use super::sampling::{peak_ratio, round_half_up, sample};
use super::sync_zone::{SyncZone, choose};
use crate::{CamPoint, PointTable, TableError};

pub use super::cut_params::{MAX_RESOLUTION, MIN_RESOLUTION};

/// ECAMTBX K100 parameters: the block both cut generators share.
pub type Params = super::cut_params::CutParams;

/// What the knife does between cuts (the manual's four cut-length cases).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CutRegime {
    /// Cut shorter than the circumference: faster between sync zones.
    SpeedUp,
    /// Cut equal to the circumference: constant speed.
    Constant,
    /// Cut between one and about two circumferences: slower between sync zones.
    SlowDown,
    /// Longer cuts: stop and wait between sync zones.
    StopAndDwell,
}

/// The words a user reads (`ecam table gen rotary-cut` prints them).
impl core::fmt::Display for CutRegime {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::SpeedUp => "speed up between cuts (cut shorter than the knife's circumference)",
            Self::Constant => "constant speed (cut equal to the circumference)",
            Self::SlowDown => "slow down between cuts (cut up to about two circumferences)",
            Self::StopAndDwell => "stop and dwell between cuts (long cut)",
        })
    }
}

/// A rotary-cut table and what was made of the parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Generated {
    /// One cut cycle: from (0, 0) to (`P1`, `P2`).
    pub table: PointTable,
    /// Master range of the sync zone (always `Some`).
    pub sync: Option<(i64, i64)>,
    /// Slave range of the sync zone.
    pub sync_slave: (i64, i64),
    /// The sync zone's ratio as sampled (`Δslave/Δmaster`).
    pub sync_ratio: f64,
    /// What the knife does between cuts.
    pub regime: CutRegime,
    /// True if the speed-up had to cruise at `P5`.
    pub capped_at_max: bool,
    /// Steepest section of the table (≤ `P5`).
    pub peak_ratio: f64,
    /// The exact motion the table samples (every point within ½ pulse of
    /// it): its velocity is the sync ratio in the sync zone, exactly.
    pub design: DesignCurve,
}

fn check(p: &Params) -> Result<(), TableError> {
    let bad = |name, reason| Err(TableError::Parameter { name, reason });
    let max = i64::from(i32::MAX);
    p.check_common()?;
    if !(1..=max).contains(&p.slave_length) {
        return bad(
            "slave length (P2)",
            "must be between 1 and 2147483647 pulses",
        );
    }
    if !(1..p.slave_length).contains(&p.sync_length) {
        return bad(
            "sync length (P3)",
            "must be at least 1 pulse and less than the slave length",
        );
    }
    p.check_ratio_order()
}

/// The cycle in table coordinates, and where its sync zone starts.
struct Design {
    path: Path,
    sync_start: CamPoint,
    bend: Bend,
}

fn design(p: &Params, zone: SyncZone, limit: f64) -> Result<Design, TableError> {
    let r = zone.ratio();
    let (lm, ls) = (p.master_length, p.slave_length);
    let free_master = lm - zone.master;
    let free_slave = ls - zone.slave;
    // The leftCAM cycle; every other placement is a view of it.
    let mut left = Path::starting_at(0.0, 0.0);
    left.push_constant(r, zone.master as f64);
    let (bend, ramps) = transition(r, r, free_master as f64, free_slave as f64, limit)?;
    left.extend(&ramps, p.accel_curve);
    let (lmf, lsf) = (lm as f64, ls as f64);

    let (path, sync_start) = match p.placement {
        CamPlacement::LeftCam => (left, CamPoint::new(0, 0)),
        CamPlacement::RightCam => (
            left.rotated(zone.master as f64, lmf, lsf, zone.slave as f64),
            CamPoint::new(lm - zone.master, ls - zone.slave),
        ),
        CamPlacement::MidCamAll | CamPlacement::MidCamBegin | CamPlacement::MidCamEnd => {
            let sync_master = free_master / 2;
            let x0 = (lm - sync_master) as f64;
            // Shift the slave by a whole number so the sync zone stays on the
            // integer grid; the path then starts within [−½, ½) of 0 and ends
            // as far from P2, which round half up brings back onto 0 and P2.
            let offset = round_half_up(left.slave_at(x0));
            let mid = left.rotated(x0, lmf, lsf, offset);
            // `offset` lies in [0, P2], so the cast is exact.
            let start = CamPoint::new(sync_master, ls - offset as i64);
            let path = match p.placement {
                CamPlacement::MidCamBegin => {
                    let (_, ramps) =
                        transition(0.0, r, start.master as f64, start.slave as f64, limit)?;
                    let mut begin = Path::starting_at(0.0, 0.0);
                    begin.extend(&ramps, p.accel_curve);
                    begin.append_pieces(mid.pieces_from(start.master as f64));
                    begin
                }
                CamPlacement::MidCamEnd => {
                    let sync_end =
                        CamPoint::new(start.master + zone.master, start.slave + zone.slave);
                    let (_, ramps) = transition(
                        r,
                        0.0,
                        (lm - sync_end.master) as f64,
                        (ls - sync_end.slave) as f64,
                        limit,
                    )?;
                    let mut end = Path::starting_at(0.0, mid.slave_at(0.0));
                    end.append_pieces(mid.pieces_until(sync_end.master as f64));
                    end.extend(&ramps, p.accel_curve);
                    end
                }
                _ => mid,
            };
            (path, start)
        }
    };
    Ok(Design {
        path,
        sync_start,
        bend,
    })
}

/// Generates the rotary-cut table.
///
/// # Errors
/// [`TableError::Parameter`] (6781) for a parameter out of range;
/// [`TableError::Infeasible`] (6781) when the cut cannot be made within `P5`
/// or the sync zone leaves no room; [`TableError::SectionCount`] (6783) when
/// the resolution is too low for the pieces of the motion.
pub fn generate(p: &Params) -> Result<Generated, TableError> {
    check(p)?;
    let zone = choose(p.sync_length, p.sync_ratio, p.master_length)?;
    if zone.ratio() > p.max_ratio {
        return Err(TableError::Infeasible {
            reason: "the sync ratio rounded onto whole pulses is above the max ratio (P5)",
        });
    }
    if zone.slave >= p.slave_length {
        return Err(TableError::Infeasible {
            reason: "the sync zone covers the whole slave length",
        });
    }
    let free_master = p.master_length - zone.master;
    let free_slave = p.slave_length - zone.slave;
    // Exact comparison of the free motion's mean ratio with the sync ratio.
    let mean_vs_sync = (i128::from(free_slave) * i128::from(zone.master))
        .cmp(&(i128::from(zone.slave) * i128::from(free_master)));

    let mut limit = p.max_ratio;
    for _ in 0..4 {
        if limit < zone.ratio() {
            break;
        }
        let d = design(p, zone, limit)?;
        let sync_end = CamPoint::new(
            d.sync_start.master + zone.master,
            d.sync_start.slave + zone.slave,
        );
        let pinned = [
            CamPoint::new(0, 0),
            CamPoint::new(p.master_length, p.slave_length),
            d.sync_start,
            sync_end,
        ];
        let table = sample(&d.path, p.master_length, usize::from(p.resolution), &pinned)?;
        let peak = peak_ratio(&table);
        if peak > p.max_ratio {
            // Whole-pulse rounding made a section steeper than the cap:
            // design again under a cap lowered by the excess.
            limit -= peak - p.max_ratio + 1e-9 * p.max_ratio;
            continue;
        }
        let regime = match (mean_vs_sync, d.bend) {
            (core::cmp::Ordering::Greater, _) => CutRegime::SpeedUp,
            (core::cmp::Ordering::Equal, _) => CutRegime::Constant,
            (_, Bend::Dwell) => CutRegime::StopAndDwell,
            _ => CutRegime::SlowDown,
        };
        return Ok(Generated {
            table,
            sync: Some((d.sync_start.master, sync_end.master)),
            sync_slave: (d.sync_start.slave, sync_end.slave),
            sync_ratio: zone.ratio(),
            regime,
            capped_at_max: d.bend == Bend::CruiseAtMax,
            peak_ratio: peak,
            design: DesignCurve::new(d.path, p.master_length),
        });
    }
    Err(TableError::Infeasible {
        reason: "the table rounded onto whole pulses exceeds the max ratio (P5): raise it or lower the resolution",
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::CamCurve;

    #[test]
    fn four_regimes() {
        let base = Params {
            master_length: 3183,
            sync_length: 333,
            ..Params::default()
        };
        let cases = [
            (400, CutRegime::SpeedUp),
            (600, CutRegime::Constant),
            (900, CutRegime::SlowDown),
            (3183, CutRegime::StopAndDwell),
        ];
        for (lm, regime) in cases {
            let g = generate(&Params {
                master_length: lm,
                ..base
            })
            .unwrap();
            assert_eq!(g.regime, regime, "cut {lm}");
            assert_eq!(g.table.slave_last(), 1000);
            assert_eq!(g.table.master_last(), lm);
        }
    }

    #[test]
    fn constant_regime_is_a_straight_line() {
        let g = generate(&Params {
            master_length: 600,
            sync_length: 333,
            ..Params::default()
        })
        .unwrap();
        for w in g.table.points().windows(2) {
            assert_eq!(
                (w[1].slave - w[0].slave) * 3,
                (w[1].master - w[0].master) * 5
            );
        }
    }

    #[test]
    fn speed_up_beyond_the_cap_cruises_or_fails() {
        let p = Params {
            master_length: 300,
            sync_length: 333,
            max_ratio: 9.0,
            ..Params::default()
        };
        let g = generate(&p).unwrap();
        assert!(g.capped_at_max);
        assert!(g.peak_ratio <= 9.0);
        let too_fast = Params {
            max_ratio: 6.0,
            ..p
        };
        assert_eq!(generate(&too_fast).unwrap_err().code(), 6781);
    }
}
