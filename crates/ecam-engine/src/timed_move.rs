//! A move over time to a whole-unit target, the state shared by
//! `MC_Phasing` (a shift of the master the slave sees, in master counts)
//! and `MC_MoveSuperimposed` (a move added to the slave, in pulses).
//!
//! Positions are fixed point with 32 fraction bits. A move starts from
//! where the last one stands, with the velocity it has (a command that
//! replaces a running one takes over without a velocity step), follows a
//! [`Trapezoid`] as a function of the whole microseconds since it started,
//! and ends exactly on its target, a whole number of units: once done the
//! shift is an integer again and nothing drifts. Within a phase of the
//! profile the position never steps back against its velocity, even by the
//! float's last bit.

use crate::trapezoid::{MoveLimits, Trapezoid};

/// One unit in fixed point.
pub(crate) const ONE: i128 = 1 << 32;

/// A timed move and where it stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TimedMove {
    from: i128,
    to: i128,
    profile: Trapezoid,
    duration: f64,
    elapsed_us: u64,
    position: i128,
    velocity: f64,
    active: bool,
}

/// `v` (fixed point) rounded to whole units, halves upwards (monotonic).
pub(crate) fn whole(v: i128) -> i128 {
    (v + ONE / 2) >> 32
}

/// Units as a float from fixed point.
pub(crate) fn to_units(v: i128) -> f64 {
    v as f64 / ONE as f64
}

impl TimedMove {
    /// Standing at `position` (fixed point).
    pub(crate) const fn at_rest(position: i128) -> Self {
        Self {
            from: position,
            to: position,
            profile: Trapezoid::REST,
            duration: 0.0,
            elapsed_us: 0,
            position,
            velocity: 0.0,
            active: false,
        }
    }

    /// Where it stands (fixed point).
    pub(crate) const fn position(&self) -> i128 {
        self.position
    }

    /// Its velocity now, units/s.
    pub(crate) const fn velocity(&self) -> f64 {
        self.velocity
    }

    /// A move is running.
    pub(crate) const fn is_active(&self) -> bool {
        self.active
    }

    /// Starts a move to `to` (whole units, fixed point) from where it
    /// stands, with its velocity, under `limits`.
    pub(crate) fn start(&mut self, to: i128, limits: MoveLimits) {
        let to = whole(to) << 32;
        self.from = self.position;
        self.to = to;
        self.profile = Trapezoid::plan(to_units(to - self.position), self.velocity, limits);
        self.duration = self.profile.duration();
        self.elapsed_us = 0;
        // Done at the next tick, even when already there.
        self.active = true;
        if self.duration <= 0.0 {
            self.position = to;
            self.velocity = 0.0;
        }
    }

    /// Brings a running move to rest at `deceleration` on the first whole
    /// unit at or beyond its stopping point (so it never slows down harder
    /// than asked, nor turns back).
    pub(crate) fn halt(&mut self, deceleration: f64) {
        if !self.active {
            return;
        }
        let v = self.velocity;
        let stopping = v * v / (2.0 * deceleration) * v.signum();
        let at = to_units(self.position) + stopping;
        let end = if v >= 0.0 {
            libm::ceil(at)
        } else {
            libm::floor(at)
        };
        if !end.is_finite() || end.abs() > 4.0e27 {
            self.stop();
            return;
        }
        // A cruise at the speed it has, then the deceleration asked for.
        let speed = v.abs().max(f64::MIN_POSITIVE);
        match MoveLimits::new(speed, deceleration, deceleration) {
            Ok(limits) => self.start((end as i128) << 32, limits),
            Err(_) => self.stop(),
        }
    }

    /// Ends a running move where it stands, on the nearest whole unit.
    pub(crate) fn stop(&mut self) {
        self.position = whole(self.position) << 32;
        self.from = self.position;
        self.to = self.position;
        self.velocity = 0.0;
        self.active = false;
    }

    /// Advances by `dt_us`; returns `true` on the tick the move ends.
    pub(crate) fn advance(&mut self, dt_us: u32) -> bool {
        if !self.active {
            return false;
        }
        self.elapsed_us = self.elapsed_us.saturating_add(u64::from(dt_us));
        let t = self.elapsed_us as f64 * 1e-6;
        if t >= self.duration {
            self.position = self.to;
            self.velocity = 0.0;
            self.active = false;
            return true;
        }
        let (x, v) = self.profile.at(t);
        let scaled = x * ONE as f64;
        let step = if scaled.is_finite() {
            libm::round(scaled) as i128
        } else {
            0
        };
        let next = self.from.saturating_add(step);
        // Never back against the velocity (a float's last bit would do it).
        self.position = if v > 0.0 {
            next.max(self.position)
        } else if v < 0.0 {
            next.min(self.position)
        } else {
            next
        };
        self.velocity = v;
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_exactly_on_whole_units_and_never_steps_back() {
        let limits = MoveLimits::new(1000.0, 5000.0, 5000.0).unwrap();
        let mut m = TimedMove::at_rest(0);
        m.start(1234 * ONE, limits);
        let mut last = m.position();
        let mut ticks = 0;
        while !m.advance(250) {
            assert!(m.position() >= last);
            last = m.position();
            ticks += 1;
            assert!(ticks < 100_000);
        }
        assert_eq!(m.position(), 1234 * ONE);
        // Replaced while running: takes over with its velocity.
        m.start(0, limits);
        for _ in 0..400 {
            m.advance(250);
        }
        let v = m.velocity();
        m.start(-500 * ONE, limits);
        m.advance(250);
        assert!((m.velocity() - v).abs() < 5000.0 * 250e-6 + 1e-9);
        // Halt lands on a whole unit ahead of the stopping point.
        m.halt(5000.0);
        let before = m.position();
        while !m.advance(250) {}
        assert_eq!(m.position() % ONE, 0);
        assert!(m.position() <= before);
    }
}
