//! One work budget per run: whatever a command, a script or a design
//! request asks for, the work it may do in all is bounded, and a server
//! can stop it early (its client left, its deadline passed).
//!
//! A budget counts *work units*: a control cycle (a PLC hardware tick, a
//! script's or scenario's tick) costs [`CYCLE_WORK`], an instruction-list
//! instruction or one term of an expression evaluated at one point costs
//! [`STEP_WORK`]. A run starts with [`Budget::per_run`]
//! ([`crate::limits::MAX_RUN_WORK`] units, so at most
//! [`crate::limits::MAX_SIMULATED_TICKS`] cycles) and stops with
//! [`OverBudget`] when it is spent. The limits are documented in
//! `docs/cli.md` ("Limits").
//!
//! ```
//! use ecam_core::budget::{Budget, OverBudget};
//!
//! let mut budget = Budget::new(100);
//! assert!(budget.cycles(5).is_ok()); // 50 units
//! assert_eq!(budget.spend(51), Err(OverBudget::Exhausted { limit: 100 }));
//! assert_eq!(budget.used(), 50); // a refused spend takes nothing
//! ```

use alloc::sync::Arc;
use core::fmt;
use core::sync::atomic::{AtomicBool, Ordering};

use crate::limits::MAX_RUN_WORK;

pub use crate::limits::{CYCLE_WORK, STEP_WORK};

/// The work a run may still do.
#[derive(Clone, Debug)]
pub struct Budget {
    used: u64,
    limit: u64,
    cancel: Option<Arc<AtomicBool>>,
}

/// Why a run stopped before its end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OverBudget {
    /// The run asked for more work than its budget.
    Exhausted {
        /// The budget, in work units.
        limit: u64,
    },
    /// The one who asked for the work gave up on it (a server's client
    /// left, or the request's deadline passed).
    Cancelled,
}

impl fmt::Display for OverBudget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Exhausted { limit } => write!(
                f,
                "more work than one run may do: the budget is {limit} units \
                 (a control cycle counts {CYCLE_WORK}, an instruction or an expression term {STEP_WORK})"
            ),
            Self::Cancelled => f.write_str("stopped: the request was given up"),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for OverBudget {}

impl Budget {
    /// A budget of `limit` work units.
    pub const fn new(limit: u64) -> Self {
        Self {
            used: 0,
            limit,
            cancel: None,
        }
    }

    /// The budget of one run: [`MAX_RUN_WORK`] units.
    pub const fn per_run() -> Self {
        Self::new(MAX_RUN_WORK)
    }

    /// This budget, stopped early once `flag` is set (by another thread).
    #[must_use]
    pub fn cancelled_by(mut self, flag: Arc<AtomicBool>) -> Self {
        self.cancel = Some(flag);
        self
    }

    /// Takes `units` from the budget.
    ///
    /// # Errors
    /// [`OverBudget::Cancelled`] once the run was given up;
    /// [`OverBudget::Exhausted`] when fewer than `units` are left (nothing
    /// is taken then).
    pub fn spend(&mut self, units: u64) -> Result<(), OverBudget> {
        self.check()?;
        match self.used.checked_add(units) {
            Some(used) if used <= self.limit => {
                self.used = used;
                Ok(())
            }
            _ => Err(OverBudget::Exhausted { limit: self.limit }),
        }
    }

    /// Takes `cycles` control cycles ([`CYCLE_WORK`] each).
    ///
    /// # Errors
    /// As [`Budget::spend`].
    pub fn cycles(&mut self, cycles: u64) -> Result<(), OverBudget> {
        self.spend(cycles.saturating_mul(CYCLE_WORK))
    }

    /// Whether the run may go on: only the cancellation is looked at.
    ///
    /// # Errors
    /// [`OverBudget::Cancelled`] once the run was given up.
    pub fn check(&self) -> Result<(), OverBudget> {
        match &self.cancel {
            Some(flag) if flag.load(Ordering::Relaxed) => Err(OverBudget::Cancelled),
            _ => Ok(()),
        }
    }

    /// Work units taken so far.
    pub fn used(&self) -> u64 {
        self.used
    }

    /// The budget, in work units.
    pub fn limit(&self) -> u64 {
        self.limit
    }
}

impl Default for Budget {
    fn default() -> Self {
        Self::per_run()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_budget_stops_at_its_limit_and_never_overflows() {
        let mut b = Budget::new(25);
        assert_eq!(b.cycles(2), Ok(()));
        assert_eq!(b.spend(5), Ok(()));
        assert_eq!(b.spend(1), Err(OverBudget::Exhausted { limit: 25 }));
        assert_eq!(b.cycles(u64::MAX), Err(OverBudget::Exhausted { limit: 25 }));
        assert_eq!(b.used(), 25);
    }

    #[test]
    fn a_cancelled_budget_stops_at_once() {
        let flag = Arc::new(AtomicBool::new(false));
        let mut b = Budget::per_run().cancelled_by(Arc::clone(&flag));
        assert_eq!(b.spend(1), Ok(()));
        flag.store(true, Ordering::Relaxed);
        assert_eq!(b.check(), Err(OverBudget::Cancelled));
        assert_eq!(b.spend(0), Err(OverBudget::Cancelled));
    }

    #[test]
    fn the_run_budget_allows_the_simulated_tick_limit_exactly() {
        let mut b = Budget::per_run();
        assert_eq!(b.cycles(crate::limits::MAX_SIMULATED_TICKS), Ok(()));
        assert!(b.spend(1).is_err());
    }
}
