//! Reading the master (S1) every hardware tick as an unwrapped position.
//!
//! A counter or register wraps at 16 or 32 bits; the cam needs a position that
//! keeps counting, so each reading is turned into a signed step from the last
//! one (the smaller way round) and added up in `i64`.
//!
//! The time base is exact time: it reads 0 at the instant the cam starts
//! ([`MasterReader::restart_time_base`]) and then counts periods of simulated
//! time with the part of a count already elapsed as a fraction, so a coarse
//! time base (K10: one count per millisecond) moves the cam a little every
//! 100 µs tick instead of a whole count's pulses at once. It never drifts:
//! the count after any run is exactly `floor(elapsed / period)`.

use core::num::NonZeroU32;

use ecam_engine::{MasterPosition, TimeBase};

use super::operands::MasterOperand;
use crate::device::C_32BIT_FIRST;
use crate::devices::Devices;

/// Unwrapped master position from S1.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MasterReader {
    operand: MasterOperand,
    last_raw: Option<i32>,
    position: i64,
    time_base: Option<TimeBase>,
}

impl MasterReader {
    /// A reader that takes the first reading as the starting position.
    pub fn new(operand: MasterOperand) -> Self {
        let time_base = match operand {
            MasterOperand::TimeBase(period) => Some(TimeBase::new(
                NonZeroU32::new(period).unwrap_or(NonZeroU32::MIN),
            )),
            MasterOperand::Counter(_) | MasterOperand::Register(_) => None,
        };
        Self {
            operand,
            last_raw: None,
            position: 0,
            time_base,
        }
    }

    /// True for a `Kn` time base.
    pub fn is_time_base(&self) -> bool {
        self.time_base.is_some()
    }

    /// Forgets the history: the next reading starts again from the raw value
    /// (time base: from 0).
    pub fn reset(&mut self) {
        self.last_raw = None;
        self.position = 0;
        self.restart_time_base();
    }

    /// A time base reads 0 from now on (the cam's start instant); a counter
    /// or register master is not affected.
    pub fn restart_time_base(&mut self) {
        if let Some(time_base) = &mut self.time_base {
            time_base.restart();
            self.position = 0;
        }
    }

    /// The position of the last reading (time base: with its fraction).
    pub fn current(&self) -> MasterPosition {
        match &self.time_base {
            Some(time_base) => MasterPosition {
                counts: time_base.position(),
                fraction: time_base.fraction(),
            },
            None => MasterPosition {
                counts: self.position,
                fraction: 0,
            },
        }
    }

    /// The last position read, in whole counts.
    pub fn position(&self) -> i64 {
        self.position
    }

    /// Reads S1 after `dt_us` of simulated time and returns the position.
    pub fn read(&mut self, devices: &Devices, dt_us: u32) -> MasterPosition {
        let (raw, sixteen_bit) = match self.operand {
            MasterOperand::TimeBase(_) => {
                if let Some(time_base) = &mut self.time_base {
                    self.position = time_base.advance(dt_us);
                }
                return self.current();
            }
            MasterOperand::Counter(n) => (devices.counter(n).unwrap_or(0), n < C_32BIT_FIRST),
            MasterOperand::Register(n) => (devices.dword(n).unwrap_or(0), false),
        };
        match self.last_raw {
            None => self.position = i64::from(raw),
            Some(last) => {
                let step = if sixteen_bit {
                    i64::from((raw as i16).wrapping_sub(last as i16))
                } else {
                    i64::from(raw.wrapping_sub(last))
                };
                self.position = self.position.saturating_add(step);
            }
        }
        self.last_raw = Some(raw);
        self.current()
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn unwraps_a_32_bit_counter() {
        let mut dev = Devices::new();
        let mut m = MasterReader::new(MasterOperand::Counter(231));
        dev.set_counter(231, i32::MAX - 1).unwrap();
        assert_eq!(m.read(&dev, 100).counts, i64::from(i32::MAX - 1));
        dev.set_counter(231, i32::MIN + 1).unwrap();
        assert_eq!(m.read(&dev, 100).counts, i64::from(i32::MAX) + 2);
    }

    #[test]
    fn unwraps_a_16_bit_counter() {
        let mut dev = Devices::new();
        let mut m = MasterReader::new(MasterOperand::Counter(5));
        dev.set_counter(5, 32767).unwrap();
        m.read(&dev, 100);
        dev.set_counter(5, 32768).unwrap();
        assert_eq!(m.read(&dev, 100).counts, 32768);
    }

    #[test]
    fn time_base_counts_exactly() {
        let dev = Devices::new();
        let mut m = MasterReader::new(MasterOperand::TimeBase(3));
        let mut last = MasterPosition::default();
        for _ in 0..31 {
            last = m.read(&dev, 100);
        }
        // 3100 µs at 300 µs per count: 10 counts and a third.
        assert_eq!(last.counts, 10);
        assert_eq!(last.fraction, (1u64 << 32).div_ceil(3) as u32 - 1);
    }

    #[test]
    fn the_time_base_reads_zero_at_the_start_instant() {
        let dev = Devices::new();
        let mut m = MasterReader::new(MasterOperand::TimeBase(10));
        for _ in 0..25 {
            m.read(&dev, 100);
        }
        m.restart_time_base();
        assert_eq!(m.current(), MasterPosition::default());
        let p = m.read(&dev, 100);
        assert_eq!(
            (p.counts, p.fraction),
            (0, (1u64 << 32).div_ceil(10) as u32 - 1)
        );
    }
}
