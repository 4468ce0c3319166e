//! Simulated time: scans every `scan_us`, hardware ticks every `tick_us`,
//! far faster than real time and exactly repeatable.
//!
//! Order: at t = 0, `scan_us`, 2·`scan_us`, … one program scan, then hardware
//! ticks that cover the time up to the next scan (the last tick of a period
//! is shorter if `tick_us` does not divide `scan_us`, so no time is lost).

use core::fmt;

use crate::interpreter::LineError;
use crate::scan::Plc;

/// Default scan period (µs).
pub const DEFAULT_SCAN_US: u32 = 1000;
/// Default hardware tick (µs).
pub const DEFAULT_TICK_US: u32 = 100;

/// How long to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunLength {
    /// This many scans (and the hardware time after each).
    Scans(u64),
    /// This many milliseconds of simulated time (scans at every `scan_us` before it).
    Millis(u64),
}

/// Timing of a simulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Timing {
    /// Scan period in µs (> 0).
    pub scan_us: u32,
    /// Hardware tick in µs (> 0).
    pub tick_us: u32,
}

impl Default for Timing {
    fn default() -> Self {
        Self {
            scan_us: DEFAULT_SCAN_US,
            tick_us: DEFAULT_TICK_US,
        }
    }
}

/// A timing that cannot run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimingError {
    /// Scan period 0.
    ZeroScan,
    /// Tick 0.
    ZeroTick,
}

impl fmt::Display for TimingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::ZeroScan => "the scan period must be at least 1 us",
            Self::ZeroTick => "the hardware tick must be at least 1 us",
        })
    }
}

impl std::error::Error for TimingError {}

/// Runs `plc` for `length`, calling `after_scan` after every scan (for
/// traces), and returns every operation error raised.
///
/// # Errors
/// A zero scan period or tick.
///
/// ```
/// use ecam_plc::sim::{run, RunLength, Timing};
/// let program = ecam_plc::Program::parse("LD M8000\nDPLSY K1000 K0 Y1\n", "demo.il").unwrap();
/// let mut plc = ecam_plc::Plc::new(program).unwrap();
/// run(&mut plc, Timing::default(), RunLength::Millis(10), |_| {}).unwrap();
/// assert_eq!(plc.devices().dword(8142), Ok(10)); // 1 kHz for 10 ms
/// ```
pub fn run(
    plc: &mut Plc,
    timing: Timing,
    length: RunLength,
    mut after_scan: impl FnMut(&Plc),
) -> Result<Vec<LineError>, TimingError> {
    if timing.scan_us == 0 {
        return Err(TimingError::ZeroScan);
    }
    if timing.tick_us == 0 {
        return Err(TimingError::ZeroTick);
    }
    let start = plc.now_us();
    let end = match length {
        RunLength::Scans(n) => start.saturating_add(n.saturating_mul(u64::from(timing.scan_us))),
        RunLength::Millis(ms) => start.saturating_add(ms.saturating_mul(1000)),
    };
    let mut errors = Vec::new();
    while plc.now_us() < end {
        errors.extend(plc.scan());
        after_scan(plc);
        let period_end = plc
            .now_us()
            .saturating_add(u64::from(timing.scan_us))
            .min(end);
        while plc.now_us() < period_end {
            let dt = (period_end - plc.now_us()).min(u64::from(timing.tick_us));
            plc.hardware_tick(dt as u32);
        }
    }
    Ok(errors)
}
