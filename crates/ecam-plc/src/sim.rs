//! Simulated time: scans every `scan_us`, hardware ticks every `tick_us`,
//! far faster than real time and exactly repeatable.
//!
//! Order: at t = 0, `scan_us`, 2·`scan_us`, … one program scan, then hardware
//! ticks that cover the time up to the next scan (the last tick of a period
//! is shorter if `tick_us` does not divide `scan_us`, so no time is lost).

use core::fmt;

use ecam_core::budget::{Budget, OverBudget, STEP_WORK};

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

/// A run that could not go on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunError {
    /// The timing cannot run.
    Timing(TimingError),
    /// The run's hardware ticks alone need more than the budget: refused
    /// before it starts.
    TooManyTicks {
        /// Ticks the run would take.
        ticks: u64,
        /// The tick, µs.
        tick_us: u32,
        /// Most ticks the budget allows.
        limit: u64,
    },
    /// The instructions used up the budget (`ecam_core::budget`), or the
    /// run was given up.
    OverBudget {
        /// What ran out.
        reason: OverBudget,
        /// Simulated time reached, µs.
        at_us: u64,
    },
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Timing(e) => e.fmt(f),
            Self::TooManyTicks {
                ticks,
                tick_us,
                limit,
            } => write!(
                f,
                "the run would take {ticks} hardware ticks of {tick_us} us; the limit is {limit} \
                 per run: ask for less simulated time"
            ),
            Self::OverBudget { reason, at_us } => write!(
                f,
                "stopped at {}.{:03} s of simulated time: {reason}",
                at_us / 1_000_000,
                at_us % 1_000_000 / 1000
            ),
        }
    }
}

impl std::error::Error for RunError {}

impl From<TimingError> for RunError {
    fn from(e: TimingError) -> Self {
        Self::Timing(e)
    }
}

/// Runs `plc` for `length` within one run's work budget
/// ([`Budget::per_run`]), calling `after_scan` after every scan (for
/// traces), and returns every operation error raised.
///
/// # Errors
/// A zero scan period or tick; a run over the budget (see [`run_within`]).
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
    after_scan: impl FnMut(&Plc),
) -> Result<Vec<LineError>, RunError> {
    run_within(plc, timing, length, &mut Budget::per_run(), after_scan)
}

/// Runs as [`run`] does, taking the work from `budget`: every hardware
/// tick costs a control cycle, taken before the run starts (so a run that
/// cannot fit is refused at once, nothing run), and every instruction a
/// scan executes one step.
///
/// # Errors
/// A zero scan period or tick; [`RunError::OverBudget`] when the ticks do
/// not fit the budget, or when the instructions use up what is left (the
/// run stops after that scan).
pub fn run_within(
    plc: &mut Plc,
    timing: Timing,
    length: RunLength,
    budget: &mut Budget,
    mut after_scan: impl FnMut(&Plc),
) -> Result<Vec<LineError>, RunError> {
    if timing.scan_us == 0 {
        return Err(TimingError::ZeroScan.into());
    }
    if timing.tick_us == 0 {
        return Err(TimingError::ZeroTick.into());
    }
    let start = plc.now_us();
    let end = match length {
        RunLength::Scans(n) => start.saturating_add(n.saturating_mul(u64::from(timing.scan_us))),
        RunLength::Millis(ms) => start.saturating_add(ms.saturating_mul(1000)),
    };
    // Each period's last tick is shorter when the tick does not divide it.
    let (span, scan, tick) = (
        end - start,
        u64::from(timing.scan_us),
        u64::from(timing.tick_us),
    );
    let ticks = (span / scan)
        .saturating_mul(scan.div_ceil(tick))
        .saturating_add((span % scan).div_ceil(tick));
    let left = budget.limit().saturating_sub(budget.used()) / ecam_core::budget::CYCLE_WORK;
    budget.cycles(ticks).map_err(|reason| match reason {
        OverBudget::Exhausted { .. } => RunError::TooManyTicks {
            ticks,
            tick_us: timing.tick_us,
            limit: left,
        },
        OverBudget::Cancelled => RunError::OverBudget {
            reason,
            at_us: start,
        },
    })?;
    let mut errors = Vec::new();
    while plc.now_us() < end {
        errors.extend(plc.scan());
        budget
            .spend(plc.last_scan_steps().saturating_mul(STEP_WORK))
            .map_err(|reason| RunError::OverBudget {
                reason,
                at_us: plc.now_us(),
            })?;
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

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    fn plc(source: &str) -> Plc {
        Plc::new(crate::Program::parse(source, "t.il").unwrap()).unwrap()
    }

    #[test]
    fn a_run_whose_ticks_do_not_fit_the_budget_is_refused_before_it_starts() {
        let mut p = plc("LD M8000\nINC D0\n");
        let mut budget = Budget::new(10 * 25);
        let err = run_within(
            &mut p,
            Timing::default(),
            RunLength::Millis(3),
            &mut budget,
            |_| {},
        )
        .unwrap_err();
        assert_eq!(
            err,
            RunError::TooManyTicks {
                ticks: 30,
                tick_us: 100,
                limit: 25
            }
        );
        assert_eq!((p.scans(), budget.used()), (0, 0), "nothing ran");
        // A tick that does not divide the scan period: 3 ticks a period.
        let timing = Timing {
            scan_us: 250,
            tick_us: 100,
        };
        let mut budget = Budget::new(10 * 12 + 8);
        run_within(&mut p, timing, RunLength::Scans(4), &mut budget, |_| {}).unwrap();
        assert_eq!(
            budget.used(),
            10 * 12 + 2 * 4,
            "12 ticks, 2 instructions a scan"
        );
    }

    #[test]
    fn instructions_count_against_the_budget_across_scans() {
        // 4 instructions a pass, 1000 passes: 4 000+ instructions a scan.
        let source = "LD M8000\nMOV K0 D0\nP0\nLD M8000\nINC D0\nLD< D0 K1000\nCJ P0\nEND\n";
        let mut p = plc(source);
        let mut budget = Budget::new(10 * 1000 + 20_000);
        let err = run_within(
            &mut p,
            Timing::default(),
            RunLength::Scans(100),
            &mut budget,
            |_| {},
        )
        .unwrap_err();
        assert!(
            matches!(err, RunError::OverBudget { reason: OverBudget::Exhausted { .. }, at_us } if at_us > 0),
            "{err:?}"
        );
        assert!(p.scans() < 10, "stopped after {} scans", p.scans());
        assert!(err.to_string().starts_with("stopped at 0.00"), "{err}");
    }
}
