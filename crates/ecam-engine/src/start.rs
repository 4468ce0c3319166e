//! Start conditions: what an armed axis waits for before it engages.
//!
//! Each condition reports the exact master position at which the cam
//! engages, so the phase of the cam does not depend on the tick period
//! (a delay of N counts engages at N counts even when a tick jumps past it).

use core::num::NonZeroU64;

use crate::turn_position::nearest;
use crate::{Compare, MissedActivation, StartMode};

/// What the start logic decided this tick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum StartStep {
    /// Still waiting for the start condition.
    Waiting,
    /// The trigger came; counting the delay.
    Delaying,
    /// Engage with the master at this position.
    Engage(i64),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    Edge,
    Delay { travelled: u64 },
    Position { fresh: bool },
    Breakpoint,
    Now,
}

/// The start logic of an armed axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct StartWatch {
    mode: StartMode,
    phase: Phase,
    policy: MissedActivation,
    /// A single-turn master's turn: the start position comes round once
    /// per turn.
    turn: Option<NonZeroU64>,
    /// The start position was passed backwards this tick.
    missed: bool,
}

impl StartWatch {
    /// Armed with `mode`; a start position passed backwards starts there.
    #[cfg(test)]
    pub(crate) fn arm(mode: StartMode) -> Self {
        Self::arm_with(mode, MissedActivation::StartNow, None)
    }

    /// Armed with `mode`; a start position passed backwards is handled
    /// as `policy` says; on a single-turn master (`turn`) the start
    /// position is a place in the turn.
    pub(crate) fn arm_with(
        mode: StartMode,
        policy: MissedActivation,
        turn: Option<NonZeroU64>,
    ) -> Self {
        let phase = match mode {
            StartMode::Immediate => Phase::Now,
            StartMode::OnRisingEdge
            | StartMode::AfterDelay {
                after_edge: true, ..
            }
            | StartMode::AtMasterPosition {
                after_edge: true, ..
            } => Phase::Edge,
            StartMode::AfterDelay { .. } => Phase::Delay { travelled: 0 },
            StartMode::AtMasterPosition { .. } => Phase::Position { fresh: false },
            StartMode::Breakpoint { .. } => Phase::Breakpoint,
        };
        Self {
            mode,
            phase,
            policy,
            turn,
            missed: false,
        }
    }

    /// True once after a tick that passed the start position backwards.
    pub(crate) fn take_missed(&mut self) -> bool {
        core::mem::take(&mut self.missed)
    }

    /// One tick: the master moved from `previous` to `master`; `edge` is a
    /// rising edge of the start input; `watch` the breakpoint position.
    pub(crate) fn step(&mut self, previous: i64, master: i64, edge: bool, watch: i64) -> StartStep {
        let mut previous = previous;
        if self.phase == Phase::Edge {
            if !edge {
                return StartStep::Waiting;
            }
            // Counting and position checks start at the edge: what the
            // master did before it does not count.
            previous = master;
            self.phase = match self.mode {
                StartMode::AfterDelay { .. } => Phase::Delay { travelled: 0 },
                StartMode::AtMasterPosition { .. } => Phase::Position { fresh: true },
                _ => Phase::Now,
            };
        }
        match (self.phase, self.mode) {
            (Phase::Now, _) => StartStep::Engage(master),
            (Phase::Delay { travelled }, StartMode::AfterDelay { counts, .. }) => {
                let remaining = counts.saturating_sub(travelled);
                if remaining == 0 {
                    return StartStep::Engage(master);
                }
                let delta = i128::from(master) - i128::from(previous);
                let moved = u64::try_from(delta.unsigned_abs()).unwrap_or(u64::MAX);
                if moved >= remaining {
                    let step = i128::from(remaining) * delta.signum();
                    let at = i64::try_from(i128::from(previous) + step).unwrap_or(master);
                    StartStep::Engage(at)
                } else {
                    self.phase = Phase::Delay {
                        travelled: travelled + moved,
                    };
                    StartStep::Delaying
                }
            }
            (Phase::Position { fresh }, StartMode::AtMasterPosition { position, .. }) => {
                self.phase = Phase::Position { fresh: false };
                let position = nearest(position, self.turn, previous, master >= previous);
                let forward = !fresh && previous < position && position < master;
                // Arriving on the position from above is a backward pass.
                let backward = !fresh && master <= position && position < previous;
                let on = master == position && (fresh || previous <= position);
                if backward {
                    self.missed = true;
                    match self.policy {
                        MissedActivation::StartNow => StartStep::Engage(position),
                        MissedActivation::NextPass => StartStep::Waiting,
                    }
                } else if on || forward {
                    StartStep::Engage(position)
                } else {
                    StartStep::Waiting
                }
            }
            (Phase::Breakpoint, StartMode::Breakpoint { compare, value }) => {
                let hit = match compare {
                    Compare::AtLeast => watch >= value,
                    Compare::AtMost => watch <= value,
                };
                if hit {
                    StartStep::Engage(master)
                } else {
                    StartStep::Waiting
                }
            }
            // Phases are only ever paired with their own mode (see `arm`).
            _ => StartStep::Engage(master),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delay_engages_at_the_exact_count() {
        let mut s = StartWatch::arm(StartMode::AfterDelay {
            counts: 250,
            after_edge: true,
        });
        assert_eq!(s.step(0, 100, false, 0), StartStep::Waiting);
        assert_eq!(s.step(100, 100, true, 0), StartStep::Delaying);
        assert_eq!(s.step(100, 300, false, 0), StartStep::Delaying);
        // Travel counts either way: 200 + 30.
        assert_eq!(s.step(300, 270, false, 0), StartStep::Delaying);
        // 20 more, reached inside this tick.
        assert_eq!(s.step(270, 1000, false, 0), StartStep::Engage(290));
    }

    #[test]
    fn position_is_reached_or_crossed() {
        let mut s = StartWatch::arm(StartMode::AtMasterPosition {
            position: 500,
            after_edge: false,
        });
        assert_eq!(s.step(0, 400, false, 0), StartStep::Waiting);
        assert_eq!(s.step(400, 900, false, 0), StartStep::Engage(500));
        let mut s = StartWatch::arm(StartMode::AtMasterPosition {
            position: -5,
            after_edge: false,
        });
        assert_eq!(s.step(0, -5, false, 0), StartStep::Engage(-5));
    }

    #[test]
    fn breakpoints_compare_the_watched_axis() {
        let mut s = StartWatch::arm(StartMode::Breakpoint {
            compare: Compare::AtLeast,
            value: 1000,
        });
        assert_eq!(s.step(0, 0, true, 999), StartStep::Waiting);
        assert_eq!(s.step(0, 7, false, 1000), StartStep::Engage(7));
        let mut s = StartWatch::arm(StartMode::Breakpoint {
            compare: Compare::AtMost,
            value: -3,
        });
        assert_eq!(s.step(0, 0, false, -2), StartStep::Waiting);
        assert_eq!(s.step(0, 0, false, -3), StartStep::Engage(0));
    }

    #[test]
    fn edge_start_needs_an_edge() {
        let mut s = StartWatch::arm(StartMode::OnRisingEdge);
        assert_eq!(s.step(0, 0, false, 0), StartStep::Waiting);
        assert_eq!(s.step(0, 3, true, 0), StartStep::Engage(3));
    }
}
