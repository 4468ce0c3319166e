//! The master's cycle locked to the drives' distributed clock: each
//! cycle's frame reads the reference drive's system time as it passes;
//! from it the master knows how long before the next SYNC0 edge its frame
//! arrived (the *lead*), and steers its own wake-ups so the lead settles
//! on the configured SYNC0 shift.
//!
//! SYNC0 edges fall on whole multiples of the cycle in DC time (ethercrab
//! rounds the first edge so), so the lead of a frame read at DC time `t`
//! is `cycle − t mod cycle`. A proportional-integral step moves the next
//! deadline by at most a tenth of a cycle per cycle; the integral takes up
//! the difference between the host's crystal and the reference drive's.

use std::time::Duration;

/// Upper bounds of the lead-error buckets, µs (the last bucket is open).
pub const ERROR_BUCKETS_US: [u64; 8] = [1, 2, 5, 10, 20, 50, 100, 200];

/// The lock and what it measured.
#[derive(Clone, Debug)]
pub struct Sync0Lock {
    period_ns: i64,
    shift_ns: i64,
    integral: i64,
    locked: bool,
    /// Frames measured.
    pub frames: u64,
    /// Smallest and largest lead measured, ns.
    pub lead_min_ns: i64,
    /// Largest lead measured, ns.
    pub lead_max_ns: i64,
    /// Sum of leads, for the mean.
    pub lead_sum_ns: i128,
    /// |lead − shift| per bucket of [`ERROR_BUCKETS_US`] (+ one open).
    pub error_counts: [u64; ERROR_BUCKETS_US.len() + 1],
}

impl Sync0Lock {
    /// A lock for SYNC0 every `period`, the frame due `shift` before it.
    pub fn new(period: Duration, shift: Duration) -> Self {
        let period_ns = i64::try_from(period.as_nanos()).unwrap_or(i64::MAX).max(1);
        Self {
            period_ns,
            shift_ns: i64::try_from(shift.as_nanos()).unwrap_or(0).min(period_ns),
            integral: 0,
            locked: false,
            frames: 0,
            lead_min_ns: i64::MAX,
            lead_max_ns: i64::MIN,
            lead_sum_ns: 0,
            error_counts: [0; ERROR_BUCKETS_US.len() + 1],
        }
    }

    /// The configured shift, ns.
    pub fn shift_ns(&self) -> i64 {
        self.shift_ns
    }

    /// The lead of a frame read at DC time `dc_time`: how long before
    /// the next SYNC0 edge it passed the reference drive, ns.
    pub fn lead(&self, dc_time: u64) -> i64 {
        let into = i64::try_from(dc_time % self.period_ns.unsigned_abs()).unwrap_or(0);
        self.period_ns - into
    }

    /// Takes one frame's DC time (recorded only while `measure`, i.e.
    /// once the line runs) and returns how far to move the next deadline,
    /// ns (positive: later). The first frame moves it the whole way; after
    /// that each step is bounded.
    pub fn step(&mut self, dc_time: u64, measure: bool) -> i64 {
        let lead = self.lead(dc_time);
        // Positive: the frame came too early; wrapped to ± half a cycle.
        let mut error = lead - self.shift_ns;
        let half = self.period_ns / 2;
        if error > half {
            error -= self.period_ns;
        } else if error < -half {
            error += self.period_ns;
        }
        if measure {
            self.frames = self.frames.saturating_add(1);
            self.lead_min_ns = self.lead_min_ns.min(lead);
            self.lead_max_ns = self.lead_max_ns.max(lead);
            self.lead_sum_ns = self.lead_sum_ns.saturating_add(i128::from(lead));
            let us = error.unsigned_abs() / 1000;
            let bucket = ERROR_BUCKETS_US
                .iter()
                .position(|&b| us < b)
                .unwrap_or(ERROR_BUCKETS_US.len());
            self.error_counts[bucket] = self.error_counts[bucket].saturating_add(1);
        }
        if !self.locked {
            self.locked = true;
            return error;
        }
        self.integral = (self.integral + error).clamp(-self.period_ns * 64, self.period_ns * 64);
        let limit = self.period_ns / 10;
        (error / 4 + self.integral / 64).clamp(-limit, limit)
    }

    /// Mean lead, ns (0 before any frame).
    pub fn lead_mean_ns(&self) -> i64 {
        if self.frames == 0 {
            return 0;
        }
        i64::try_from(self.lead_sum_ns / i128::from(self.frames)).unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A master whose wake-ups are offset from SYNC0 and whose crystal
    /// runs 50 ppm fast settles on the shift.
    #[test]
    fn settles_on_the_shift_despite_drift() {
        let period = 1_000_000i64;
        let mut lock = Sync0Lock::new(
            Duration::from_nanos(1_000_000),
            Duration::from_nanos(250_000),
        );
        // DC time at the first frame: 730 µs into a cycle.
        let mut dc = 5_000_730_000i64;
        let mut last_error = 0;
        for k in 0..4000 {
            let correction = lock.step(u64::try_from(dc).unwrap(), k > 3000);
            // The host's period is 50 ns long against DC; the correction
            // moves the next frame.
            dc += period + 50 + correction;
            last_error = lock.lead(u64::try_from(dc).unwrap()) - 250_000;
        }
        assert!(last_error.abs() < 200, "{last_error}");
        assert_eq!(lock.frames, 999);
        assert!((lock.lead_mean_ns() - 250_000).abs() < 500);
        assert_eq!(lock.error_counts[0], 999, "all within 1 µs");
    }
}
