//! Reading the master (S1) every hardware tick as an unwrapped position.
//!
//! A counter or register wraps at 16 or 32 bits; the cam needs a position that
//! keeps counting, so each reading is turned into a signed step from the last
//! one (the smaller way round) and added up in `i64`. The time base counts
//! exact multiples of its period from the moment the DECAM was enabled, with
//! the remainder carried, so it never drifts.

use super::operands::MasterOperand;
use crate::devices::{C_32BIT_FIRST, Devices};

/// Unwrapped master position from S1.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MasterReader {
    operand: MasterOperand,
    last_raw: Option<i32>,
    position: i64,
    elapsed_us: u64,
}

impl MasterReader {
    /// A reader that takes the first reading as the starting position.
    pub fn new(operand: MasterOperand) -> Self {
        Self {
            operand,
            last_raw: None,
            position: 0,
            elapsed_us: 0,
        }
    }

    /// True for a `Kn` time base.
    pub fn is_time_base(&self) -> bool {
        matches!(self.operand, MasterOperand::TimeBase(_))
    }

    /// Forgets the history: the next reading starts again from the raw value
    /// (time base: from 0).
    pub fn reset(&mut self) {
        self.last_raw = None;
        self.position = 0;
        self.elapsed_us = 0;
    }

    /// The last position read.
    pub fn position(&self) -> i64 {
        self.position
    }

    /// Reads S1 after `dt_us` of simulated time and returns the position.
    pub fn read(&mut self, devices: &Devices, dt_us: u32) -> i64 {
        let (raw, sixteen_bit) = match self.operand {
            MasterOperand::TimeBase(period) => {
                self.elapsed_us = self.elapsed_us.saturating_add(u64::from(dt_us));
                let period_us = u64::from(period).saturating_mul(100).max(1);
                self.position = i64::try_from(self.elapsed_us / period_us).unwrap_or(i64::MAX);
                return self.position;
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
        self.position
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
        assert_eq!(m.read(&dev, 100), i64::from(i32::MAX - 1));
        dev.set_counter(231, i32::MIN + 1).unwrap();
        assert_eq!(m.read(&dev, 100), i64::from(i32::MAX) + 2);
    }

    #[test]
    fn unwraps_a_16_bit_counter() {
        let mut dev = Devices::new();
        let mut m = MasterReader::new(MasterOperand::Counter(5));
        dev.set_counter(5, 32767).unwrap();
        m.read(&dev, 100);
        dev.set_counter(5, 32768).unwrap();
        assert_eq!(m.read(&dev, 100), 32768);
    }

    #[test]
    fn time_base_counts_exactly() {
        let dev = Devices::new();
        let mut m = MasterReader::new(MasterOperand::TimeBase(3));
        let mut last = 0;
        for _ in 0..30 {
            last = m.read(&dev, 100);
        }
        assert_eq!(last, 10);
    }
}
