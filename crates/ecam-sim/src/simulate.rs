//! The simulation loop: the engine ticked in simulated time along a
//! scenario's master motion, start input and stop, summarised as it goes.

use ecam_engine::{CamAxis, TickInput, TickOutput};

use crate::error::SimulateError;
use crate::scenario::Scenario;
use crate::summary::{Summary, Tally};
use crate::trace::Row;

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
    if scenario.couplings.is_some() {
        // A slave axis; the trace sees the axis as a cam's output.
        return crate::coupled::simulate_couplings(scenario, |row, tick, traced| {
            record(row, &tick.view, traced)
        });
    }
    let curve: &dyn ecam_core::CamCurve = scenario.curve.as_ref();
    let mut axis =
        CamAxis::new(curve, scenario.config).map_err(|error| SimulateError::Refused {
            error: error.into(),
            master_range: (curve.master_first(), curve.master_last()),
            single_turn: scenario.config.single_turn.map(|t| t.get()),
        })?;
    axis.set_slave_position(scenario.slave_start)
        .map_err(|e| SimulateError::SlaveStart(e.into()))?;
    axis.arm().map_err(SimulateError::Arm)?;

    let tick_us = u64::from(scenario.tick_us);
    let ticks = scenario.ticks();
    let mut stop_pending = scenario.stop;
    let mut switches = scenario.switches.iter().enumerate().peekable();
    let mut tally = Tally::new(scenario);
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
        let row = tally.take(k, t_us, master, master_input, &out, out.in_sync);
        record(&row, &out, k % scenario.trace_every == 0 || k == ticks)
            .map_err(SimulateError::Record)?;
    }
    Ok(tally.summary)
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
