//! `ecam simulate`: run a scenario through the engine in simulated time.
//!
//! Prints one JSON object on stdout (a contract: keys may only be added),
//! e.g. `{"final_master":60000,"final_slave":3500,"pulses":3000,...}`:
//! - `final_master`: master position at the end (unwrapped counts);
//! - `final_slave`: commanded slave position at the end;
//! - `final_emitted`: emitted output position at the end;
//! - `pulses`: net pulses emitted (forward minus reverse),
//!   `pulses_forward` / `pulses_reverse`: each direction's count;
//! - `cycles`: completed cam cycles (signed), `max_backlog`: the largest
//!   |commanded − emitted| seen; `state`: the engine state at the end;
//! - `engaged_at_s`: when the cam engaged (null if never), `sync_ticks`: ticks
//!   with a sync window on; `ticks`, `time_s`: how much was simulated;
//! - `input_offset`, `output_offset`: document 002's CamInputOffset and
//!   CamOutputOffset at the end; `fault`: the engine's runtime fault, if any.

use std::io::Write;

use std::path::PathBuf;

use ecam_engine::{CamAxis, TickInput};
use serde::Serialize;

use crate::progress::Progress;
use crate::scenario::Scenario;
use crate::trace::{Row, TraceWriter, state_name};
use ecam_plot::{Figure, Panel, Series};

/// Arguments of `ecam simulate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scenario file (TOML; see docs/simulate.md).
    pub scenario: PathBuf,
    /// Write every tick (or every `trace_every`-th) to this CSV file.
    #[arg(long, value_name = "FILE.csv")]
    pub trace: Option<PathBuf>,
    /// Plot master, slave, velocity and backlog over time (SVG or PNG).
    #[arg(long, value_name = "FILE.svg|png")]
    pub plot: Option<PathBuf>,
}

/// The one-line JSON summary.
#[derive(Serialize, Debug)]
struct Summary {
    final_master: i64,
    final_slave: i64,
    final_emitted: i64,
    pulses: i64,
    pulses_forward: u64,
    pulses_reverse: u64,
    cycles: i64,
    max_backlog: u64,
    state: &'static str,
    engaged_at_s: Option<f64>,
    sync_ticks: u64,
    ticks: u64,
    time_s: f64,
    input_offset: i64,
    output_offset: i64,
    /// Seams where a periodic table's slave jumped (spread under the ceiling).
    seam_jumps: u64,
    /// Most pulses in one tick (the drive's peak frequency × tick).
    max_pulses_per_tick: u64,
    /// Times the emitted direction turned round.
    direction_changes: u64,
    fault: Option<String>,
}

/// Most points a trace plot draws (about two per pixel); longer runs are
/// thinned evenly.
const PLOT_POINTS: usize = 2_000;

/// Runs `ecam simulate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    if let Some(plot) = &args.plot {
        crate::plot::Format::of(plot)?;
    }
    let scenario = Scenario::load(&args.scenario)?;
    let mut trace = args.trace.as_deref().map(TraceWriter::create).transpose()?;
    let ticks = scenario.duration_us.div_ceil(u64::from(scenario.tick_us));
    let mut plotted = args.plot.as_ref().map(|_| PlotRows::new(ticks));
    let summary = simulate(&scenario, |row, out, traced| {
        if traced {
            if let Some(t) = trace.as_mut() {
                t.write(row, out)?;
            }
        }
        if let Some(p) = plotted.as_mut() {
            p.add(row);
        }
        Ok(())
    })?;
    if let Some(t) = trace {
        t.finish()?;
    }
    if let (Some(plot), Some(rows)) = (&args.plot, plotted) {
        crate::plot::draw(&rows.figure(&args.scenario), plot)?;
    }
    // A handle, not `println!`: a closed pipe is an error, not a panic.
    writeln!(
        std::io::stdout().lock(),
        "{}",
        serde_json::to_string(&summary)?
    )?;
    Ok(())
}

/// Runs the scenario tick by tick; `record` sees every tick, and whether
/// the trace keeps it (`trace_every`).
fn simulate(
    scenario: &Scenario,
    mut record: impl FnMut(&Row, &ecam_engine::TickOutput, bool) -> anyhow::Result<()>,
) -> anyhow::Result<Summary> {
    let curve: &dyn ecam_core::CamCurve = scenario.curve.as_ref();
    let mut axis = CamAxis::new(curve, scenario.config).map_err(|e| {
        // Name the numbers the engine compared, so the user sees what to change.
        let turn = match scenario.config.single_turn {
            Some(t) => format!(", single_turn = {t}"),
            None => String::new(),
        };
        anyhow::anyhow!(
            "the engine refuses the scenario: {e} (table master {} .. {}{turn})",
            curve.master_first(),
            curve.master_last()
        )
    })?;
    axis.set_slave_position(scenario.slave_start)
        .map_err(|e| anyhow::anyhow!("cannot set the start slave position: {e}"))?;
    axis.arm()
        .map_err(|e| anyhow::anyhow!("cannot arm the cam: {e}"))?;

    let tick_us = u64::from(scenario.tick_us);
    let ticks = scenario.duration_us.div_ceil(tick_us);
    let progress = Progress::new(ticks);
    let mut stop_pending = scenario.stop;
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
        record(&row, &out, k % scenario.trace_every == 0 || k == ticks)?;
        summary.final_master = master;
        summary.final_slave = out.slave;
        summary.final_emitted = out.emitted;
        summary.cycles = out.cycle;
        summary.state = state_name(out.state);
        summary.input_offset = out.input_offset;
        summary.output_offset = out.output_offset;
        summary.ticks = k + 1;
        summary.time_s = t;
        progress.tick(k);
    }
    progress.finish();
    Ok(summary)
}

/// What the trace plot keeps of a run: at most about [`PLOT_POINTS`]
/// evenly spaced rows (a year-long run must not hold every tick in memory),
/// and every span of time a sync window was on.
struct PlotRows {
    step: u64,
    seen: u64,
    kept: Vec<Row>,
    last: Option<Row>,
    sync_from: Option<f64>,
    shaded: Vec<(f64, f64)>,
}

impl PlotRows {
    fn new(ticks: u64) -> Self {
        Self {
            step: ticks.div_ceil(PLOT_POINTS as u64).max(1),
            seen: 0,
            kept: Vec::new(),
            last: None,
            sync_from: None,
            shaded: Vec::new(),
        }
    }

    fn add(&mut self, row: &Row) {
        if self.seen % self.step == 0 {
            self.kept.push(*row);
        } else if let Some(k) = self.kept.last_mut() {
            // A backlog spike between kept rows must still show.
            if row.backlog.unsigned_abs() > k.backlog.unsigned_abs() {
                k.backlog = row.backlog;
            }
        }
        self.seen += 1;
        match (row.in_sync, self.sync_from) {
            (true, None) => self.sync_from = Some(row.t),
            (false, Some(from)) => {
                self.shaded.push((from, row.t));
                self.sync_from = None;
            }
            _ => {}
        }
        self.last = Some(*row);
    }

    /// Master, slave, velocity and backlog over time; sync-on spans shaded.
    fn figure(mut self, scenario: &std::path::Path) -> Figure {
        if let Some(last) = self.last {
            if self.kept.last().is_none_or(|k| k.t < last.t) {
                self.kept.push(last);
            }
            if let Some(from) = self.sync_from {
                self.shaded.push((from, last.t));
            }
        }
        // Velocity over each kept interval: per-tick values jump between
        // whole pulses per tick, which hides the motion in a plot.
        let mut prev: Option<Row> = None;
        for r in &mut self.kept {
            r.velocity = match prev {
                Some(p) if r.t > p.t => (r.slave - p.slave) as f64 / (r.t - p.t),
                _ => 0.0,
            };
            prev = Some(*r);
        }
        trace_figure(&self.kept, self.shaded, scenario)
    }
}

fn trace_figure(kept: &[Row], shaded: Vec<(f64, f64)>, scenario: &std::path::Path) -> Figure {
    let column = |f: fn(&Row) -> f64| kept.iter().map(f).collect::<Vec<f64>>();
    let name = scenario
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    Figure {
        title: format!("ecam simulate {name}"),
        x_label: "time (s)".into(),
        x: column(|r| r.t),
        panels: vec![
            Panel {
                title: "master (counts)".into(),
                series: vec![Series {
                    name: "master".into(),
                    values: column(|r| r.master as f64),
                }],
            },
            Panel {
                title: "slave (pulses)".into(),
                series: vec![
                    Series {
                        name: "commanded".into(),
                        values: column(|r| r.slave as f64),
                    },
                    Series {
                        name: "emitted".into(),
                        values: column(|r| r.emitted as f64),
                    },
                ],
            },
            Panel {
                title: "velocity (pulses/s)".into(),
                series: vec![Series {
                    name: "commanded".into(),
                    values: column(|r| r.velocity),
                }],
            },
            Panel {
                title: "backlog (pulses)".into(),
                series: vec![Series {
                    name: "backlog".into(),
                    values: column(|r| r.backlog as f64),
                }],
            },
        ],
        shaded,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn row(t: f64, in_sync: bool) -> Row {
        Row {
            t,
            master: 0,
            slave: 0,
            velocity: 0.0,
            pulses: 0,
            emitted: 0,
            backlog: 0,
            in_sync,
        }
    }

    #[test]
    fn plot_rows_thin_long_runs_but_keep_sync_spans() {
        let ticks = 10 * PLOT_POINTS as u64;
        let mut p = PlotRows::new(ticks);
        for k in 0..=ticks {
            p.add(&row(k as f64, (1000..=1004).contains(&k) || k >= ticks - 2));
        }
        let fig = p.figure(std::path::Path::new("x.toml"));
        assert!(fig.x.len() <= PLOT_POINTS + 2);
        assert_eq!(fig.x.last(), Some(&(ticks as f64)));
        assert_eq!(
            fig.shaded,
            vec![(1000.0, 1005.0), ((ticks - 2) as f64, ticks as f64)]
        );
    }

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
        let summary = simulate(&s, |_, _, _| Ok(())).unwrap();
        assert_eq!(summary.final_master, 101);
        assert_eq!(summary.final_slave, 202);
        assert_eq!(summary.pulses, 202);
    }
}
