//! Registration (print-mark) correction, as rotary knives and flying saws
//! cut to printed marks: a touch probe latches the master (or the slave)
//! when a sensor sees a mark on the material, and the cam's phase is
//! corrected each cycle towards where the mark is expected.
//!
//! Per mark: the error is where the mark was latched, in the cycle, minus
//! where it is expected (taken the shorter way round the cycle, and with
//! the corrections already asked for counted as done). A latch farther
//! than the window from the expected position is not a mark (`rejected`);
//! a window that closes without a mark is a missed mark (`missed`). A
//! mark in the window corrects by the error, at most `max_correction` per
//! mark, so a large error is taken out over several cycles and a false
//! latch can do little harm. Each correction is ramped over `ramp` master
//! counts with the quintic `10u³ − 15u⁴ + 6u⁵` (position, velocity and
//! acceleration continuous) and ends exactly on its whole count.
//!
//! A master latch corrects the phase of the master the cam sees (a shift
//! in master counts, like `MC_Phasing`: a late mark delays the tool); a
//! slave latch corrects the slave itself (an offset in pulses: a late mark
//! on what the slave carries takes the slave on by the error). The ramp must be at least twice the
//! largest correction: the shift's extra speed is then at most
//! `1.875 × max / ramp < 1` master count per count, so a correction never
//! turns the master the cam sees (nor the slave) back.

use core::num::NonZeroU64;

use crate::CouplingError;
use crate::ramp::quintic;
use crate::timed_move::{ONE, to_units, whole};

/// Which axis the touch probe latches.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LatchSource {
    /// The master (the material's feed): the correction shifts the phase
    /// of the master the cam sees.
    #[default]
    Master,
    /// The slave: the correction is an offset of the slave.
    Slave,
}

/// Registration settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RegistrationConfig {
    /// Which position the latches are.
    pub source: LatchSource,
    /// The mark spacing: one cycle, in the source's units (master counts
    /// seen by the cam, or slave pulses).
    pub cycle: NonZeroU64,
    /// Where in the cycle (`0..cycle`, from the source's zero) the mark
    /// should be latched.
    pub expected: i64,
    /// A latch within this distance of `expected` is a mark.
    pub window: u64,
    /// The largest correction per mark.
    pub max_correction: u64,
    /// Master counts over which each correction is ramped in.
    pub ramp: NonZeroU64,
}

impl RegistrationConfig {
    /// Checks the settings against each other.
    ///
    /// # Errors
    /// [`CouplingError::BadRegistration`] when the window is not below half
    /// a cycle or the ramp is shorter than twice the largest correction.
    pub fn check(&self) -> Result<(), CouplingError> {
        let half = self.cycle.get() / 2;
        if self.window >= half.max(1) || self.ramp.get() < self.max_correction.saturating_mul(2) {
            return Err(CouplingError::BadRegistration);
        }
        Ok(())
    }
}

/// What registration reports every tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RegistrationStatus {
    /// Marks latched within the window (each one a correction).
    pub marks: u64,
    /// Windows that closed without a mark.
    pub missed: u64,
    /// Latches outside the window (not taken as marks).
    pub rejected: u64,
    /// The last mark's error (latched minus expected, corrections asked
    /// for counted as done), source units.
    pub last_error: i64,
    /// The last correction (at most `max_correction` either way): −error
    /// for a master latch, +error for a slave latch.
    pub last_correction: i64,
    /// The correction in force now (master counts or pulses, with its
    /// fraction while a ramp runs).
    pub correction: f64,
    /// A correction is being ramped in.
    pub correcting: bool,
    /// A mark was taken this tick.
    pub mark: bool,
}

/// A correction ramp: from `from` to the target over the master distance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Ramp {
    from: i128,
    at: i128,
}

/// Registration's state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Registration {
    config: RegistrationConfig,
    /// The total correction asked for (fixed point, whole units).
    target: i128,
    current: i128,
    ramp: Option<Ramp>,
    /// The last window (index) the source has left, and whether a mark
    /// was taken in the window it is in.
    window: Option<i128>,
    marked: bool,
    status: RegistrationStatus,
}

impl Registration {
    pub(crate) fn new(config: RegistrationConfig) -> Result<Self, CouplingError> {
        config.check()?;
        Ok(Self {
            config,
            target: 0,
            current: 0,
            ramp: None,
            window: None,
            marked: false,
            status: RegistrationStatus::default(),
        })
    }

    pub(crate) fn source(&self) -> LatchSource {
        self.config.source
    }

    /// The correction at guarded master `g` (fixed point): moves the ramp on.
    pub(crate) fn correction_at(&mut self, g: i128) -> i128 {
        if let Some(ramp) = self.ramp {
            let u = to_units(g - ramp.at).abs() / self.config.ramp.get() as f64;
            if u >= 1.0 {
                self.current = self.target;
                self.ramp = None;
            } else {
                let gap = to_units(self.target - ramp.from);
                let step = libm::round(gap * quintic(u) * ONE as f64);
                self.current = ramp.from + step as i128;
            }
        }
        self.current
    }

    /// The correction in force (fixed point).
    pub(crate) fn current(&self) -> i128 {
        self.current
    }

    /// Where a position of the source lies in the frame the marks are
    /// expected in, the corrections asked for so far counted as done. A
    /// master position (`position` = the master the cam would see without
    /// a correction) is shifted by them; a slave position (the slave as
    /// commanded, correction included) is taken back by them, to where the
    /// command without a correction would be.
    fn frame(&self, position: i128) -> i128 {
        match self.config.source {
            LatchSource::Master => position + self.target,
            LatchSource::Slave => position - self.target,
        }
    }

    /// A latch at `position` (fixed point; for a master latch the master
    /// the cam would see without a correction, for a slave latch the slave
    /// position as latched); `g` is the guarded master where a correction
    /// ramp starts.
    pub(crate) fn latch(&mut self, position: i128, g: i128) {
        let position = self.frame(position);
        let cycle = i128::from(self.config.cycle.get()) * ONE;
        let expected = i128::from(self.config.expected) * ONE;
        let mut error = (position - expected).rem_euclid(cycle);
        if 2 * error > cycle {
            error -= cycle;
        }
        let error = whole(error);
        if error.unsigned_abs() > u128::from(self.config.window) {
            self.status.rejected += 1;
            return;
        }
        let max = i128::from(self.config.max_correction);
        // A master latch moves the tool to the mark: a late mark delays
        // the phase. A slave latch moves what the slave carries: a late
        // mark takes the slave on (the frame is the command without the
        // correction, so the mark shows up earlier by what it adds).
        let correction = match self.config.source {
            LatchSource::Master => -error,
            LatchSource::Slave => error,
        }
        .clamp(-max, max);
        self.status.marks += 1;
        self.status.mark = true;
        self.status.last_error = clamp(error);
        self.status.last_correction = clamp(correction);
        self.marked = true;
        if correction != 0 {
            self.target += correction * ONE;
            self.ramp = Some(Ramp {
                from: self.current,
                at: g,
            });
        }
    }

    /// Watches the source's position `position` (fixed point, as for
    /// [`Registration::latch`]): a window left without a mark is missed.
    pub(crate) fn watch(&mut self, position: i128) {
        let position = self.frame(position);
        let cycle = i128::from(self.config.cycle.get()) * ONE;
        let close =
            i128::from(self.config.expected).saturating_add(i128::from(self.config.window)) * ONE;
        let index = (position - close).div_euclid(cycle);
        match self.window {
            None => self.window = Some(index),
            Some(last) if index > last => {
                let passed = (index - last).unsigned_abs();
                let missed = passed.saturating_sub(u128::from(self.marked));
                self.status.missed = self
                    .status
                    .missed
                    .saturating_add(u64::try_from(missed).unwrap_or(u64::MAX));
                self.window = Some(index);
                self.marked = false;
            }
            // Going back over a window does not count it again.
            Some(_) => {}
        }
    }

    /// The status, and clears this tick's event.
    pub(crate) fn status(&mut self) -> RegistrationStatus {
        let mut s = self.status;
        s.correction = to_units(self.current);
        s.correcting = self.ramp.is_some();
        self.status.mark = false;
        s
    }
}

fn clamp(v: i128) -> i64 {
    i64::try_from(v).unwrap_or(if v < 0 { i64::MIN } else { i64::MAX })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config() -> RegistrationConfig {
        RegistrationConfig {
            source: LatchSource::Master,
            cycle: NonZeroU64::new(10_000).unwrap(),
            expected: 2000,
            window: 500,
            max_correction: 100,
            ramp: NonZeroU64::new(1000).unwrap(),
        }
    }

    fn f(v: i64) -> i128 {
        i128::from(v) * ONE
    }

    #[test]
    fn corrects_by_the_error_within_the_limit() {
        let mut r = Registration::new(config()).unwrap();
        r.watch(0);
        // Latched 250 late: corrected by −100 (the limit), ramped.
        r.latch(f(2250), f(2250));
        assert_eq!(r.status().last_correction, -100);
        assert_eq!(r.correction_at(f(2250)), 0);
        assert_eq!(r.correction_at(f(3250)), f(-100));
        // Next cycle: still 150 late.
        r.latch(f(12_250), f(12_250));
        assert_eq!(r.status().last_error, 150);
        assert_eq!(r.status().last_correction, -100);
        // A latch far outside the window is rejected.
        r.latch(f(16_000), f(16_000));
        assert_eq!(r.status().rejected, 1);
    }

    #[test]
    fn missed_windows_are_counted_once() {
        let mut r = Registration::new(config()).unwrap();
        r.watch(0);
        r.watch(f(2600)); // window closed at 2500 without a mark
        r.latch(f(12_000), f(12_000));
        r.watch(f(12_600)); // with a mark
        r.watch(f(11_000)); // back again
        r.watch(f(12_700));
        r.watch(f(42_600)); // three windows, none marked
        assert_eq!(r.status().missed, 4);
        assert_eq!(
            Registration::new(RegistrationConfig {
                ramp: NonZeroU64::new(150).unwrap(),
                ..config()
            })
            .err(),
            Some(CouplingError::BadRegistration)
        );
    }
}
