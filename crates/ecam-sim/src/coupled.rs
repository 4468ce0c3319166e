//! The simulation loop of a slave axis: a scenario with couplings beyond
//! the cam (`[modulo]`, `[direction_guard]`, `[registration]`,
//! `[cam_switches]`, `[[plcopen]]` steps) runs on
//! [`ecam_engine::SlaveAxis`]: around the scenario's cam as configured, or,
//! with `[[plcopen]]` steps, around the PLCopen facade the steps drive.

use ecam_core::CamCurve;
use ecam_engine::plcopen_slave::McSlaveAxis;
use ecam_engine::{
    CamAxis, CouplingError, LatchSource, SlaveAxis, SlaveInput, SlaveOutput, StopKind, TickInput,
    TickOutput,
};

use crate::couplings::{Couplings, SwitchAxis};
use crate::error::SimulateError;
use crate::steps::Block;
use crate::summary::{Summary, Tally};
use crate::{Row, Scenario};

/// What one tick of a slave axis' run reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CouplingTick {
    /// The axis: the sum and each coupling's status.
    pub axis: SlaveOutput,
    /// The cam-switch tracks on (bit `i` for track `i`).
    pub tracks: u32,
    /// The axis as a cam's output (the cam's state, events and place,
    /// with the axis' commanded position and pulses): what the trace
    /// and plot of `ecam simulate` draw.
    pub view: TickOutput,
}

/// What the loop needs of the axis it drives; `'s` is the scenario's
/// lifetime (a step's table is borrowed from it for the run).
trait Driven<'s> {
    fn tick(&mut self, input: &SlaveInput) -> SlaveOutput;
    fn apply(&mut self, block: &'s Block) -> Result<(), CouplingError>;
    fn stop(&mut self, kind: StopKind);
}

impl<'s, C: CamCurve> Driven<'s> for SlaveAxis<CamAxis<C>> {
    fn tick(&mut self, input: &SlaveInput) -> SlaveOutput {
        *SlaveAxis::tick(self, input)
    }

    fn apply(&mut self, _block: &'s Block) -> Result<(), CouplingError> {
        // Scenarios with steps run on the facade (see `simulate_couplings`).
        Err(CouplingError::Engine(ecam_engine::EngineError::Busy))
    }

    fn stop(&mut self, kind: StopKind) {
        self.cam_mut().stop(kind);
        if kind == StopKind::Immediate {
            self.stop_couplings();
        }
    }
}

impl<'s> Driven<'s> for McSlaveAxis<&'s dyn CamCurve> {
    fn tick(&mut self, input: &SlaveInput) -> SlaveOutput {
        self.tick_input(input).axis
    }

    fn apply(&mut self, block: &'s Block) -> Result<(), CouplingError> {
        match block {
            Block::CamTableSelect { select, table } => match table {
                Some(table) => self.select_table(table.as_ref(), *select),
                None => self.cam_table_select(*select),
            },
            Block::CamIn(c) => self.cam_in(c),
            Block::CamOut(how) => {
                self.cam_out(*how);
                Ok(())
            }
            Block::GearIn(c) => self.gear_in(c),
            Block::GearInPos(c) => self.gear_in_pos(c),
            Block::GearOut(c) => self.gear_out(c),
            Block::Phasing(c) => self.phasing(c),
            Block::MoveSuperimposed(c) => self.move_superimposed(c),
            Block::HaltSuperimposed(d) => self.halt_superimposed(*d),
            Block::Stop => {
                McSlaveAxis::stop(self);
                Ok(())
            }
        }
    }

    fn stop(&mut self, kind: StopKind) {
        match kind {
            StopKind::Immediate => McSlaveAxis::stop(self),
            StopKind::EndOfCycle => self.cam_out(ecam_engine::plcopen::CamOut::EndOfCycle),
        }
    }
}

/// Runs a scenario with couplings tick by tick; `record` sees every
/// tick's row and the axis' full report, and whether the trace keeps it.
///
/// # Errors
/// A scenario without couplings, a cam or configuration the engine
/// refuses, a `[[plcopen]]` step it refuses (naming the step), or an
/// error of `record`.
pub fn simulate_couplings<E>(
    scenario: &Scenario,
    record: impl FnMut(&Row, &CouplingTick, bool) -> Result<(), E>,
) -> Result<Summary, SimulateError<E>> {
    let Some(couplings) = &scenario.couplings else {
        return Err(SimulateError::NoCouplings);
    };
    let curve: &dyn CamCurve = scenario.curve.as_ref();
    let refused = |error: CouplingError| SimulateError::Refused {
        error,
        master_range: (curve.master_first(), curve.master_last()),
        single_turn: scenario.config.single_turn.map(|t| t.get()),
    };
    if couplings.steps.is_empty() {
        let mut axis =
            SlaveAxis::with_cam(curve, scenario.config, couplings.slave).map_err(refused)?;
        axis.set_slave_position(scenario.slave_start)
            .map_err(SimulateError::SlaveStart)?;
        axis.cam_mut().arm().map_err(SimulateError::Arm)?;
        run(scenario, couplings, axis, record)
    } else {
        let mut axis = McSlaveAxis::new(curve, couplings.slave).map_err(refused)?;
        axis.set_slave_position(scenario.slave_start)
            .map_err(SimulateError::SlaveStart)?;
        run(scenario, couplings, axis, record)
    }
}

fn run<'s, E>(
    scenario: &'s Scenario,
    couplings: &'s Couplings,
    mut axis: impl Driven<'s>,
    mut record: impl FnMut(&Row, &CouplingTick, bool) -> Result<(), E>,
) -> Result<Summary, SimulateError<E>> {
    let tick_us = u64::from(scenario.tick_us);
    let ticks = scenario.ticks();
    let mut stop_pending = scenario.stop;
    let mut steps = couplings.steps.iter().enumerate().peekable();
    let mut done_steps = 0u64;
    let mut switches = couplings.cam_switches.clone();
    let source = couplings.slave.registration.map(|r| r.source);
    let mut tally = Tally::new(scenario);
    let mut last_master = scenario.master_start;
    let mut last_slave = scenario.slave_start;
    let mut slave_latch = None;
    let mut last = None;
    for k in 0..=ticks {
        let t_us = k.saturating_mul(tick_us).min(scenario.duration_us);
        let master = scenario.master_read_at(t_us);
        if let Some(stop) = stop_pending
            && stop.fires(t_us, master)
        {
            axis.stop(stop.kind);
            stop_pending = None;
        }
        while let Some((i, step)) = steps.next_if(|(_, s)| s.trigger.fires(t_us, master)) {
            axis.apply(&step.block)
                .map_err(|error| SimulateError::Step {
                    number: i + 1,
                    block: step.block.name(),
                    error,
                })?;
            done_steps += 1;
        }
        let master_input = scenario.master_input(master);
        // A touch probe latches the mark's position exactly (in hardware,
        // between ticks): a master mark in this tick's travel, a slave mark
        // in the last tick's.
        let latch = match (source, &couplings.marks) {
            (Some(LatchSource::Master), Some(marks)) if k > 0 => marks
                .passed(last_master, master)
                .next()
                .map(|m| scenario.master_input(m)),
            (Some(LatchSource::Slave), Some(_)) => slave_latch.take(),
            _ => None,
        };
        let input = SlaveInput {
            tick: TickInput {
                master: master_input,
                master_fraction: 0,
                start_input: scenario.start_input_at(t_us),
                watch: master,
                dt_us: scenario.tick_us,
                output_enabled: true,
            },
            latch,
        };
        let out = axis.tick(&input);
        if let (Some(LatchSource::Slave), Some(marks)) = (source, &couplings.marks) {
            slave_latch = marks.passed(last_slave, out.slave).next();
        }
        last_master = master;
        last_slave = out.slave;
        let tracks = match &mut switches {
            Some(s) => {
                let position = match s.axis {
                    SwitchAxis::Master => libm_floor(out.master_seen),
                    SwitchAxis::Slave => out.slave,
                };
                s.group
                    .tick(&s.switches, position, scenario.tick_us, u32::MAX)
            }
            None => 0,
        };
        let view = TickOutput {
            slave: out.slave,
            pulses: out.pulses,
            direction_forward: out.direction_forward,
            emitted: out.emitted,
            backlog: out.backlog,
            pulse_delayed: out.pulse_delayed,
            busy: out.busy,
            ..out.cam
        };
        let in_sync = view.in_sync || tracks != 0;
        let row = tally.take(k, t_us, master, master_input, &view, in_sync);
        if let Some(fault) = out.fault {
            // A gear command the next tick could not carry out.
            tally.summary.fault.get_or_insert_with(|| fault.to_string());
        }
        let tick = CouplingTick {
            axis: out,
            tracks,
            view,
        };
        record(&row, &tick, k % scenario.trace_every == 0 || k == ticks)
            .map_err(SimulateError::Record)?;
        last = Some(out);
    }
    let mut summary = tally.summary;
    if let Some(out) = last {
        summary.modulo_position = out.modulo.map(|m| m.position);
        summary.modulo_turns = out.modulo.map(|m| m.turns);
        summary.cam_slave = Some(out.cam.slave);
        summary.gear_slave = Some(out.gear.slave);
        summary.superimposed = Some(out.superimposed.position);
        summary.phase_shift = Some(out.phasing.shift);
        if let Some(r) = out.registration {
            summary.registration_marks = Some(r.marks);
            summary.registration_missed = Some(r.missed);
            summary.registration_rejected = Some(r.rejected);
            summary.registration_correction = Some(r.correction);
        }
        summary.guard_lost = out.guard.map(|g| g.lost);
    }
    summary.cam_switch_toggles = switches.map(|s| s.group.toggles());
    summary.plcopen_steps = (!couplings.steps.is_empty()).then_some(done_steps);
    Ok(summary)
}

/// `v` rounded down to a whole count (saturating).
fn libm_floor(v: f64) -> i64 {
    let f = v.floor();
    if f.is_finite() { f as i64 } else { 0 }
}
