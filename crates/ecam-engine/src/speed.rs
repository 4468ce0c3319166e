//! The master's speed, for sizing a ramp-in under limits.
//!
//! Measured over the last 32 ticks (bounded memory and work); since the
//! master is read in whole counts (plus the tracker's fraction), the
//! measurement can be short by up to one count over that window, so the
//! bound a ramp-in is sized for adds that count: a ramp sized for it keeps
//! its limits at the true speed.

use crate::MasterPosition;
use crate::rounding::exact_f64;

const WINDOW: usize = 32;
const _: () = assert!(WINDOW.is_power_of_two());

/// The followed master of the last ticks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MasterSpeed {
    /// Followed positions (whole counts and the fraction, kept apart so
    /// the tick stores two words, not a 128-bit shift) and the tick
    /// lengths that led to them, oldest first once full.
    counts: [i64; WINDOW],
    fractions: [u32; WINDOW],
    dts: [u32; WINDOW],
    /// The sum of `dts`, kept as they change: the window's time span is
    /// read without a pass over the ring (on the engaging tick of a
    /// ramp-in under limits, the dearest path, see docs/engine.md).
    total_us: u64,
    filled: usize,
    next: usize,
}

impl MasterSpeed {
    pub(crate) const fn new() -> Self {
        Self {
            counts: [0; WINDOW],
            fractions: [0; WINDOW],
            dts: [0; WINDOW],
            total_us: 0,
            filled: 0,
            next: 0,
        }
    }

    /// Takes this tick's followed position after `dt_us`.
    #[inline]
    pub(crate) fn update(&mut self, at: MasterPosition, dt_us: u32) {
        // WINDOW is a power of two: masking keeps the index in range
        // without a division or a bounds check.
        let slot = self.next & (WINDOW - 1);
        self.counts[slot] = at.counts;
        self.fractions[slot] = at.fraction;
        // Exact: the sum holds the slot's own length, and never exceeds
        // WINDOW × u32::MAX, far inside 64 bits (the wrapping forms are
        // the plain ones without an overflow check that cannot fire).
        self.total_us = self
            .total_us
            .wrapping_sub(u64::from(self.dts[slot]))
            .wrapping_add(u64::from(dt_us));
        self.dts[slot] = dt_us;
        self.next = (slot + 1) & (WINDOW - 1);
        self.filled += usize::from(self.filled < WINDOW);
    }

    /// Counts travelled from the reading in slot `from` to the one in
    /// `to`: their fixed-point difference (32 fraction bits) as a float,
    /// rounded once. In 64 bits where the difference of the whole counts
    /// is exact as a float (the sum of two exact terms, rounded once, is
    /// that same float), else through 128 bits.
    fn travel(&self, from: usize, to: usize) -> f64 {
        let counts = |slot: usize| self.counts.get(slot).copied().unwrap_or(0);
        let fraction = |slot: usize| i64::from(self.fractions.get(slot).copied().unwrap_or(0));
        let df = fraction(to) - fraction(from);
        match counts(to).checked_sub(counts(from)) {
            Some(dc) if dc.unsigned_abs() < 1 << 53 => dc as f64 + df as f64 / 4_294_967_296.0,
            _ => {
                let wide = (i128::from(counts(to)) - i128::from(counts(from))) << 32;
                exact_f64(wide + i128::from(df)) / 4_294_967_296.0
            }
        }
    }

    /// Time from the oldest reading (in slot `oldest`) to the newest, µs:
    /// the tick lengths after the oldest. Slots not yet filled hold 0, so
    /// it is the sum of every slot less the oldest's own.
    fn span_us(&self, oldest: usize) -> u64 {
        self.total_us - u64::from(self.dts.get(oldest).copied().unwrap_or(0))
    }

    /// The master's mean velocity over the window (counts/s, signed), 0
    /// before two readings: what a cam-out continues from.
    pub(crate) fn velocity(&self) -> f64 {
        if self.filled < 2 {
            return 0.0;
        }
        let newest = (self.next + WINDOW - 1) % WINDOW;
        let oldest = (self.next + WINDOW - self.filled) % WINDOW;
        let us = self.span_us(oldest);
        if us == 0 {
            return 0.0;
        }
        self.travel(oldest, newest) * 1.0e6 / us as f64
    }

    /// An upper bound of the master's speed (counts/s, either sign as
    /// magnitude), 0 before two readings.
    pub(crate) fn bound(&self) -> f64 {
        if self.filled < 2 {
            return 0.0;
        }
        let newest = (self.next + WINDOW - 1) % WINDOW;
        let oldest = (self.next + WINDOW - self.filled) % WINDOW;
        // Time from the oldest reading to the newest.
        let us = self.span_us(oldest);
        if us == 0 {
            return 0.0;
        }
        let counts = self.travel(oldest, newest).abs();
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

    use proptest::prelude::*;

    proptest! {
        /// The travel between two readings is their fixed-point
        /// difference as a float, rounded once (what the 128-bit route
        /// gives), near and far apart and across the whole range.
        #[test]
        fn the_travel_is_the_fixed_point_difference_rounded_once(
            from in any::<i64>(),
            apart in any::<i64>(),
            near in any::<bool>(),
            fractions in (any::<u32>(), any::<u32>()),
        ) {
            let to = if near { from.saturating_add(apart >> 24) } else { apart };
            let mut s = MasterSpeed::new();
            s.update(MasterPosition { counts: from, fraction: fractions.0 }, 0);
            s.update(MasterPosition { counts: to, fraction: fractions.1 }, 1);
            let fixed = |c: i64, f: u32| (i128::from(c) << 32) | i128::from(f);
            let wide = fixed(to, fractions.1) - fixed(from, fractions.0);
            prop_assert_eq!(s.travel(0, 1).to_bits(), (wide as f64 / 4_294_967_296.0).to_bits());
        }
    }

    proptest! {
        /// The window's time span, as it fills and after it wraps, is the
        /// tick lengths after the oldest reading, as a walk around the
        /// ring gives it.
        #[test]
        fn the_span_is_the_ticks_after_the_oldest(
            ticks in proptest::collection::vec(
                (-1_000_000i64..1_000_000, prop_oneof![0u32..5000, any::<u32>()]),
                2..100,
            ),
        ) {
            let mut s = MasterSpeed::new();
            let mut kept: std::vec::Vec<(i64, u32)> = std::vec::Vec::new();
            for &(counts, dt) in &ticks {
                s.update(MasterPosition { counts, fraction: 0 }, dt);
                kept.push((counts, dt));
                let window = &kept[kept.len().saturating_sub(WINDOW)..];
                let us: u64 = window.iter().skip(1).map(|&(_, dt)| u64::from(dt)).sum();
                let oldest = (s.next + WINDOW - s.filled) % WINDOW;
                if window.len() >= 2 {
                    prop_assert_eq!(s.span_us(oldest), us);
                    let travel = (window[window.len() - 1].0 - window[0].0) as f64;
                    let expected = if us == 0 { 0.0 } else { travel * 1.0e6 / us as f64 };
                    prop_assert!((s.velocity() - expected).abs() <= 1e-9 * expected.abs().max(1.0));
                }
            }
        }
    }
}
