//! When something a scenario asks for happens: a time, or the master
//! reaching a position (`[stop]`, `[[switch]]`, `[[plcopen]]`), and
//! seconds read as microseconds.

use crate::error::ScenarioError;

/// What requests a stop, a table switch or a PLCopen step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopTrigger {
    /// At this time, in microseconds from the start.
    Time(u64),
    /// When the (unwrapped) master reaches this position or more: document
    /// 002's stop breakpoint.
    MasterAtLeast(i64),
    /// When the master reaches this position or less.
    MasterAtMost(i64),
}

impl StopTrigger {
    /// Whether the trigger fires on a tick at `t_us` with the master at `master`.
    pub fn fires(&self, t_us: u64, master: i64) -> bool {
        match *self {
            Self::Time(at) => t_us >= at,
            Self::MasterAtLeast(p) => master >= p,
            Self::MasterAtMost(p) => master <= p,
        }
    }
}

/// The one trigger of a `[stop]`, `[[switch]]` or `[[plcopen]]` entry.
pub(crate) fn trigger(
    at_s: Option<f64>,
    master_at_least: Option<i64>,
    master_at_most: Option<i64>,
    what: &str,
) -> Result<StopTrigger, ScenarioError> {
    Ok(match (at_s, master_at_least, master_at_most) {
        (Some(t), None, None) => StopTrigger::Time(micros(t, &format!("{what} at_s"))?),
        (None, Some(p), None) => StopTrigger::MasterAtLeast(p),
        (None, None, Some(p)) => StopTrigger::MasterAtMost(p),
        _ => {
            return Err(ScenarioError::Trigger {
                what: what.to_string(),
            });
        }
    })
}

/// Seconds → microseconds, refusing negatives, NaN and absurd lengths.
pub(crate) fn micros(seconds: f64, what: &str) -> Result<u64, ScenarioError> {
    // A year of simulated time is far beyond any useful scenario.
    if !(0.0..=3.2e7).contains(&seconds) {
        return Err(ScenarioError::Seconds {
            what: what.to_string(),
            seconds,
        });
    }
    Ok((seconds * 1e6).round() as u64)
}
