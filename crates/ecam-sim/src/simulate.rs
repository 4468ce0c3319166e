//! The simulation loop: the engine ticked in simulated time along a
//! scenario's master motion, start input and stop, summarised as it goes.

use ecam_engine::{CamAxis, TickInput, TickOutput};
use serde::Serialize;

use crate::error::SimulateError;
use crate::scenario::Scenario;
use crate::trace::{Row, state_name};

/// What a run did, as `ecam simulate` prints it (one JSON object; a
/// contract: keys may only be added, at the end).
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct Summary {
    /// Master position at the end (unwrapped counts).
    pub final_master: i64,
    /// Commanded slave position at the end.
    pub final_slave: i64,
    /// Emitted output position at the end.
    pub final_emitted: i64,
    /// Net pulses emitted (forward minus reverse).
    pub pulses: i64,
    /// Pulses emitted forward.
    pub pulses_forward: u64,
    /// Pulses emitted in reverse.
    pub pulses_reverse: u64,
    /// Completed cam cycles (signed).
    pub cycles: i64,
    /// The largest |commanded − emitted| seen.
    pub max_backlog: u64,
    /// The engine state at the end ([`state_name`]).
    pub state: &'static str,
    /// When the cam engaged, in seconds (`None`: never).
    pub engaged_at_s: Option<f64>,
    /// Ticks with a sync window on.
    pub sync_ticks: u64,
    /// Ticks simulated (tick 0 included).
    pub ticks: u64,
    /// Simulated time at the last tick, in seconds.
    pub time_s: f64,
    /// Document 002's CamInputOffset at the end.
    pub input_offset: i64,
    /// Document 002's CamOutputOffset at the end.
    pub output_offset: i64,
    /// Seams where a periodic table's slave jumped (spread under the ceiling).
    pub seam_jumps: u64,
    /// Tables that took over at a seam (`[[switch]]`).
    pub table_switches: u64,
    /// Most pulses in one tick (the drive's peak frequency × tick).
    pub max_pulses_per_tick: u64,
    /// Times the emitted direction turned round.
    pub direction_changes: u64,
    /// The engine's first runtime fault, if any.
    pub fault: Option<String>,
}

/// Runs the scenario tick by tick; `record` sees every tick, and whether
/// the trace keeps it (`trace_every`).
///
/// # Errors
/// A cam or configuration the engine refuses (naming the table's master
/// range), a start slave position or arming it refuses, or an error of
/// `record`, which stops the run.
pub fn simulate<E>(
    scenario: &Scenario,
    mut record: impl FnMut(&Row, &TickOutput, bool) -> Result<(), E>,
) -> Result<Summary, SimulateError<E>> {
    let curve: &dyn ecam_core::CamCurve = scenario.curve.as_ref();
    let mut axis =
        CamAxis::new(curve, scenario.config).map_err(|error| SimulateError::Refused {
            error,
            master_range: (curve.master_first(), curve.master_last()),
            single_turn: scenario.config.single_turn.map(|t| t.get()),
        })?;
    axis.set_slave_position(scenario.slave_start)
        .map_err(SimulateError::SlaveStart)?;
    axis.arm().map_err(SimulateError::Arm)?;

    let tick_us = u64::from(scenario.tick_us);
    let ticks = scenario.ticks();
    let mut stop_pending = scenario.stop;
    let mut switches = scenario.switches.iter().enumerate().peekable();
    let mut prev_slave = scenario.slave_start;
    let mut summary = Summary {
        final_master: scenario.master_start,
        final_slave: scenario.slave_start,
        final_emitted: scenario.slave_start,
        pulses: 0,
        pulses_forward: 0,
        pulses_reverse: 0,
        cycles: 0,
        max_backlog: 0,
        state: "idle",
        engaged_at_s: None,
        sync_ticks: 0,
        ticks: 0,
        time_s: 0.0,
        input_offset: 0,
        output_offset: 0,
        seam_jumps: 0,
        table_switches: 0,
        max_pulses_per_tick: 0,
        direction_changes: 0,
        fault: None,
    };
    let mut last_direction = 0i64;
    // Tick 0 is the state at t = 0; the last tick lands on the duration.
    for k in 0..=ticks {
        let t_us = k.saturating_mul(tick_us).min(scenario.duration_us);
        let master = scenario.master_read_at(t_us);
        if let Some(stop) = stop_pending {
            if stop.fires(t_us, master) {
                axis.stop(stop.kind);
                stop_pending = None;
            }
        }
        while let Some((i, switch)) = switches.next_if(|(_, s)| s.trigger.fires(t_us, master)) {
            let curve: &dyn ecam_core::CamCurve = switch.curve.as_ref();
            axis.switch_curve(curve, switch.at)
                .map_err(|error| SimulateError::Switch {
                    number: i + 1,
                    error,
                    master_range: (curve.master_first(), curve.master_last()),
                })?;
        }
        let master_input = scenario.master_input(master);
        let input = TickInput {
            master: master_input,
            master_fraction: 0,
            start_input: scenario.start_input_at(t_us),
            watch: master,
            dt_us: scenario.tick_us,
            output_enabled: true,
        };
        let out = axis.tick(&input);
        // Dividing by the exact power of ten keeps `t` free of float noise
        // (0.101, not 0.10099999999999999).
        let t = t_us as f64 / 1e6;
        // Tick 0 has no interval before it: a jump at engage is not a speed.
        let velocity = if k == 0 {
            0.0
        } else {
            (out.slave.saturating_sub(prev_slave)) as f64 * 1e6 / tick_us as f64
        };
        prev_slave = out.slave;
        summary.pulses = summary.pulses.saturating_add(out.pulses);
        if out.pulses > 0 {
            summary.pulses_forward = summary
                .pulses_forward
                .saturating_add(out.pulses.unsigned_abs());
        } else {
            summary.pulses_reverse = summary
                .pulses_reverse
                .saturating_add(out.pulses.unsigned_abs());
        }
        summary.max_backlog = summary.max_backlog.max(out.backlog.unsigned_abs());
        summary.max_pulses_per_tick = summary.max_pulses_per_tick.max(out.pulses.unsigned_abs());
        if out.pulses != 0 {
            if last_direction != 0 && out.pulses.signum() != last_direction {
                summary.direction_changes += 1;
            }
            last_direction = out.pulses.signum();
        }
        if out.events.seam_jump {
            summary.seam_jumps += 1;
        }
        if out.events.table_switched {
            summary.table_switches += 1;
        }
        if out.in_sync {
            summary.sync_ticks += 1;
        }
        if out.events.engaged && summary.engaged_at_s.is_none() {
            summary.engaged_at_s = Some(t);
        }
        if let Some(fault) = out.fault {
            summary.fault.get_or_insert_with(|| fault.to_string());
        }
        let row = Row {
            t,
            master: master_input,
            slave: out.slave,
            velocity,
            pulses: out.pulses,
            emitted: out.emitted,
            backlog: out.backlog,
            in_sync: out.in_sync,
        };
        record(&row, &out, k % scenario.trace_every == 0 || k == ticks)
            .map_err(SimulateError::Record)?;
        summary.final_master = master;
        summary.final_slave = out.slave;
        summary.final_emitted = out.emitted;
        summary.cycles = out.cycle;
        summary.state = state_name(out.state);
        summary.input_offset = out.input_offset;
        summary.output_offset = out.output_offset;
        summary.ticks = k + 1;
        summary.time_s = t;
    }
    Ok(summary)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn document_002_linear_table_gives_202_at_input_101() {
        let s = Scenario::parse(
            r#"
            tick_us = 1000
            [table]
            uniform = [0, 100, 200]
            counts = 100
            [cam]
            kind = "repeat"
            [start]
            slave_align = "relative"
            [master]
            moves = [[0.101, 101]]
            "#,
            std::path::Path::new("."),
        )
        .unwrap();
        let summary = simulate(&s, |_, _, _| Ok::<(), std::io::Error>(())).unwrap();
        assert_eq!(summary.final_master, 101);
        assert_eq!(summary.final_slave, 202);
        assert_eq!(summary.pulses, 202);
    }
}
