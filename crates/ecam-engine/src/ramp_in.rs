//! Ramp-in under limits (after PLCopen `MC_CamIn` ramp-in, `ramp_in_pos`,
//! `ramp_in_neg`): the distance of the quintic ramp-in chosen at engage so
//! that catching up a moving master stays within the slave's velocity and
//! acceleration limits, and the direction of the catch-up restricted.
//!
//! The ramp-in commands `hold + w(u) × (cam − hold)` over a master distance
//! `D` (see the `ramp` module). With the master at speed `V` (counts/s),
//! the cam's velocity ratio `r` and the gap `g = cam − hold` at engage, its
//! velocity is `V × (r × (w + u w') + w' × g / D)` and its acceleration
//! `V² × (r × (2w' + u w'') / D + w'' × g / D²)` plus the cam's own
//! (`w' ≤ 1.875`, `w + u w' ≤ 1.78`, `|2w' + u w''| ≤ 4.63`,
//! `|w''| ≤ 5.78`): catching up needs up to 1.78 times the cam's velocity,
//! and a distance of at least
//! `D_v = 1.875 |g| V / (v_max − 1.78 |r| V)` and the `D_a` that solves
//! `V² (5.78 |g| / D² + 4.63 |r| / D) = a_max`.
//!
//! With a jerk limit the third derivative counts too: the ramp's jerk is
//! `V³ × (r × (3w'' + u w''') / D² + w''' × g / D³)` plus the cam's own,
//! with `|w'''| ≤ 60` and `|3w'' + u w'''| ≤ 60` on `[0, 1]`, so the
//! distance is also at least the `D_j` that solves
//! `V³ (60 |g| / D³ + 60 |r| / D²) = j_max`. The quintic keeps its shape:
//! the limits only stretch it.

use core::num::{NonZeroU32, NonZeroU64};

use crate::EngineError;

/// Which way the slave may move to close the gap at ramp-in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RampDirection {
    /// The nearer way.
    #[default]
    Either,
    /// Only forwards (PLCopen `ramp_in_pos`): on a repeat cam the target is
    /// the equivalent position ahead (whole strokes added).
    Positive,
    /// Only backwards (PLCopen `ramp_in_neg`).
    Negative,
}

/// Limits a ramp-in keeps to ([`crate::CamAxis::set_ramp_in_limits`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RampInLimits {
    /// Slave velocity limit, pulses per second.
    pub max_velocity: NonZeroU32,
    /// Slave acceleration limit, pulses per second².
    pub max_acceleration: NonZeroU64,
    /// Which way the gap may be closed.
    pub direction: RampDirection,
    /// Slave jerk limit, pulses per second³ (`None`: no jerk limit).
    pub max_jerk: Option<NonZeroU64>,
}

/// Constants of the quintic's derivatives (upper bounds on [0, 1]).
const W1: f64 = 1.875;
const H: f64 = 1.78;
const H1: f64 = 4.63;
const W2: f64 = 5.78;
const W3: f64 = 60.0;
const J1: f64 = 60.0;

impl RampInLimits {
    /// The shortest ramp distance (master counts) for a gap `gap` (pulses),
    /// a cam velocity ratio `ratio` and a master speed `speed` (counts/s);
    /// `None` for a master at rest (no speed to size it for).
    ///
    /// # Errors
    /// [`EngineError::RampInLimits`] when the cam alone, at this speed, needs
    /// more than the velocity limit allows for a catch-up.
    pub(crate) fn distance(
        &self,
        gap: f64,
        ratio: f64,
        speed: f64,
    ) -> Result<Option<u64>, EngineError> {
        let v = libm::fabs(speed);
        if v == 0.0 || !v.is_finite() {
            return Ok(None);
        }
        let (g, r) = (libm::fabs(gap), libm::fabs(ratio));
        let room = f64::from(self.max_velocity.get()) - H * r * v;
        if room <= 0.0 {
            return Err(EngineError::RampInLimits);
        }
        let d_v = W1 * g * v / room;
        let a = W2 * g * v * v;
        let b = H1 * r * v * v;
        let c = self.max_acceleration.get() as f64;
        // D² c − b D − a ≥ 0.
        let d_a = (b + libm::sqrt(b * b + 4.0 * a * c)) / (2.0 * c);
        let d_j = match self.max_jerk {
            Some(j) => jerk_distance(g, r, v, j.get() as f64),
            None => 0.0,
        };
        let d = libm::ceil(d_v.max(d_a).max(d_j)).max(1.0);
        if !d.is_finite() {
            return Err(EngineError::RampInLimits);
        }
        Ok(Some(if d >= 1.8e19 { u64::MAX } else { d as u64 }))
    }
}

/// The smallest whole `D ≥ 1` with `j D³ − J1 |r| V³ D − W3 |g| V³ ≥ 0`
/// (the left side has one positive root and grows beyond it), as a float.
///
/// A bounded amount of work, for the tick that engages: Newton's method
/// from `∛(q/j) + √(p/j)`, which lies at or above the root (the cubic is
/// convex there, so every step stays above it and moves down), a fixed
/// number of steps, then the whole counts around the estimate checked
/// with the cubic itself. `distance` rounds the largest of the three
/// distances up to a whole count, so this gives what it gave when the
/// root was bisected to the last bit (tested), except where the root
/// lies within rounding of a whole count.
fn jerk_distance(g: f64, r: f64, v: f64, j: f64) -> f64 {
    let v3 = v * v * v;
    let (p, q) = (J1 * r * v3, W3 * g * v3);
    let excess = |d: f64| j * d * d * d - p * d - q;
    let at_one = excess(1.0);
    if at_one.is_nan() {
        return f64::NAN;
    }
    if at_one >= 0.0 {
        return 1.0;
    }
    let mut d = libm::cbrt(q / j) + libm::sqrt(p / j);
    for _ in 0..NEWTON_STEPS {
        let slope = 3.0 * j * d * d - p;
        let next = d - excess(d) / slope;
        if !(next.is_finite() && next < d) {
            break;
        }
        d = next;
    }
    if !d.is_finite() {
        return d;
    }
    // The estimate is within a count of the root: take the first whole
    // count the cubic accepts, looking a few counts either side.
    let mut whole = libm::ceil(d).max(1.0);
    for _ in 0..WHOLE_STEPS {
        if whole > 1.0 && excess(whole - 1.0) >= 0.0 {
            whole -= 1.0;
        } else if excess(whole) < 0.0 {
            whole += 1.0;
        } else {
            return whole;
        }
    }
    // Not settled within its steps (extreme figures): bisect, as before.
    libm::ceil(jerk_root_bisected(g, r, v, j)).max(1.0)
}

/// The root of [`jerk_distance`]'s cubic, bisected to the last bit on a
/// bracket found by doubling: a bounded number of steps, but many; the
/// fallback for figures the Newton steps do not settle.
fn jerk_root_bisected(g: f64, r: f64, v: f64, j: f64) -> f64 {
    let v3 = v * v * v;
    let excess = |d: f64| j * d * d * d - J1 * r * v3 * d - W3 * g * v3;
    if excess(1.0) >= 0.0 {
        return 1.0;
    }
    let mut high = 2.0;
    let mut steps = 0;
    while excess(high) < 0.0 && steps < 1100 {
        high *= 2.0;
        steps += 1;
    }
    let mut low = high / 2.0;
    for _ in 0..64 {
        let mid = 0.5 * (low + high);
        if excess(mid) < 0.0 {
            low = mid;
        } else {
            high = mid;
        }
    }
    high
}

/// Newton steps of [`jerk_distance`]: from its start, which is at most
/// about twice the root, a dozen steps reach the root to a few units in
/// the last place.
const NEWTON_STEPS: usize = 16;
/// Whole counts [`jerk_distance`] may move from its estimate.
const WHOLE_STEPS: usize = 4;

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> RampInLimits {
        RampInLimits {
            max_velocity: NonZeroU32::new(10_000).unwrap(),
            max_acceleration: NonZeroU64::new(100_000).unwrap(),
            direction: RampDirection::Either,
            max_jerk: None,
        }
    }

    #[test]
    fn the_bounds_of_the_quintic_hold() {
        let w1 = |u: f64| 30.0 * u * u * (1.0 - u) * (1.0 - u);
        let w2 = |u: f64| 60.0 * u * (1.0 - u) * (1.0 - 2.0 * u);
        let w = |u: f64| u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
        let w3 = |u: f64| 60.0 - 360.0 * u + 360.0 * u * u;
        for i in 0..=10_000 {
            let u = f64::from(i) / 10_000.0;
            assert!(w3(u).abs() <= W3 + 1e-9);
            assert!((3.0 * w2(u) + u * w3(u)).abs() <= J1 + 1e-9);
            assert!(w1(u) <= W1 + 1e-12);
            assert!(w(u) + u * w1(u) <= H);
            assert!((2.0 * w1(u) + u * w2(u)).abs() <= H1);
            assert!(w2(u).abs() <= W2);
        }
    }

    #[test]
    fn a_faster_master_needs_a_longer_ramp() {
        let l = limits();
        let slow = l.distance(1000.0, 1.0, 1000.0).unwrap().unwrap();
        let fast = l.distance(1000.0, 1.0, 4000.0).unwrap().unwrap();
        assert!(fast > slow);
        assert_eq!(l.distance(1000.0, 1.0, 0.0), Ok(None));
        assert_eq!(
            l.distance(0.0, 10.0, 1000.0),
            Err(EngineError::RampInLimits)
        );
    }

    #[test]
    fn the_jerk_distance_is_the_bisected_root_rounded_up() {
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        let mut unit = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut differ = 0;
        for _ in 0..20_000 {
            let g = 10f64.powf(unit() * 8.0);
            let r = unit() * 5.0;
            let v = 10f64.powf(unit() * 6.0);
            let j = 10f64.powf(4.0 + unit() * 12.0);
            let new = jerk_distance(g, r, v, j);
            let old = libm::ceil(jerk_root_bisected(g, r, v, j)).max(1.0);
            if new != old {
                // Only where the root is within rounding of a whole count.
                let root = jerk_root_bisected(g, r, v, j);
                assert!(
                    (root - libm::round(root)).abs() <= 1e-9 * root.max(1.0),
                    "{g} {r} {v} {j}: {new} vs {old}"
                );
                differ += 1;
            }
        }
        assert!(differ < 10, "{differ}");
    }

    #[test]
    fn a_jerk_limit_lengthens_the_ramp_to_its_root() {
        let free = limits().distance(1000.0, 1.0, 1000.0).unwrap().unwrap();
        let limited = RampInLimits {
            max_jerk: NonZeroU64::new(1_000_000),
            ..limits()
        };
        let d = limited.distance(1000.0, 1.0, 1000.0).unwrap().unwrap();
        assert!(d > free);
        // At the distance the jerk bound is met, one count shorter it is not.
        let jerk = |d: f64| 1e9 * (60.0 * 1000.0 / (d * d * d) + 60.0 / (d * d));
        assert!(jerk(d as f64) <= 1_000_000.0);
        assert!(jerk(d as f64 - 1.0) > 1_000_000.0);
    }
}
