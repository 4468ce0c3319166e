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
//!
//! The run itself, and every field of the summary, is [`ecam_sim`]'s; this
//! writes what it reports.

use std::io::Write;
use std::path::PathBuf;

use ecam_plot::{Figure, Panel, Series};
use ecam_sim::{Row, Scenario, simulate};

use crate::progress::Progress;
use crate::trace::TraceWriter;

/// Arguments of `ecam simulate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scenario file (TOML; see docs/simulate.md).
    pub scenario: PathBuf,
    /// Write every tick (or every `trace_every`-th) to this CSV file.
    #[arg(long, value_name = "FILE.csv", value_parser = crate::paths::csv)]
    pub trace: Option<PathBuf>,
    /// Plot master, slave, velocity and backlog over time (SVG or PNG).
    #[arg(long, value_name = "FILE.svg|png", value_parser = crate::paths::picture)]
    pub plot: Option<PathBuf>,
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
    let ticks = scenario.ticks();
    let mut plotted = args.plot.as_ref().map(|_| PlotRows::new(ticks));
    // Made at the first tick, once the engine has accepted the scenario.
    let mut progress = None;
    let mut done = 0u64;
    let summary = simulate(&scenario, |row, out, traced| {
        if traced {
            if let Some(t) = trace.as_mut() {
                t.write(row, out)?;
            }
        }
        if let Some(p) = plotted.as_mut() {
            p.add(row);
        }
        progress
            .get_or_insert_with(|| Progress::new(ticks))
            .tick(done);
        done += 1;
        Ok::<(), anyhow::Error>(())
    })?;
    if let Some(progress) = progress {
        progress.finish();
    }
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
        if self.seen.is_multiple_of(self.step) {
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
}
