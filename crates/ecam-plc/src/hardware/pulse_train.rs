//! The pulse-train generator behind PLSY/DPLSY.

/// A train of pulses at a fixed frequency, finite or endless.
///
/// Exact in simulated time: `frequency × elapsed µs` is accumulated in
/// integer pulse-microseconds and only whole pulses leave, so 3 Hz for one
/// second gives 3 pulses whatever the tick.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PulseTrain {
    frequency_hz: u32,
    /// Pulses still to send; `None` = endless (PLSY pulse count 0).
    remaining: Option<u64>,
    /// Fraction of a pulse carried over, in pulse·µs (< 1 000 000).
    carry: u64,
    /// Pulses sent so far.
    sent: u64,
}

impl PulseTrain {
    /// A train of `count` pulses (`0` = endless) at `frequency_hz`.
    pub fn new(frequency_hz: u32, count: u64) -> Self {
        Self {
            frequency_hz,
            remaining: (count > 0).then_some(count),
            carry: 0,
            sent: 0,
        }
    }

    /// Changes the frequency; the carried fraction is kept.
    pub fn set_frequency(&mut self, frequency_hz: u32) {
        self.frequency_hz = frequency_hz;
    }

    /// Pulses sent so far.
    #[cfg(test)]
    pub fn sent(&self) -> u64 {
        self.sent
    }

    /// True when a finite train has sent all its pulses.
    pub fn is_finished(&self) -> bool {
        self.remaining == Some(0)
    }

    /// Pulses due in the next `dt_us` microseconds.
    pub fn advance(&mut self, dt_us: u32) -> u64 {
        let total = self.carry + u64::from(self.frequency_hz) * u64::from(dt_us);
        let mut pulses = total / 1_000_000;
        self.carry = total % 1_000_000;
        if let Some(remaining) = self.remaining.as_mut() {
            pulses = pulses.min(*remaining);
            *remaining -= pulses;
        }
        self.sent = self.sent.saturating_add(pulses);
        pulses
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_hertz_for_a_second_is_three_pulses_whatever_the_tick() {
        let mut train = PulseTrain::new(3, 0);
        let pulses: u64 = (0..10_000).map(|_| train.advance(100)).sum();
        assert_eq!(pulses, 3);
    }

    #[test]
    fn carries_fractions_exactly() {
        let mut train = PulseTrain::new(1234, 0);
        let pulses: u64 = (0..100_000).map(|_| train.advance(100)).sum();
        assert_eq!(pulses, 12_340); // 10 s
    }

    #[test]
    fn stops_after_its_count() {
        let mut train = PulseTrain::new(100_000, 25);
        assert_eq!(train.advance(100), 10);
        assert_eq!(train.advance(100), 10);
        assert_eq!(train.advance(100), 5);
        assert!(train.is_finished());
        assert_eq!(train.advance(100), 0);
        assert_eq!(train.sent(), 25);
    }
}
