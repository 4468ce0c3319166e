//! The time-optimal trapezoidal profile behind the timed couplings
//! (PLCopen `MC_Phasing` and `MC_MoveSuperimposed`): from a position with
//! a velocity to rest at a distance, under a velocity limit, an
//! acceleration (speeding up) and a deceleration (slowing down).
//!
//! At most four phases of constant acceleration: stop first when moving
//! away from the target (or when the target is closer than the stopping
//! distance, then come back), slow down to the velocity limit when above
//! it, then speed up, cruise and slow down to rest exactly at the target.
//! Jerk is not limited (the acceleration steps); the profile is evaluated
//! as a function of the time since its start, so nothing accumulates from
//! tick to tick.

use crate::CouplingError;

/// Velocity (units/s), acceleration and deceleration (units/s²) of a
/// timed move, each a finite number above zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveLimits {
    velocity: f64,
    acceleration: f64,
    deceleration: f64,
}

impl MoveLimits {
    /// Limits for a timed move.
    ///
    /// # Errors
    /// [`CouplingError::BadLimit`] unless each is finite and above zero.
    pub fn new(velocity: f64, acceleration: f64, deceleration: f64) -> Result<Self, CouplingError> {
        let ok = |v: f64| v.is_finite() && v > 0.0;
        if ok(velocity) && ok(acceleration) && ok(deceleration) {
            Ok(Self {
                velocity,
                acceleration,
                deceleration,
            })
        } else {
            Err(CouplingError::BadLimit)
        }
    }

    /// The velocity limit.
    pub fn velocity(&self) -> f64 {
        self.velocity
    }

    /// The acceleration limit (speeding up).
    pub fn acceleration(&self) -> f64 {
        self.acceleration
    }

    /// The deceleration limit (slowing down).
    pub fn deceleration(&self) -> f64 {
        self.deceleration
    }
}

/// A planned profile: the start velocity and up to four phases of
/// (duration in s, acceleration).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Trapezoid {
    v0: f64,
    phases: [(f64, f64); 4],
    count: usize,
}

impl Trapezoid {
    /// A profile that stands still.
    pub(crate) const REST: Self = Self {
        v0: 0.0,
        phases: [(0.0, 0.0); 4],
        count: 0,
    };

    fn push(&mut self, duration: f64, acceleration: f64) {
        if duration > 0.0
            && duration.is_finite()
            && let Some(slot) = self.phases.get_mut(self.count)
        {
            *slot = (duration, acceleration);
            self.count += 1;
        }
    }

    /// Rest to rest over `d >= 0` in the direction `sign`.
    fn rest_to_rest(&mut self, d: f64, sign: f64, l: MoveLimits) {
        self.speed_up_cruise_slow_down(d, 0.0, sign, l);
    }

    /// From `u` (0 <= u <= limit, towards the target) to rest after `d`.
    fn speed_up_cruise_slow_down(&mut self, d: f64, u: f64, sign: f64, l: MoveLimits) {
        let (a, dec, vmax) = (l.acceleration, l.deceleration, l.velocity);
        let peak = libm::sqrt((2.0 * a * dec * d + dec * u * u) / (a + dec)).max(u);
        if peak > vmax {
            let x1 = (vmax * vmax - u * u) / (2.0 * a);
            let x3 = vmax * vmax / (2.0 * dec);
            self.push((vmax - u) / a, sign * a);
            self.push(((d - x1 - x3) / vmax).max(0.0), 0.0);
            self.push(vmax / dec, -sign * dec);
        } else {
            self.push((peak - u) / a, sign * a);
            self.push(peak / dec, -sign * dec);
        }
    }

    /// The time-optimal profile from velocity `v0` to rest `distance` away.
    pub(crate) fn plan(distance: f64, v0: f64, limits: MoveLimits) -> Self {
        let mut p = Self { v0, ..Self::REST };
        let sign = if distance >= 0.0 { 1.0 } else { -1.0 };
        let mut d = distance.abs();
        let mut u = sign * v0;
        let dec = limits.deceleration;
        if u < 0.0 {
            // Moving away: stop first; the way back adds to the distance.
            p.push(-u / dec, sign * dec);
            d += u * u / (2.0 * dec);
            u = 0.0;
        }
        let stopping = u * u / (2.0 * dec);
        if stopping > d {
            // Too fast to stop in time: stop past the target, come back.
            p.push(u / dec, -sign * dec);
            p.rest_to_rest(stopping - d, -sign, limits);
            return p;
        }
        if u > limits.velocity {
            p.push((u - limits.velocity) / dec, -sign * dec);
            d -= (u * u - limits.velocity * limits.velocity) / (2.0 * dec);
            u = limits.velocity;
        }
        p.speed_up_cruise_slow_down(d.max(0.0), u, sign, limits);
        p
    }

    /// The total duration in seconds.
    pub(crate) fn duration(&self) -> f64 {
        self.phases.iter().take(self.count).map(|&(t, _)| t).sum()
    }

    /// Position (from the start) and velocity `t` seconds after the start.
    pub(crate) fn at(&self, t: f64) -> (f64, f64) {
        let (mut x, mut v, mut left) = (0.0, self.v0, t.max(0.0));
        for &(duration, a) in self.phases.iter().take(self.count) {
            let dt = left.min(duration);
            x += v * dt + 0.5 * a * dt * dt;
            v += a * dt;
            left -= dt;
            if left <= 0.0 {
                return (x, v);
            }
        }
        // Past the end: at rest where the profile ends.
        (x, 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> MoveLimits {
        MoveLimits::new(1000.0, 4000.0, 2000.0).unwrap()
    }

    fn ends(p: &Trapezoid) -> (f64, f64) {
        p.at(p.duration() + 1.0)
    }

    fn check(p: &Trapezoid, distance: f64, l: MoveLimits, start_speed: f64) {
        let (x, _) = ends(p);
        assert!((x - distance).abs() < 1e-6, "ends at {x}, not {distance}");
        let steps = 4000;
        let dt = p.duration() / f64::from(steps);
        let mut last = p.at(0.0);
        for i in 1..=steps {
            let now = p.at(dt * f64::from(i));
            let a = (now.1 - last.1) / dt;
            assert!(
                now.1.abs() <= l.velocity().max(start_speed) + 1e-6,
                "speed {}",
                now.1
            );
            assert!(
                a.abs() <= l.acceleration().max(l.deceleration()) + 1e-3,
                "acc {a}"
            );
            last = now;
        }
    }

    #[test]
    fn reaches_the_target_at_rest_within_the_limits() {
        let l = limits();
        for (d, v0) in [
            (5000.0, 0.0),
            (100.0, 0.0),
            (-3000.0, 0.0),
            (5000.0, 600.0),
            (5000.0, 1500.0),
            (100.0, 900.0),
            (-200.0, 800.0),
            (3000.0, -700.0),
            (0.0, 500.0),
        ] {
            let p = Trapezoid::plan(d, v0, l);
            check(&p, d, l, v0.abs());
        }
    }

    #[test]
    fn triangle_and_trapezoid_durations() {
        let l = limits();
        // 5000 at 1000/s: 0.25 s up (125), 0.5 s down (250), 4.625 s cruise.
        let p = Trapezoid::plan(5000.0, 0.0, l);
        assert!((p.duration() - (0.25 + 4.625 + 0.5)).abs() < 1e-9);
        assert_eq!(MoveLimits::new(0.0, 1.0, 1.0), Err(CouplingError::BadLimit));
        assert!(MoveLimits::new(1.0, f64::NAN, 1.0).is_err());
    }
}
