//! Choosing the synchronised zone on the whole-count grid.
//!
//! The sync zone is one straight section of the table, so its ratio is
//! `Δslave/Δmaster` of two integers. We take the master span `Δm` from
//! `⌈P3/ratio⌉` upwards and `Δs = round(ratio·Δm)`, and keep the pair whose
//! ratio is closest to the requested one, among zones at most 1 % (+1 pulse)
//! longer than `P3`. The zone is never shorter than asked, and a rational
//! ratio such as the manual's 5/3 comes out exactly (333 pulses → 335 over
//! 201 counts); an irrational one such as 3π is matched to better than
//! `0.5/Δm`.

use crate::TableError;

/// A sync zone: `master` counts during which the slave moves `slave` pulses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SyncZone {
    pub master: i64,
    pub slave: i64,
}

impl SyncZone {
    /// The achieved ratio `slave/master`.
    pub fn ratio(self) -> f64 {
        self.slave as f64 / self.master as f64
    }
}

/// Most master spans tried.
const CANDIDATES: i64 = 64;

/// The sync zone for `sync_length` slave pulses at `ratio`, shorter than
/// `master_length` counts. `sync_length ≥ 1` and `ratio` finite and positive.
///
/// # Errors
/// [`TableError::Infeasible`] if the zone does not fit in `master_length`.
pub(crate) fn choose(
    sync_length: i64,
    ratio: f64,
    master_length: i64,
) -> Result<SyncZone, TableError> {
    let too_long = TableError::Infeasible {
        reason: "the sync zone is as long as the master length at this ratio: shorten the sync length or raise the ratio",
    };
    let first = libm::ceil(sync_length as f64 / ratio);
    if !(first.is_finite() && first < master_length as f64) {
        return Err(too_long);
    }
    // `first` is below master_length ≤ 2³¹, so the cast is exact.
    let first = (first as i64).max(1);
    let longest = sync_length + sync_length / 100 + 1;
    let mut best: Option<(f64, SyncZone)> = None;
    for master in first..first.saturating_add(CANDIDATES).min(master_length) {
        let slave = libm::round(ratio * master as f64);
        if slave > longest as f64 && best.is_some() {
            break;
        }
        if !(1.0..4.6e18).contains(&slave) {
            continue;
        }
        let error = (slave / master as f64 - ratio).abs();
        if best.is_none_or(|(e, _)| error < e) {
            best = Some((
                error,
                SyncZone {
                    master,
                    slave: slave as i64,
                },
            ));
        }
    }
    best.map(|(_, z)| z).ok_or(too_long)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn five_thirds_is_exact() {
        let z = choose(333, 5.0 / 3.0, 3183).unwrap();
        assert_eq!(
            z,
            SyncZone {
                master: 201,
                slave: 335
            }
        );
        let f32_ratio = f64::from(5.0_f32 / 3.0);
        assert_eq!(choose(333, f32_ratio, 3183).unwrap(), z);
    }

    #[test]
    fn three_pi_is_close_and_not_shorter() {
        let r = 3.0 * core::f64::consts::PI;
        let z = choose(667, r, 1750).unwrap();
        assert!(z.slave >= 667 && z.slave <= 674);
        assert!((z.ratio() - r).abs() <= 0.5 / z.master as f64);
    }

    #[test]
    fn zone_longer_than_master_is_infeasible() {
        assert!(choose(1000, 0.5, 2000).is_err());
        assert!(choose(1000, 0.5, 2001).is_ok());
    }
}
