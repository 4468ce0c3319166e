//! The blend after a table switch (beyond the documents, after PLCopen
//! `MC_CamIn` with `BufferMode` aborting): from the old cam onto the new
//! one over a master distance, without a velocity step.
//!
//! At the switch position `p` the slave stands at `p0` with the old cam's
//! velocity `v0` (slave counts per master count). Over the blend, with
//! `u = |master − p| / distance` and the new cam's velocity `v1` where the
//! blend ends, the slave's velocity is
//!
//! `v(u) = v0 + (v1 − v0)(3u² − 2u³)`
//!
//! so it starts on the old cam's velocity, ends on the new cam's and never
//! leaves the range between them: two cams that do not reverse there give
//! a blend that does not reverse, and no faster than the faster of the two.
//! Its acceleration (per master count²) is `6u(1 − u)(v1 − v0) / distance`,
//! at most `1.5 |v1 − v0| / distance` ([`min_blend_distance`] turns this
//! into a distance for an acceleration limit), and it is 0 at both ends, so
//! the acceleration at the ends is the cams' own. The position is its
//! integral, a polynomial in `u`: the blend covers `distance × (v0 + v1) / 2`,
//! and the new cam's output offset is set so that the blend ends on it (the
//! slave is continuous there and afterwards the new cam is again a pure
//! function of the master). The end's fraction of a pulse, rounded towards
//! the travel, is spread over the blend with the quintic `10u³ − 15u⁴ + 6u⁵`,
//! which cannot turn the slave back.

use core::num::NonZeroU64;

use crate::coupling::{round_half_away, unsigned_to_f64};
use crate::ramp::quintic;
use crate::{EngineError, MasterPosition};

/// One way out of the blend (the master may leave it forwards or backwards).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Side {
    /// The new cam's velocity where the blend ends on this side.
    v1: f64,
    /// The blend's end position minus its polynomial (|·| below one pulse).
    residual: f64,
    /// The whole pulses the new cam's output moves by when the blend ends here.
    shift: i128,
}

/// A blend in progress.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Blend {
    from: i64,
    distance: u64,
    p0: i64,
    v0: f64,
    sides: [Side; 2],
}

/// The new cam where a blend ends on one side: its position (as anchored
/// at the switch) and velocity there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BlendEnd {
    pub(crate) slave: i64,
    pub(crate) velocity_ratio: f64,
}

/// `∫₀ᵘ (3t² − 2t³) dt`.
fn smoothstep_integral(u: f64) -> f64 {
    u * u * u * (1.0 - 0.5 * u)
}

/// What the blend commands at one master position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Blended {
    pub(crate) slave: i64,
    pub(crate) velocity_ratio: f64,
}

impl Blend {
    /// The master positions where a blend from `from` over `distance` ends,
    /// forwards and backwards.
    pub(crate) fn ends(from: i64, distance: u64) -> Result<[i64; 2], EngineError> {
        let d = i128::from(distance);
        let at = |v: i128| i64::try_from(v).map_err(|_| EngineError::SlaveOverflow);
        Ok([at(i128::from(from) + d)?, at(i128::from(from) - d)?])
    }

    /// A blend from the slave at `p0` with velocity `v0` at master `from`
    /// onto the new cam, which ends at `ends` (as from [`Blend::ends`]).
    pub(crate) fn start(
        from: i64,
        distance: u64,
        p0: i64,
        v0: f64,
        ends: [BlendEnd; 2],
    ) -> Result<Self, EngineError> {
        let mut sides = [Side {
            v1: 0.0,
            residual: 0.0,
            shift: 0,
        }; 2];
        for ((side, end), sign) in sides.iter_mut().zip(ends).zip([1.0, -1.0]) {
            let v1 = end.velocity_ratio;
            let target = p0 as f64 + sign * distance as f64 * 0.5 * (v0 + v1);
            let gap = target - end.slave as f64;
            let shift = if target >= p0 as f64 {
                libm::ceil(gap)
            } else {
                libm::floor(gap)
            };
            if !shift.is_finite() || shift.abs() > 9.0e18 {
                return Err(EngineError::SlaveOverflow);
            }
            *side = Side {
                v1,
                residual: shift - gap,
                shift: shift as i128,
            };
        }
        Ok(Self {
            from,
            distance,
            p0,
            v0,
            sides,
        })
    }

    /// [`Self::finished`] for the position itself, fraction included.
    pub(crate) fn finished_at(&self, at: MasterPosition) -> Option<i128> {
        self.finished(at.count_toward(self.from))
    }

    /// The whole pulses to move the new cam's output by, once `master`
    /// has completed the blend; `None` while it runs.
    pub(crate) fn finished(&self, master: i64) -> Option<i128> {
        let travelled = (i128::from(master) - i128::from(self.from)).unsigned_abs();
        (travelled >= u128::from(self.distance)).then(|| {
            self.sides
                .get(usize::from(master < self.from))
                .map_or(0, |s| s.shift)
        })
    }

    /// The blended command at `master` (past the end: the end itself).
    pub(crate) fn command(&self, master: i64) -> Result<Blended, EngineError> {
        let travelled = i128::from(master) - i128::from(self.from);
        let backwards = travelled < 0;
        let sign = if backwards { -1.0 } else { 1.0 };
        let Some(side) = self.sides.get(usize::from(backwards)) else {
            return Err(EngineError::SlaveOverflow);
        };
        let d = self.distance as f64;
        let u = (unsigned_to_f64(travelled.unsigned_abs()) / d).min(1.0);
        let dv = side.v1 - self.v0;
        let position = self.p0 as f64
            + sign * d * (self.v0 * u + dv * smoothstep_integral(u))
            + side.residual * quintic(u);
        // `libm::round`'s value, the common case without its routine.
        let position = round_half_away(position);
        if !position.is_finite() || position.abs() > 9.0e18 {
            return Err(EngineError::SlaveOverflow);
        }
        Ok(Blended {
            slave: position as i64,
            velocity_ratio: self.v0 + dv * u * u * (3.0 - 2.0 * u),
        })
    }
}

/// The shortest blend (master counts) that keeps the slave's acceleration
/// within `max_acceleration` (slave counts/s²) when the velocity ratio
/// changes by `ratio_gap` (slave counts per master count) while the master
/// runs at `master_speed` (counts/s): `1.5 × |gap| × speed² / limit`,
/// rounded up. `None` when no blend is needed (no gap or no master speed),
/// or the limit is not a positive number.
///
/// ```
/// use ecam_engine::min_blend_distance;
/// // From ratio 1 to 3 at 10 000 counts/s within 1 000 000 counts/s²:
/// assert_eq!(min_blend_distance(2.0, 10_000.0, 1.0e6).map(|d| d.get()), Some(300));
/// ```
pub fn min_blend_distance(
    ratio_gap: f64,
    master_speed: f64,
    max_acceleration: f64,
) -> Option<NonZeroU64> {
    if max_acceleration.is_nan() || max_acceleration <= 0.0 {
        return None;
    }
    let distance =
        libm::ceil(1.5 * libm::fabs(ratio_gap) * master_speed * master_speed / max_acceleration);
    if !distance.is_finite() {
        return NonZeroU64::new(u64::MAX);
    }
    NonZeroU64::new(distance as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_blend_ends_on_the_new_cam_with_its_velocity() {
        let end = |slave| BlendEnd {
            slave,
            velocity_ratio: 3.0,
        };
        // From ratio 1 at slave 100 over 1000 counts: covers 2000.
        let blend = Blend::start(0, 1000, 100, 1.0, [end(2000), end(-5000)]).unwrap();
        assert_eq!(blend.command(0).unwrap().slave, 100);
        assert_eq!(blend.command(1000).unwrap().slave, 2100);
        assert_eq!(blend.finished(1000), Some(100));
        assert_eq!(blend.finished(999), None);
        assert_eq!(blend.command(-1000).unwrap().slave, 100 - 2000);
        assert_eq!(blend.finished(-1000), Some(3100));
        assert!((blend.command(500).unwrap().velocity_ratio - 2.0).abs() < 1e-12);
    }
}
