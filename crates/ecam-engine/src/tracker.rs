//! Estimating the master between its updates.
//!
//! A pulse output is ticked far more often than a coarse master changes: a
//! high-speed counter fed at 1 kHz, or a register the PLC program writes
//! once per scan, reads the same value for ten 100 µs ticks and then jumps
//! by a count. Taken as it is, such a master makes the slave move in bursts
//! (all of one count's pulses in one tick, none in the next nine), which a
//! drive sees as a multiple of the commanded speed.
//!
//! [`MasterFilter::Interpolate`] is the drive-side fine interpolator a motion
//! engineer knows from cyclic-synchronous position mode: each time the
//! reading changes, the estimate sets off from where it is towards the new
//! reading and covers the distance in the mean of the last four intervals
//! between changes. So
//! - at constant speed the estimate moves at the master's speed, one update
//!   interval behind the reading;
//! - it never passes the reading and never moves away from it, so it cannot
//!   overshoot when the master stops, nor reverse unless the master does;
//! - once the master stands still the estimate lands exactly on the reading
//!   (zero drift: the cam is again the exact function of the master).
//!
//! Transient: after a change of speed the interval estimate settles within
//! four changes of the reading; meanwhile the estimate lags by at most the
//! distance the master covers in `max_interval_us`. A reading that changes
//! after a rest longer than `max_interval_us` is reached in
//! `max_interval_us` (the master's speed out of rest is unknown).
//!
//! Positions are fixed point with 32 fractional bits, so a master read every
//! tick at full resolution ([`MasterFilter::Direct`]) and an exact time base
//! with its fraction pass through unchanged.

use core::num::NonZeroU32;

/// How the axis turns master readings into the position it follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MasterFilter {
    /// Each reading is the master position (a master that changes every
    /// tick, or an exact time base with [`crate::TickInput::master_fraction`]).
    Direct,
    /// Interpolate between changes of the reading (see the module docs).
    Interpolate {
        /// Longest interval between two changes taken as one update (a
        /// longer one is a rest): bounds the lag when the master starts.
        max_interval_us: NonZeroU32,
    },
}

impl MasterFilter {
    /// Interpolation with a 20 ms rest limit: fits masters updated from
    /// every tick down to 50 Hz.
    pub const INTERPOLATE: Self = Self::Interpolate {
        max_interval_us: match NonZeroU32::new(20_000) {
            Some(v) => v,
            None => NonZeroU32::MIN,
        },
    };
}

/// One count in fixed point.
const ONE: i128 = 1 << 32;
/// Intervals averaged for the update period.
const INTERVALS: usize = 4;

/// A master position with a fraction of a count.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MasterPosition {
    /// Whole counts (floor).
    pub counts: i64,
    /// Fraction of a count above `counts`, in 1/2^32.
    pub fraction: u32,
}

impl MasterPosition {
    fn from_fixed(v: i128) -> Self {
        let counts = v >> 32;
        Self {
            counts: i64::try_from(counts).unwrap_or(if counts < 0 { i64::MIN } else { i64::MAX }),
            // The low 32 bits of a two's complement value are the floor's fraction.
            fraction: (v & (ONE - 1)) as u32,
        }
    }

    fn fixed(counts: i64, fraction: u32) -> i128 {
        (i128::from(counts) << 32) | i128::from(fraction)
    }

    /// The whole count next to this position on the side of `from`: the
    /// farthest count from `from` that the position has fully reached.
    /// Below `from` with a fraction, that is the count above (`counts` is
    /// the floor, which the position has not reached yet). A ramp or
    /// blend that started at `from` is over only once this count is past
    /// its end, so it never ends early while the master runs backwards.
    pub(crate) fn count_toward(&self, from: i64) -> i64 {
        if self.fraction != 0 && self.counts < from {
            self.counts.saturating_add(1)
        } else {
            self.counts
        }
    }
}

/// The master-velocity tracker of one axis (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MasterTracker {
    filter: MasterFilter,
    started: bool,
    reading: i128,
    estimate: i128,
    from: i128,
    elapsed_us: u64,
    window_us: u64,
    since_change_us: u64,
    intervals: [u32; INTERVALS],
    filled: usize,
    next: usize,
}

impl MasterTracker {
    /// A tracker that takes its first reading as it is.
    pub const fn new(filter: MasterFilter) -> Self {
        Self {
            filter,
            started: false,
            reading: 0,
            estimate: 0,
            from: 0,
            elapsed_us: 0,
            window_us: 0,
            since_change_us: 0,
            intervals: [0; INTERVALS],
            filled: 0,
            next: 0,
        }
    }

    /// The filter in use.
    pub const fn filter(&self) -> MasterFilter {
        self.filter
    }

    /// Forgets the history: the next reading is taken as it is.
    pub fn reset(&mut self) {
        *self = Self::new(self.filter);
    }

    /// True when the estimate stands on the last reading.
    pub fn settled(&self) -> bool {
        self.estimate == self.reading
    }

    /// The estimate after the last update.
    pub fn estimate(&self) -> MasterPosition {
        MasterPosition::from_fixed(self.estimate)
    }

    /// Takes this tick's reading (`counts` + `fraction`/2^32) after `dt_us`
    /// and returns the position to follow.
    #[inline]
    pub fn update(&mut self, counts: i64, fraction: u32, dt_us: u32) -> MasterPosition {
        let reading = MasterPosition::fixed(counts, fraction);
        let max_interval = match self.filter {
            MasterFilter::Direct => {
                self.started = true;
                self.reading = reading;
                self.estimate = reading;
                // The reading as it came (what `from_fixed` would give back).
                return MasterPosition { counts, fraction };
            }
            MasterFilter::Interpolate { max_interval_us } => u64::from(max_interval_us.get()),
        };
        if !self.started {
            self.started = true;
            self.reading = reading;
            self.estimate = reading;
            self.from = reading;
            return MasterPosition::from_fixed(reading);
        }
        self.since_change_us = self.since_change_us.saturating_add(u64::from(dt_us));
        if reading != self.reading {
            let interval = self.since_change_us.clamp(1, max_interval);
            self.since_change_us = 0;
            self.push_interval(interval);
            self.from = self.estimate;
            self.reading = reading;
            self.elapsed_us = 0;
        }
        self.elapsed_us = self.elapsed_us.saturating_add(u64::from(dt_us));
        self.estimate = if self.elapsed_us >= self.window_us {
            self.reading
        } else {
            let distance = self.reading - self.from;
            distance
                .checked_mul(i128::from(self.elapsed_us))
                .map_or(self.reading, |d| {
                    self.from + d.div_euclid(i128::from(self.window_us))
                })
        };
        MasterPosition::from_fixed(self.estimate)
    }

    fn push_interval(&mut self, interval: u64) {
        let interval = u32::try_from(interval).unwrap_or(u32::MAX);
        if let Some(slot) = self.intervals.get_mut(self.next) {
            *slot = interval;
        }
        self.next = (self.next + 1) % INTERVALS;
        self.filled = (self.filled + 1).min(INTERVALS);
        let sum: u64 = self
            .intervals
            .iter()
            .take(self.filled)
            .map(|&i| u64::from(i))
            .sum();
        // filled >= 1 here.
        self.window_us = (sum / self.filled as u64).max(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    fn positions(filter: MasterFilter, readings: &[i64], dt: u32) -> Vec<f64> {
        let mut t = MasterTracker::new(filter);
        readings
            .iter()
            .map(|&r| {
                let e = t.update(r, 0, dt);
                e.counts as f64 + f64::from(e.fraction) / 4_294_967_296.0
            })
            .collect()
    }

    #[test]
    fn a_coarse_master_is_spread_over_the_ticks() {
        // One count every 10 ticks of 100 µs.
        let readings: Vec<i64> = (0..200).map(|i| i / 10).collect();
        let est = positions(MasterFilter::INTERPOLATE, &readings, 100);
        // After the interval average has settled (4 changes), every tick
        // moves a tenth of a count.
        for w in est[60..].windows(2) {
            let step = w[1] - w[0];
            assert!((step - 0.1).abs() < 1e-6, "step {step}");
        }
    }

    #[test]
    fn it_never_passes_the_reading_and_lands_on_it_at_rest() {
        let mut readings: Vec<i64> = (0..100).map(|i| i / 10).collect();
        readings.extend(core::iter::repeat_n(9, 300));
        let est = positions(MasterFilter::INTERPOLATE, &readings, 100);
        for (e, r) in est.iter().zip(&readings) {
            assert!(*e <= *r as f64 + 1e-9);
        }
        for w in est.windows(2) {
            assert!(w[1] >= w[0], "never moves back while the master does not");
        }
        assert_eq!(*est.last().unwrap(), 9.0);
    }

    #[test]
    fn direct_passes_the_reading_and_its_fraction_through() {
        let mut t = MasterTracker::new(MasterFilter::Direct);
        assert_eq!(
            t.update(-3, 1 << 31, 100),
            MasterPosition {
                counts: -3,
                fraction: 1 << 31
            }
        );
        assert!(t.settled());
    }

    #[test]
    fn a_reversing_master_is_followed_back() {
        let readings: Vec<i64> = (0..100)
            .map(|i| if i < 50 { i / 5 } else { 10 - (i - 50) / 5 })
            .collect();
        let est = positions(MasterFilter::INTERPOLATE, &readings, 100);
        let last = *est.last().unwrap();
        assert!(last < 2.0, "followed the master back: {last}");
    }

    #[test]
    fn huge_jumps_do_not_overflow() {
        let mut t = MasterTracker::new(MasterFilter::INTERPOLATE);
        t.update(i64::MIN, 0, 100);
        t.update(i64::MAX, u32::MAX, u32::MAX);
        let e = t.update(i64::MAX, u32::MAX, 100);
        assert_eq!(e.counts, i64::MAX);
    }
}
