//! Master sources: turning raw readings into one unwrapped `i64` position.
//!
//! Document 003 names three master kinds (a high-speed counter C, a D
//! register, the virtual time base K); document 002 adds the commanded or
//! actual position of another axis. The engine's tick takes an `i64`; these
//! helpers produce it exactly:
//! - a 32-bit counter (up/down, wrapping) → [`Unwrap32`];
//! - a register value → itself (through [`Unwrap32`] if it may wrap);
//! - the time base → [`TimeBase`];
//! - another axis → its [`crate::TickOutput::slave`] (commanded) or
//!   [`crate::TickOutput::emitted`] (actual output).

use core::num::{NonZeroU32, NonZeroU64};

/// Unwraps a wrapping 32-bit counter into an unbounded position.
///
/// Between two readings the counter must move less than 2^31 counts, which
/// any real counter read every few milliseconds does; the change is taken as
/// the shortest signed distance, so counting down through zero works too.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unwrap32 {
    last_raw: u32,
    position: i64,
}

impl Unwrap32 {
    /// Starts at `first_raw` read as a signed 32-bit value.
    pub const fn new(first_raw: u32) -> Self {
        Self {
            last_raw: first_raw,
            position: first_raw as i32 as i64,
        }
    }

    /// Takes a new raw reading and returns the unwrapped position.
    pub fn update(&mut self, raw: u32) -> i64 {
        let delta = raw.wrapping_sub(self.last_raw) as i32;
        self.last_raw = raw;
        self.position = self.position.saturating_add(i64::from(delta));
        self.position
    }

    /// The unwrapped position after the last reading.
    pub const fn position(&self) -> i64 {
        self.position
    }
}

/// Document 003's virtual time base: one master count every K × 100 µs.
///
/// The microseconds that do not yet make a count are carried, so the count
/// after any sequence of ticks is exactly `floor(total_us / (K × 100))`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TimeBase {
    period_us: u64,
    carried_us: u64,
    position: i64,
}

impl TimeBase {
    /// One count every `period_100us` × 100 µs (K1 = 100 µs, K10 = 1 ms).
    pub fn new(period_100us: NonZeroU32) -> Self {
        Self {
            period_us: u64::from(period_100us.get()) * 100,
            carried_us: 0,
            position: 0,
        }
    }

    /// Advances time by `dt_us` and returns the master position.
    pub fn advance(&mut self, dt_us: u32) -> i64 {
        // period_us >= 100 and carried_us < period_us, so the sum cannot overflow.
        let total = self.carried_us + u64::from(dt_us);
        let counts = total / self.period_us;
        self.carried_us = total % self.period_us;
        self.position = self
            .position
            .saturating_add(i64::try_from(counts).unwrap_or(i64::MAX));
        self.position
    }

    /// The master position after the last advance.
    pub const fn position(&self) -> i64 {
        self.position
    }

    /// The part of a count that has elapsed since the last whole count, in
    /// 1/2^32 of a count ([`crate::TickInput::master_fraction`]): the time
    /// base is exact time, so a cam on a coarse time base (K10: one count per
    /// millisecond) is spread over every tick instead of stepping once per
    /// count.
    pub fn fraction(&self) -> u32 {
        // carried_us < period_us, so the quotient is below 2^32.
        u32::try_from((u128::from(self.carried_us) << 32) / u128::from(self.period_us))
            .unwrap_or(u32::MAX)
    }

    /// Starts again at 0 with nothing carried (the cam's engage instant).
    pub fn restart(&mut self) {
        self.carried_us = 0;
        self.position = 0;
    }
}

/// Unwraps a single-turn master (document 001): the reading lies in
/// `[0, turn)` and wraps; the shortest way round is taken between readings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct TurnUnwrap {
    turn: i64,
    last: Option<(i64, i64)>,
}

impl TurnUnwrap {
    pub(crate) fn new(turn: NonZeroU64) -> Self {
        Self {
            turn: i64::try_from(turn.get()).unwrap_or(i64::MAX),
            last: None,
        }
    }

    /// The unwrapped master for a raw turn reading (taken modulo the turn).
    pub(crate) fn update(&mut self, raw: i64) -> i64 {
        let raw = raw.rem_euclid(self.turn);
        let position = match self.last {
            None => raw,
            Some((last_raw, last_position)) => {
                let mut delta = raw - last_raw;
                if delta > self.turn / 2 {
                    delta -= self.turn;
                } else if delta < -(self.turn / 2) {
                    delta += self.turn;
                }
                last_position.saturating_add(delta)
            }
        };
        self.last = Some((raw, position));
        position
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counter_unwraps_both_ways() {
        let mut u = Unwrap32::new(u32::MAX - 1);
        assert_eq!(u.position(), -2);
        assert_eq!(u.update(3), 3);
        let mut u = Unwrap32::new(0x7FFF_FFF0);
        assert_eq!(u.update(0x8000_0010), 0x8000_0010);
        assert_eq!(u.update(0x7FFF_FFF0), 0x7FFF_FFF0);
    }

    #[test]
    fn time_base_carries_the_remainder() {
        let Some(k3) = NonZeroU32::new(3) else {
            return;
        };
        let mut t = TimeBase::new(k3);
        // 300 µs per count: 7 ticks of 100 µs give 2 counts, 100 µs carried.
        for _ in 0..7 {
            t.advance(100);
        }
        assert_eq!(t.position(), 2);
        assert_eq!(t.advance(200), 3);
        assert_eq!(t.advance(1_000_000), 3 + 3333);
    }

    #[test]
    fn turn_unwraps_over_the_seam() {
        let Some(turn) = NonZeroU64::new(30000) else {
            return;
        };
        let mut t = TurnUnwrap::new(turn);
        assert_eq!(t.update(29000), 29000);
        assert_eq!(t.update(1000), 31000);
        assert_eq!(t.update(29500), 29500);
        assert_eq!(t.update(29500 + 30000), 29500);
    }
}
