//! What a run did, as `ecam simulate` prints it, built up tick by tick
//! (by the plain cam's loop and the slave axis' alike).

use ecam_engine::TickOutput;
use serde::Serialize;

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
    /// A modulo slave's place in the turn at the end (`[modulo]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modulo_position: Option<i64>,
    /// A modulo slave's whole turns at the end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modulo_turns: Option<i64>,
    /// The cam's part of the slave at the end (a slave axis' run).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cam_slave: Option<i64>,
    /// The gear's part at the end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gear_slave: Option<i64>,
    /// The superimposed moves' part at the end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub superimposed: Option<i64>,
    /// The phase shift at the end, master counts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phase_shift: Option<f64>,
    /// Registration: marks taken, windows missed, latches rejected.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub registration_marks: Option<u64>,
    /// Registration windows that closed without a mark.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub registration_missed: Option<u64>,
    /// Latches outside the registration window.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub registration_rejected: Option<u64>,
    /// The registration correction in force at the end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub registration_correction: Option<f64>,
    /// The direction guard's lost master travel at the end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub guard_lost: Option<f64>,
    /// How many times a cam-switch track switched.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cam_switch_toggles: Option<u64>,
    /// `[[plcopen]]` steps carried out.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plcopen_steps: Option<u64>,
}

/// The summary built up tick by tick, and each tick's trace row.
pub(crate) struct Tally {
    pub(crate) summary: Summary,
    last_direction: i64,
    prev_slave: i64,
    tick_us: u64,
}

impl Tally {
    pub(crate) fn new(scenario: &Scenario) -> Self {
        Self {
            summary: Summary {
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
                modulo_position: None,
                modulo_turns: None,
                cam_slave: None,
                gear_slave: None,
                superimposed: None,
                phase_shift: None,
                registration_marks: None,
                registration_missed: None,
                registration_rejected: None,
                registration_correction: None,
                guard_lost: None,
                cam_switch_toggles: None,
                plcopen_steps: None,
            },
            last_direction: 0,
            prev_slave: scenario.slave_start,
            tick_us: u64::from(scenario.tick_us),
        }
    }

    /// Takes tick `k` (at `t_us`, the master at `master`, handed to the
    /// engine as `master_input`) and gives its trace row; `in_sync` is what
    /// the row and the summary count as a sync window on.
    pub(crate) fn take(
        &mut self,
        k: u64,
        t_us: u64,
        master: i64,
        master_input: i64,
        out: &TickOutput,
        in_sync: bool,
    ) -> Row {
        let summary = &mut self.summary;
        // Dividing by the exact power of ten keeps `t` free of float noise
        // (0.101, not 0.10099999999999999).
        let t = t_us as f64 / 1e6;
        // Tick 0 has no interval before it: a jump at engage is not a speed.
        let velocity = if k == 0 {
            0.0
        } else {
            (out.slave.saturating_sub(self.prev_slave)) as f64 * 1e6 / self.tick_us as f64
        };
        self.prev_slave = out.slave;
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
            if self.last_direction != 0 && out.pulses.signum() != self.last_direction {
                summary.direction_changes += 1;
            }
            self.last_direction = out.pulses.signum();
        }
        if out.events.seam_jump {
            summary.seam_jumps += 1;
        }
        if out.events.table_switched {
            summary.table_switches += 1;
        }
        if in_sync {
            summary.sync_ticks += 1;
        }
        if out.events.engaged && summary.engaged_at_s.is_none() {
            summary.engaged_at_s = Some(t);
        }
        if let Some(fault) = out.fault {
            summary.fault.get_or_insert_with(|| fault.to_string());
        }
        summary.final_master = master;
        summary.final_slave = out.slave;
        summary.final_emitted = out.emitted;
        summary.cycles = out.cycle;
        summary.state = state_name(out.state);
        summary.input_offset = out.input_offset;
        summary.output_offset = out.output_offset;
        summary.ticks = k + 1;
        summary.time_s = t;
        Row {
            t,
            master: master_input,
            slave: out.slave,
            velocity,
            pulses: out.pulses,
            emitted: out.emitted,
            backlog: out.backlog,
            in_sync,
        }
    }
}
