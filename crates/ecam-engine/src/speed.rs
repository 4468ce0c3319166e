//! The master's speed, for sizing a ramp-in under limits.
//!
//! Measured over the last 32 ticks (bounded memory and work); since the
//! master is read in whole counts (plus the tracker's fraction), the
//! measurement can be short by up to one count over that window, so the
//! bound a ramp-in is sized for adds that count: a ramp sized for it keeps
//! its limits at the true speed.

use crate::MasterPosition;

const WINDOW: usize = 32;

/// The followed master of the last ticks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MasterSpeed {
    /// Followed positions (fixed point, 32 fraction bits) and the tick
    /// lengths that led to them, oldest first once full.
    positions: [i128; WINDOW],
    dts: [u32; WINDOW],
    filled: usize,
    next: usize,
}

impl MasterSpeed {
    pub(crate) const fn new() -> Self {
        Self {
            positions: [0; WINDOW],
            dts: [0; WINDOW],
            filled: 0,
            next: 0,
        }
    }

    /// Takes this tick's followed position after `dt_us`.
    pub(crate) fn update(&mut self, at: MasterPosition, dt_us: u32) {
        let fixed = (i128::from(at.counts) << 32) | i128::from(at.fraction);
        if let (Some(p), Some(d)) = (
            self.positions.get_mut(self.next),
            self.dts.get_mut(self.next),
        ) {
            *p = fixed;
            *d = dt_us;
        }
        self.next = (self.next + 1) % WINDOW;
        self.filled = (self.filled + 1).min(WINDOW);
    }

    /// The master's mean velocity over the window (counts/s, signed), 0
    /// before two readings: what a cam-out continues from.
    pub(crate) fn velocity(&self) -> f64 {
        if self.filled < 2 {
            return 0.0;
        }
        let newest = (self.next + WINDOW - 1) % WINDOW;
        let oldest = (self.next + WINDOW - self.filled) % WINDOW;
        let mut us: u64 = 0;
        for i in 1..self.filled {
            us += u64::from(self.dts.get((oldest + i) % WINDOW).copied().unwrap_or(0));
        }
        if us == 0 {
            return 0.0;
        }
        let travel = self.positions.get(newest).copied().unwrap_or(0)
            - self.positions.get(oldest).copied().unwrap_or(0);
        travel as f64 / 4_294_967_296.0 * 1.0e6 / us as f64
    }

    /// An upper bound of the master's speed (counts/s, either sign as
    /// magnitude), 0 before two readings.
    pub(crate) fn bound(&self) -> f64 {
        if self.filled < 2 {
            return 0.0;
        }
        let newest = (self.next + WINDOW - 1) % WINDOW;
        let oldest = (self.next + WINDOW - self.filled) % WINDOW;
        // Time from the oldest reading to the newest: the dts after the oldest.
        let mut us: u64 = 0;
        for i in 1..self.filled {
            us += u64::from(self.dts.get((oldest + i) % WINDOW).copied().unwrap_or(0));
        }
        if us == 0 {
            return 0.0;
        }
        let travel = self.positions.get(newest).copied().unwrap_or(0)
            - self.positions.get(oldest).copied().unwrap_or(0);
        let counts = (travel as f64 / 4_294_967_296.0).abs();
        if counts == 0.0 {
            return 0.0;
        }
        (counts + 1.0) * 1.0e6 / us as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bound_covers_a_count_of_quantisation() {
        let mut s = MasterSpeed::new();
        for (i, counts) in [0, 1, 2, 3, 5, 6, 7, 8].into_iter().enumerate() {
            s.update(
                MasterPosition {
                    counts,
                    fraction: 0,
                },
                if i == 0 { 0 } else { 1000 },
            );
        }
        // 8 counts in 7 ms, plus one count: 9/7 counts per ms.
        assert!((s.bound() - 9.0 / 7.0 * 1000.0).abs() < 1e-6);
    }
}
