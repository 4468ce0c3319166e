//! The pulse generator: emits exactly the change of the commanded position,
//! limited by the maximum output frequency; what cannot go out this tick is
//! carried as a backlog (document 003 flag bit 2, "pulse output delayed"),
//! never dropped.

/// Pulse budget units: one pulse = 10^6 Hz·µs.
const PULSE: u64 = 1_000_000;

/// The output side of an axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct PulseOutput {
    /// Cumulative emitted position (what the drive has received).
    pub(crate) emitted: i64,
    /// Unused budget below one pulse, carried only while a backlog waits.
    credit: u64,
    /// Direction of the last pulses.
    pub(crate) forward: bool,
}

impl PulseOutput {
    /// An output standing at `position`.
    pub(crate) fn at(position: i64) -> Self {
        Self {
            emitted: position,
            credit: 0,
            forward: true,
        }
    }

    /// Pulses still owed to reach `commanded`.
    pub(crate) fn backlog(&self, commanded: i64) -> i64 {
        commanded.saturating_sub(self.emitted)
    }

    /// Emits towards `commanded` within `hz × dt_us`; returns the signed
    /// pulse count. Never more than `(hz × dt_us + credit) / 10^6` pulses,
    /// with the carried credit below one pulse, so the average rate never
    /// exceeds `hz`.
    #[inline]
    pub(crate) fn step(&mut self, commanded: i64, enabled: bool, hz: u32, dt_us: u32) -> i64 {
        // Nearly always the pulses owed fit 64 bits: one subtraction.
        let Some(owed) = commanded.checked_sub(self.emitted) else {
            return self.step_wide(commanded, enabled, hz, dt_us);
        };
        if !enabled || owed == 0 {
            self.credit = 0;
            return 0;
        }
        let budget = self.credit + u64::from(hz) * u64::from(dt_us);
        let allowed = budget / PULSE;
        let wanted = owed.unsigned_abs();
        let count = wanted.min(allowed);
        self.credit = if count == wanted {
            0
        } else {
            budget - count * PULSE
        };
        let count = i64::try_from(count).unwrap_or(i64::MAX);
        self.emit(if owed > 0 { count } else { -count })
    }

    /// [`PulseOutput::step`] when the pulses owed exceed 64 bits.
    #[cold]
    fn step_wide(&mut self, commanded: i64, enabled: bool, hz: u32, dt_us: u32) -> i64 {
        let owed = i128::from(commanded) - i128::from(self.emitted);
        if !enabled || owed == 0 {
            self.credit = 0;
            return 0;
        }
        let budget = self.credit + u64::from(hz) * u64::from(dt_us);
        let allowed = budget / PULSE;
        let wanted = owed.unsigned_abs();
        let count = u64::try_from(wanted).map_or(allowed, |w| w.min(allowed));
        self.credit = if u128::from(count) == wanted {
            0
        } else {
            budget - count * PULSE
        };
        let count = i64::try_from(count).unwrap_or(i64::MAX);
        self.emit(if owed > 0 { count } else { -count })
    }

    /// Moves the emitted position by `pulses` and notes their direction.
    #[inline]
    fn emit(&mut self, pulses: i64) -> i64 {
        self.emitted = self.emitted.saturating_add(pulses);
        if pulses != 0 {
            self.forward = pulses > 0;
        }
        pulses
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_and_carries() {
        let mut p = PulseOutput::at(0);
        // 5 kHz, 100 µs ticks: one pulse every second tick.
        assert_eq!(p.step(10, true, 5000, 100), 0);
        assert_eq!(p.step(10, true, 5000, 100), 1);
        assert_eq!(p.backlog(10), 9);
        assert_eq!(p.step(10, true, 200_000, 1000), 9);
        assert_eq!(p.step(-10, true, 200_000, 100), -20);
        assert!(!p.forward);
        assert_eq!(p.step(0, false, 200_000, 100), 0);
        assert_eq!(p.backlog(0), 10);
    }

    #[test]
    fn narrow_and_wide_steps_agree() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for _ in 0..20_000 {
            let emitted = (next() as i64) >> (next() % 64);
            let commanded = emitted.saturating_add((next() as i64) >> (next() % 64));
            let (hz, dt) = ((next() % 300_000) as u32, (next() % 5000) as u32);
            let enabled = next() % 8 != 0;
            let mut a = PulseOutput::at(emitted);
            a.credit = next() % PULSE;
            let mut b = a;
            assert_eq!(
                a.step(commanded, enabled, hz, dt),
                b.step_wide(commanded, enabled, hz, dt)
            );
            assert_eq!(a, b);
        }
    }
}
