//! What the simulation loop reports at each tick, besides the engine's own
//! [`TickOutput`](ecam_engine::TickOutput).

use ecam_engine::AxisState;

/// One tick of a run: the trace CSV's first columns, and what a trace plot
/// draws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    /// Seconds since the start.
    pub t: f64,
    /// Master input of the tick (the raw turn position on a single-turn
    /// master).
    pub master: i64,
    /// Commanded slave position.
    pub slave: i64,
    /// Commanded slave velocity over the last tick, pulses per second (0 at
    /// tick 0, which has no interval before it).
    pub velocity: f64,
    /// Pulses this tick (signed).
    pub pulses: i64,
    /// Emitted position.
    pub emitted: i64,
    /// Commanded minus emitted.
    pub backlog: i64,
    /// Whether any sync window was on.
    pub in_sync: bool,
}

/// The engine state as a lower-case word, as the summary and the trace
/// write it.
pub fn state_name(state: AxisState) -> &'static str {
    match state {
        AxisState::Idle => "idle",
        AxisState::Armed => "armed",
        AxisState::Delaying => "delaying",
        AxisState::Running => "running",
        AxisState::Stopping => "stopping",
        AxisState::Finished => "finished",
        AxisState::Velocity => "velocity",
    }
}
