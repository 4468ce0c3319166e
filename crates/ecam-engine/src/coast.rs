//! The slave after a PLCopen `MC_CamOut`: it leaves the cam and keeps the
//! velocity it had, until a stop holds it or a decelerating stop brings it
//! to rest under a deceleration limit.
//!
//! Integer arithmetic only: the velocity is fixed point (1/2^16 pulse per
//! second) and the travel is the exact sum of velocity × tick length, so
//! the commanded position never drifts from the integral of the velocity
//! and, with the velocity moving only towards zero, never reverses.

use core::num::NonZeroU64;

/// Fraction bits of the fixed-point velocity.
const FRACTION: u32 = 16;
/// Travel units per pulse: velocity units (2^16 per pulse/s) × µs per s.
const PER_PULSE: i128 = (1_i128 << FRACTION) * 1_000_000;

/// A slave moving at constant velocity, or decelerating to rest.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Coast {
    /// The slave where the motion started.
    origin: i64,
    /// Pulses per second × 2^16, signed.
    velocity: i128,
    /// Travel since the start, in pulses × [`PER_PULSE`].
    travel: i128,
    /// Pulses per second², when a decelerating stop was asked for.
    deceleration: Option<NonZeroU64>,
}

impl Coast {
    /// Motion from `origin` at `pulses_per_s`, bounded by `ceiling_hz`
    /// (the pulse frequency limit: a faster velocity could never go out,
    /// and the backlog would grow without end).
    pub(crate) fn new(origin: i64, pulses_per_s: f64, ceiling_hz: u32) -> Self {
        let ceiling = f64::from(ceiling_hz);
        let v = if pulses_per_s.is_finite() {
            pulses_per_s.clamp(-ceiling, ceiling)
        } else {
            0.0
        };
        Self {
            origin,
            velocity: libm::round(v * f64::from(1_u32 << FRACTION)) as i128,
            travel: 0,
            deceleration: None,
        }
    }

    /// From now on, decelerate to rest at `deceleration` pulses/s².
    pub(crate) fn decelerate(&mut self, deceleration: NonZeroU64) {
        self.deceleration = Some(deceleration);
    }

    /// The velocity now, pulses per second.
    pub(crate) fn velocity(&self) -> f64 {
        self.velocity as f64 / f64::from(1_u32 << FRACTION)
    }

    /// Advances one tick of `dt_us`; gives the commanded slave and whether
    /// the motion came to rest (only a decelerating stop does).
    pub(crate) fn advance(&mut self, dt_us: u32) -> (i64, bool) {
        let dt = i128::from(dt_us);
        let v0 = self.velocity;
        let v1 = match self.deceleration {
            Some(d) => {
                // Towards zero, never past it: no reversal.
                let dv = i128::from(d.get()).saturating_mul(dt) * (1 << FRACTION) / 1_000_000;
                if v0 > 0 {
                    (v0 - dv).max(0)
                } else {
                    (v0 + dv).min(0)
                }
            }
            None => v0,
        };
        // Trapezoid over the tick: exact for constant velocity and for a
        // constant deceleration.
        let step = (v0 + v1).saturating_mul(dt) / 2;
        self.travel = self.travel.saturating_add(step);
        self.velocity = v1;
        // Truncated towards zero: monotonic in the travel.
        let pulses = self.travel / PER_PULSE;
        let at = i128::from(self.origin).saturating_add(pulses);
        let at = i64::try_from(at).unwrap_or(if at < 0 { i64::MIN } else { i64::MAX });
        (at, self.deceleration.is_some() && v1 == 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_velocity_is_exact_over_a_long_run() {
        let mut c = Coast::new(100, 1234.0, 200_000);
        let mut at = 0;
        for _ in 0..1_000_000 {
            at = c.advance(1000).0;
        }
        // 1000 s at 1234 pulses/s.
        assert_eq!(at, 100 + 1_234_000);
    }

    #[test]
    fn the_ceiling_bounds_the_velocity() {
        let c = Coast::new(0, -1.0e9, 50_000);
        assert_eq!(c.velocity(), -50_000.0);
        assert_eq!(Coast::new(0, f64::NAN, 10).velocity(), 0.0);
    }

    #[test]
    fn a_decelerating_stop_comes_to_rest_without_reversing() {
        let mut c = Coast::new(0, -1000.0, 200_000);
        c.decelerate(NonZeroU64::new(10_000).unwrap());
        let mut last = 0;
        let mut ticks = 0;
        loop {
            let (at, done) = c.advance(1000);
            assert!(at <= last, "reversed at {at}");
            last = at;
            ticks += 1;
            if done {
                break;
            }
        }
        // 0.1 s to rest; v²/2a = 50 pulses.
        assert_eq!(ticks, 100);
        assert_eq!(last, -50);
    }
}
