//! Turning a designed [`Path`] into a [`PointTable`] of whole pulses.
//!
//! Constant-velocity pieces (sync zones, cruises, dwells) are straight lines,
//! so one section each represents them exactly; the ramps share the rest of
//! the point budget in proportion to their master length. Masters are
//! rounded to whole counts (duplicates merged, so a short table may get fewer
//! points than asked for); slaves are rounded to whole pulses except the
//! pinned points, which are exact by construction.

use alloc::vec::Vec;

use super::motion_path::Path;
use crate::{CamPoint, PointTable, TableError};

/// Most sections a DECAM register block holds (document 003).
pub(crate) const MAX_SECTIONS: usize = crate::register_image::MAX_SECTIONS;

/// Samples `path` over `[0, master_end]` into at most `points` points.
/// `pinned` points (table ends, sync-zone ends) get exactly their slave value.
/// The path must be non-decreasing (generators mirror afterwards for
/// backward motion), and so is the table.
///
/// # Errors
/// [`TableError::SectionCount`] if the path has more pieces than `points − 1`
/// sections can show; [`TableError::ValueOutOfRange`] for a slave that does
/// not fit an `i64`.
pub(crate) fn sample(
    path: &Path,
    master_end: i64,
    points: usize,
    pinned: &[CamPoint],
) -> Result<PointTable, TableError> {
    let budget = points.saturating_sub(1);
    let pieces = path.pieces();
    let constant = pieces.iter().filter(|p| p.is_constant_velocity()).count();
    let ramps = pieces.len() - constant;
    if pieces.len() > budget {
        return Err(TableError::SectionCount {
            count: budget,
            min: pieces.len(),
            max: MAX_SECTIONS,
        });
    }
    let ramp_master: f64 = pieces
        .iter()
        .filter(|p| !p.is_constant_velocity())
        .map(|p| p.len)
        .sum();
    let spare = budget - constant - ramps;
    let mut shares = ramp_shares(
        pieces
            .iter()
            .filter(|p| !p.is_constant_velocity())
            .map(|p| p.len),
        ramp_master,
        spare,
    )
    .into_iter();

    let end = master_end as f64;
    let mut masters: Vec<i64> = Vec::with_capacity(points + pinned.len());
    masters.push(0);
    masters.push(master_end);
    masters.extend(pinned.iter().map(|p| p.master));
    for p in pieces {
        masters.push(round_master(p.master_start, end));
        if p.is_constant_velocity() {
            continue;
        }
        // Each ramp gets one section plus its share of the spare ones.
        let sections = shares.next().unwrap_or(0).saturating_add(1);
        for j in 1..sections {
            masters.push(round_master(
                p.master_start + p.len * j as f64 / sections as f64,
                end,
            ));
        }
    }
    masters.sort_unstable();
    masters.dedup();

    let mut table = Vec::with_capacity(masters.len());
    let mut is_pinned = Vec::with_capacity(masters.len());
    for (section, &m) in masters.iter().enumerate() {
        let slave = match pinned.iter().find(|p| p.master == m) {
            Some(p) => p.slave,
            None => round_slave(path.slave_at(m as f64))
                .ok_or(TableError::ValueOutOfRange { section })?,
        };
        table.push(CamPoint::new(m, slave));
        is_pinned.push(pinned.iter().any(|p| p.master == m));
    }
    // The paths never move backwards. Where float noise puts a value a hair
    // past a rounding boundary (the mid placements sit on exact halves),
    // keep the table monotone and between its pinned neighbours.
    let mut floor = i64::MIN;
    for (p, &fixed) in table.iter_mut().zip(&is_pinned) {
        if !fixed {
            p.slave = p.slave.max(floor);
        }
        floor = p.slave;
    }
    let mut ceiling = i64::MAX;
    for (p, &fixed) in table.iter_mut().zip(&is_pinned).rev() {
        if !fixed {
            p.slave = p.slave.min(ceiling);
        }
        ceiling = p.slave;
    }
    PointTable::new(table)
}

/// Splits `spare` sections over ramps of master lengths `lens` (summing to
/// `total`) in proportion to their length, by largest remainder: the shares
/// add up to exactly `spare`, so a table gets the resolution asked for
/// (P7 is the number of points) unless whole-count masters coincide.
fn ramp_shares(lens: impl Iterator<Item = f64>, total: f64, spare: usize) -> Vec<usize> {
    if total.is_nan() || total <= 0.0 {
        return lens.map(|_| 0).collect();
    }
    let exact: Vec<f64> = lens.map(|len| spare as f64 * len / total).collect();
    let mut shares: Vec<usize> = exact.iter().map(|&q| q as usize).collect();
    let given: usize = shares.iter().sum();
    let mut order: Vec<usize> = (0..exact.len()).collect();
    // Largest fractional part first; ties keep the ramps' order.
    order.sort_by(|&a, &b| {
        let (fa, fb) = (
            exact[a] - libm::floor(exact[a]),
            exact[b] - libm::floor(exact[b]),
        );
        fb.total_cmp(&fa)
    });
    for &i in order.iter().take(spare.saturating_sub(given)) {
        if let Some(s) = shares.get_mut(i) {
            *s += 1;
        }
    }
    shares
}

fn round_master(m: f64, end: f64) -> i64 {
    // `end` is an exact integer in range, so the clamp keeps the cast exact.
    libm::round(m.clamp(0.0, end)) as i64
}

/// Rounds half up (never away from zero), so a path shifted by exactly −½
/// (see the rotary cut's mid placements) still rounds onto its pinned ends.
pub(crate) fn round_half_up(x: f64) -> f64 {
    libm::floor(x + 0.5)
}

fn round_slave(s: f64) -> Option<i64> {
    let r = round_half_up(s);
    // 2^62 keeps every later difference of two slaves inside i64.
    (r.is_finite() && r.abs() < 4.6e18).then_some(r as i64)
}

/// Largest `|Δslave/Δmaster|` over the sections: the table's peak ratio.
pub(crate) fn peak_ratio(table: &PointTable) -> f64 {
    table
        .points()
        .windows(2)
        .map(|w| ((w[1].slave - w[0].slave) as f64 / (w[1].master - w[0].master) as f64).abs())
        .fold(0.0, f64::max)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::CamCurve;
    use crate::generator::AccelCurve;
    use crate::generator::motion_path::Ramp;

    #[test]
    fn pins_points_and_respects_the_budget() {
        let mut p = Path::starting_at(0.0, 0.0);
        p.push(
            Ramp {
                v0: 0.0,
                v1: 2.0,
                len: 50.0,
            },
            AccelCurve::UniformAcceleration,
        );
        p.push_constant(2.0, 100.0);
        p.push(
            Ramp {
                v0: 2.0,
                v1: 0.0,
                len: 50.0,
            },
            AccelCurve::UniformAcceleration,
        );
        let pinned = [CamPoint::new(0, 0), CamPoint::new(200, 300)];
        let t = sample(&p, 200, 20, &pinned).unwrap();
        assert!(t.points().len() <= 20);
        assert_eq!(t.slave_last(), 300);
        assert_eq!(t.master_last(), 200);
        // The constant piece is one straight section from 50 to 150.
        assert!(t.points().iter().any(|q| q.master == 50 && q.slave == 50));
        assert!(t.points().iter().any(|q| q.master == 150 && q.slave == 250));
        assert!(peak_ratio(&t) <= 2.0 + 1e-12);
    }

    #[test]
    fn ramps_share_every_spare_section() {
        // Three ramps of equal length and 10 spare sections: 10/3 each
        // would floor to 3 + 3 + 3 and lose a point.
        assert_eq!(
            ramp_shares([5.0, 5.0, 5.0].into_iter(), 15.0, 10),
            [4, 3, 3]
        );
        assert_eq!(ramp_shares([1.0, 2.0].into_iter(), 3.0, 0), [0, 0]);
        assert_eq!(ramp_shares([0.0].into_iter(), 0.0, 4), [0]);
        let s = ramp_shares([399.0, 0.5, 399.0].into_iter(), 798.5, 93);
        assert_eq!(s.iter().sum::<usize>(), 93);
    }

    #[test]
    fn the_rotary_cut_demo_gets_every_point_asked_for() {
        use crate::generator::rotary_cut::{Params, generate};
        let g = generate(&Params {
            master_length: 3183,
            slave_length: 1000,
            sync_length: 333,
            sync_ratio: 5.0 / 3.0,
            max_ratio: 50.0 / 3.0,
            ..Params::default()
        })
        .unwrap();
        assert_eq!(g.table.points().len(), 100);
    }

    #[test]
    fn too_many_pieces_for_the_budget_is_6783() {
        let mut p = Path::starting_at(0.0, 0.0);
        for _ in 0..5 {
            p.push_constant(1.0, 10.0);
        }
        assert_eq!(sample(&p, 50, 4, &[]).unwrap_err().code(), 6783);
    }
}
