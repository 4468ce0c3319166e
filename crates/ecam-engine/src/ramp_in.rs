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
//!
//! The figures are the ones at engage; the engaging tick checks the room
//! for the catch-up and keeps them ([`LimitedLength`]), and the distance
//! is worked out from them on the next tick (docs/engine.md, "Ramp-in
//! under limits").

use core::num::{NonZeroU32, NonZeroU64};

use crate::EngineError;
use crate::rounding::ceil_whole;

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
    /// Whether a ramp-in can keep to the velocity limit at all: not when
    /// the cam alone, with velocity ratio `ratio` at master speed `speed`
    /// (counts/s), needs more than the limit allows for a catch-up. A
    /// master at rest (or a speed that is no number) sizes nothing and
    /// passes.
    ///
    /// # Errors
    /// [`EngineError::RampInLimits`] when it cannot.
    pub(crate) fn check_room(&self, ratio: f64, speed: f64) -> Result<(), EngineError> {
        let v = libm::fabs(speed);
        if !(v > 0.0 && v < f64::INFINITY) {
            return Ok(());
        }
        if self.room(libm::fabs(ratio), v) <= 0.0 {
            return Err(EngineError::RampInLimits);
        }
        Ok(())
    }

    /// The velocity left for the catch-up over the cam's own at `r × v`.
    fn room(&self, r: f64, v: f64) -> f64 {
        f64::from(self.max_velocity.get()) - H * r * v
    }

    /// The shortest ramp distance (master counts) for a gap `gap` (pulses),
    /// a cam velocity ratio `ratio` and a master speed `speed` (counts/s)
    /// that [`RampInLimits::check_room`] passed; `None` for a master at
    /// rest (no speed to size it for).
    ///
    /// Every figure the axis passes is finite and bounded (a gap and a
    /// travel between 64-bit positions, at least a µs per tick), so the
    /// distance is a finite float; one that were not (or beyond 64 bits)
    /// would be the longest ramp there is.
    pub(crate) fn shortest(&self, gap: f64, ratio: f64, speed: f64) -> Option<u64> {
        let v = libm::fabs(speed);
        if !(v > 0.0 && v < f64::INFINITY) {
            return None;
        }
        let (g, r) = (libm::fabs(gap), libm::fabs(ratio));
        let d_v = W1 * g * v / self.room(r, v);
        let a = W2 * g * v * v;
        let b = H1 * r * v * v;
        let c = self.max_acceleration.get() as f64;
        // D² c − b D − a ≥ 0.
        let d_a = (b + libm::sqrt(b * b + 4.0 * a * c)) / (2.0 * c);
        let d_j = match self.max_jerk {
            Some(j) => jerk_distance(g, r, v, j.get() as f64),
            None => 0.0,
        };
        let d = ceil_whole(d_v.max(d_a).max(d_j)).max(1.0);
        Some(if d < 1.8e19 { d as u64 } else { u64::MAX })
    }

    /// [`RampInLimits::check_room`], then [`RampInLimits::shortest`].
    #[cfg(test)]
    fn distance(&self, gap: f64, ratio: f64, speed: f64) -> Result<Option<u64>, EngineError> {
        self.check_room(ratio, speed)?;
        Ok(self.shortest(gap, ratio, speed))
    }
}

/// What sizes a ramp-in under limits, as the engaging tick found it: the
/// gap the ramp closes and the cam's velocity ratio where it engages,
/// the master's speed bound then, and the ramp-in distance configured
/// (the ramp is at least that long). Built only where the room check
/// passed, so the distance it gives is always one to run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LimitedLength {
    limits: RampInLimits,
    gap: f64,
    ratio: f64,
    speed: f64,
    configured: Option<NonZeroU64>,
}

impl LimitedLength {
    /// The figures of a ramp-in under `limits` (see the type).
    ///
    /// # Errors
    /// [`EngineError::RampInLimits`] where the room check fails.
    pub(crate) fn new(
        limits: RampInLimits,
        gap: f64,
        ratio: f64,
        speed: f64,
        configured: Option<NonZeroU64>,
    ) -> Result<Self, EngineError> {
        limits.check_room(ratio, speed)?;
        Ok(Self {
            limits,
            gap,
            ratio,
            speed,
            configured,
        })
    }

    /// The ramp's master distance: the shortest the limits allow, or the
    /// configured one if longer. A master at rest gives no speed to size
    /// for: then the configured distance, or one master count per 1/1.875
    /// pulse of gap (the quintic's steepest slope is 1.875).
    pub(crate) fn distance(&self) -> NonZeroU64 {
        let needed = self.limits.shortest(self.gap, self.ratio, self.speed);
        let counts = match (needed, self.configured.map(NonZeroU64::get)) {
            (Some(a), Some(b)) => a.max(b),
            (Some(d), None) | (None, Some(d)) => d,
            (None, None) => ceil_whole(1.875 * libm::fabs(self.gap)).max(1.0) as u64,
        };
        // Never 0 (each arm is at least 1): the saturating form only
        // spares an unwrap.
        NonZeroU64::MIN.saturating_add(counts.saturating_sub(1))
    }
}

/// The smallest whole `D ≥ 1` with `j D³ − J1 |r| V³ D − W3 |g| V³ ≥ 0`
/// (the left side has one positive root and grows beyond it), as a float.
///
/// A bounded amount of work, for the tick that sizes the ramp: Newton's
/// method from close to the root, a fixed number of steps, then the
/// whole counts around the estimate checked with the cubic itself.
/// Divided by `j`, the cubic is `D³ − P D − Q`; with `a = √P` and
/// `b = ∛Q`, both `a + Q / 2P` and `b + P / 3b` leave it at or above 0
/// (put them in: what is left is `3a e² + e³` with `e = Q / 2P`, and
/// `P³ / 27b³`), so the smaller is at or above the root and within 3 % of
/// it, the worst being near `Q² = P³ / 8`. `b` is taken from
/// [`cube_root_start`], within a few parts in a thousand, so the start may
/// lie a little below the root; one step then puts it above (the cubic
/// is convex and rising beyond `√(P/3)`, and the start is beyond it), and
/// from there every step moves down to the root, a handful reaching it to
/// the last bits (at most six over the figures the tests draw).
/// `distance` rounds the largest of the three distances up to a whole
/// count, so this gives what it gave when the root was bisected to the
/// last bit (tested), except where the root lies within rounding of a
/// whole count.
fn jerk_distance(g: f64, r: f64, v: f64, j: f64) -> f64 {
    let v3 = v * v * v;
    let (p, q) = (J1 * r * v3, W3 * g * v3);
    let excess = |d: f64| j * d * d * d - p * d - q;
    let (pj, qj) = (p / j, q / j);
    let a = libm::sqrt(pj);
    let mut d = if qj > 0.0 {
        let b = cube_root_start(qj);
        let from_q = b + pj / (3.0 * b);
        if pj > 0.0 {
            from_q.min(a + qj / (2.0 * pj))
        } else {
            from_q
        }
    } else {
        a
    };
    if excess(d) < 0.0 {
        d -= excess(d) / (3.0 * j * d * d - p);
    }
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
    let mut whole = ceil_whole(d).max(1.0);
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
    ceil_whole(jerk_root_bisected(g, r, v, j)).max(1.0)
}

/// A start for the cube root of `x` (positive, finite, not subnormal):
/// the exponent divided by three in the float's bits (with the constant
/// that centres the error, a few per cent), then one Newton step for
/// `y³ = x` (a few parts in a thousand). Only a start for
/// [`jerk_distance`], which settles the root on its cubic; `libm::cbrt`
/// rounds correctly but costs some 130 instructions, and its first call
/// in a process some 270 more (it looks up the CPU's features then),
/// which would land in a control tick.
fn cube_root_start(x: f64) -> f64 {
    let y = f64::from_bits(x.to_bits() / 3 + 0x2A9F_7893_782D_A1CE);
    y - (y - x / (y * y)) / 3.0
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

/// Newton steps of [`jerk_distance`]: from its start, within 3 % of the
/// root, six steps at most reach it to a few units in the last place;
/// the rest are a margin for figures at the ends of the range.
const NEWTON_STEPS: usize = 8;
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

    proptest::proptest! {
        /// A ramp under limits is as long as the limits need, at least
        /// the configured distance, and at rest the configured distance
        /// or one count per 1/1.875 pulse of gap; where the room check
        /// fails nothing is kept. Any figures: never 0, never a panic.
        #[test]
        fn a_limited_length_is_the_longer_of_needed_and_configured(
            gap in proptest::prop_oneof![-1e6f64..1e6, -1.8e19f64..1.8e19],
            ratio in proptest::prop_oneof![-3f64..3.0, -1e12f64..1e12],
            speed in proptest::prop_oneof![0f64..1e6, 0f64..1.8e25, proptest::strategy::Just(0.0)],
            configured in proptest::option::of(1u64..u64::MAX),
            velocity in 1u32..u32::MAX,
            acceleration in 1u64..u64::MAX,
            jerk in proptest::option::of(1u64..u64::MAX),
        ) {
            let limits = RampInLimits {
                max_velocity: NonZeroU32::new(velocity).unwrap(),
                max_acceleration: NonZeroU64::new(acceleration).unwrap(),
                direction: RampDirection::Either,
                max_jerk: jerk.and_then(NonZeroU64::new),
            };
            let configured = configured.and_then(NonZeroU64::new);
            let kept = LimitedLength::new(limits, gap, ratio, speed, configured);
            let room = f64::from(velocity) - H * ratio.abs() * speed;
            if speed > 0.0 && room <= 0.0 {
                proptest::prop_assert_eq!(kept, Err(EngineError::RampInLimits));
                return Ok(());
            }
            let d = kept.unwrap().distance().get();
            let at_least = configured.map_or(1, NonZeroU64::get);
            proptest::prop_assert!(d >= at_least);
            match limits.shortest(gap, ratio, speed) {
                Some(needed) => proptest::prop_assert_eq!(d, needed.max(at_least)),
                None => {
                    proptest::prop_assert_eq!(speed, 0.0);
                    let by_gap = libm::ceil(1.875 * gap.abs()).max(1.0) as u64;
                    proptest::prop_assert_eq!(d, configured.map_or(by_gap, NonZeroU64::get));
                }
            }
        }
    }

    #[test]
    fn the_cube_root_start_is_within_a_few_parts_in_a_thousand() {
        for i in -400..=400 {
            for m in [1.0, 1.7, 2.9, 5.3, 9.99] {
                let x = m * libm::pow(10.0, f64::from(i) / 4.0);
                let start = cube_root_start(x);
                assert!((start / libm::cbrt(x) - 1.0).abs() < 2e-3, "{x}");
            }
        }
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
