//! Timers T0–T255 of the FX3U (which the LX3V follows): T0–T199 count
//! 100 ms, T200–T245 10 ms, T246–T249 1 ms and T250–T255 100 ms; the last
//! two groups are retentive (they keep their value while the coil is off,
//! until `RST`).
//!
//! As on the FX3U, a timer is updated when its `OUT Tn` instruction runs:
//! the time elapsed since that instruction last ran with its coil on is added
//! (whole clock units; the remainder is carried, so nothing is lost to
//! rounding), the value stops at the set value, and the contact turns on at
//! that `OUT` once the value has reached it. Contacts earlier in the program
//! see the change in the next scan, as on the PLC.

use crate::device::DeviceError;

/// Number of timers T0…T255.
pub const T_COUNT: u16 = 256;

/// One timer's state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Timer {
    /// Current value in clock units (0…32767).
    value: i16,
    /// The output contact.
    contact: bool,
    /// The coil was on when `OUT` last ran (timing is under way).
    driven: bool,
    /// Time of that last `OUT` execution, µs.
    last_us: u64,
    /// Elapsed µs not yet a whole clock unit.
    carry_us: u64,
}

/// All timers of one PLC.
#[derive(Debug, PartialEq, Eq)]
pub struct Timers {
    timers: Vec<Timer>,
}

impl Clone for Timers {
    fn clone(&self) -> Self {
        Self {
            timers: self.timers.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.timers.clone_from(&source.timers);
    }
}

impl Default for Timers {
    fn default() -> Self {
        Self::new()
    }
}

/// Clock unit of timer `n` in µs, and whether it is retentive.
pub(crate) const fn timer_clock(n: u16) -> (u64, bool) {
    match n {
        0..=199 => (100_000, false),
        200..=245 => (10_000, false),
        246..=249 => (1_000, true),
        _ => (100_000, true),
    }
}

impl Timers {
    /// Every timer at 0, contacts off.
    pub(crate) fn new() -> Self {
        Self {
            timers: vec![Timer::default(); usize::from(T_COUNT)],
        }
    }

    /// Current value of `Tn` in clock units.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past T255.
    pub fn value(&self, n: u16) -> Result<i16, DeviceError> {
        self.get(n).map(|t| t.value)
    }

    /// The contact of `Tn`.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past T255.
    pub fn contact(&self, n: u16) -> Result<bool, DeviceError> {
        self.get(n).map(|t| t.contact)
    }

    /// Writes the current value of `Tn` (MOV K5 T0 on the FX); the contact
    /// follows at the next `OUT Tn`.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past T255.
    pub(crate) fn set_value(&mut self, n: u16, value: i16) -> Result<(), DeviceError> {
        let timer = self.get_mut(n)?;
        timer.value = value;
        Ok(())
    }

    /// `RST Tn`: value 0, contact off, timing restarts at the next `OUT`.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past T255.
    pub(crate) fn reset(&mut self, n: u16) -> Result<(), DeviceError> {
        *self.get_mut(n)? = Timer::default();
        Ok(())
    }

    /// `OUT Tn preset` executed at `now_us` with power flow `power`. A
    /// preset below 0 is treated by the caller (operation error).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past T255.
    pub(crate) fn drive(
        &mut self,
        n: u16,
        power: bool,
        preset: i16,
        now_us: u64,
    ) -> Result<(), DeviceError> {
        let (clock_us, retentive) = timer_clock(n);
        let timer = self.get_mut(n)?;
        if !power {
            if retentive {
                timer.driven = false;
            } else {
                *timer = Timer::default();
            }
            return Ok(());
        }
        if timer.driven {
            let elapsed = now_us
                .saturating_sub(timer.last_us)
                .saturating_add(timer.carry_us);
            let units = elapsed / clock_us;
            timer.carry_us = elapsed % clock_us;
            let value =
                i64::from(timer.value).saturating_add(i64::try_from(units).unwrap_or(i64::MAX));
            // The value stops at the set value (and never passes K32767).
            let cap = i64::from(preset.max(timer.value));
            timer.value = i16::try_from(value.min(cap)).unwrap_or(i16::MAX);
        } else {
            timer.driven = true;
            timer.carry_us = 0;
        }
        timer.last_us = now_us;
        timer.contact = timer.value >= preset;
        Ok(())
    }

    fn get(&self, n: u16) -> Result<&Timer, DeviceError> {
        self.timers
            .get(usize::from(n))
            .ok_or(DeviceError::OutOfRange)
    }

    fn get_mut(&mut self, n: u16) -> Result<&mut Timer, DeviceError> {
        self.timers
            .get_mut(usize::from(n))
            .ok_or(DeviceError::OutOfRange)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_100ms_timer_counts_whole_units_and_carries_the_rest() {
        let mut timers = Timers::new();
        timers.drive(0, true, 3, 0).unwrap();
        timers.drive(0, true, 3, 150_000).unwrap();
        assert_eq!(timers.value(0), Ok(1));
        timers.drive(0, true, 3, 200_000).unwrap();
        assert_eq!(timers.value(0), Ok(2));
        assert_eq!(timers.contact(0), Ok(false));
        timers.drive(0, true, 3, 900_000).unwrap();
        assert_eq!((timers.value(0), timers.contact(0)), (Ok(3), Ok(true)));
        timers.drive(0, false, 3, 1_000_000).unwrap();
        assert_eq!((timers.value(0), timers.contact(0)), (Ok(0), Ok(false)));
    }

    #[test]
    fn retentive_timers_keep_their_value() {
        let mut timers = Timers::new();
        timers.drive(250, true, 10, 0).unwrap();
        timers.drive(250, true, 10, 500_000).unwrap();
        timers.drive(250, false, 10, 600_000).unwrap();
        // Off time does not count.
        timers.drive(250, true, 10, 5_000_000).unwrap();
        assert_eq!(timers.value(250), Ok(5));
        timers.drive(250, true, 10, 5_500_000).unwrap();
        assert_eq!((timers.value(250), timers.contact(250)), (Ok(10), Ok(true)));
        timers.reset(250).unwrap();
        assert_eq!((timers.value(250), timers.contact(250)), (Ok(0), Ok(false)));
        assert_eq!(timers.value(256), Err(DeviceError::OutOfRange));
    }
}
