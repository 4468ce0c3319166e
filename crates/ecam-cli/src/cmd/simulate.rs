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
//! The run itself, every field of the summary, the trace CSV and the plot
//! are [`ecam_sim`]'s; this wires them to the arguments.

use std::io::Write;
use std::path::PathBuf;

use ecam_sim::{Scenario, TracePlot, TraceWriter, simulate};

use crate::progress::Progress;

/// Arguments of `ecam simulate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scenario file (TOML; see docs/simulate.md).
    #[arg(value_hint = clap::ValueHint::FilePath)]
    pub scenario: PathBuf,
    /// Write every tick (or every `trace_every`-th) to this CSV file.
    #[arg(long, value_name = "FILE.csv", value_parser = crate::paths::csv)]
    pub trace: Option<PathBuf>,
    /// Plot master, slave, velocity and backlog over time (SVG or PNG).
    #[arg(long, value_name = "FILE.svg|png", value_parser = crate::paths::picture)]
    pub plot: Option<PathBuf>,
}

/// Runs `ecam simulate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = Scenario::load(&args.scenario)?;
    let mut trace = args.trace.as_deref().map(TraceWriter::create).transpose()?;
    let ticks = scenario.ticks();
    let mut plotted = args.plot.as_ref().map(|_| TracePlot::new(ticks));
    tracing::debug!(
        "{}: {ticks} ticks of {} us",
        args.scenario.display(),
        scenario.tick_us
    );
    let progress = Progress::new("simulating", ticks);
    let mut done = 0u64;
    let summary = simulate(&scenario, |row, out, traced| {
        if traced {
            if let Some(t) = trace.as_mut() {
                t.write(row, out)?;
            }
        }
        if let Some(p) = plotted.as_mut() {
            p.add(row, out);
        }
        progress.at(done);
        done += 1;
        Ok::<(), ecam_sim::TraceError>(())
    })?;
    progress.finish();
    if let Some(t) = trace {
        t.finish()?;
    }
    if let (Some(plot), Some(rows)) = (&args.plot, plotted) {
        let name = args.scenario.file_name().unwrap_or_default();
        ecam_plot::draw_chart(&rows.chart(&name.to_string_lossy()), plot)?;
    }
    // A handle, not `println!`: a closed pipe is an error, not a panic.
    writeln!(
        std::io::stdout().lock(),
        "{}",
        serde_json::to_string(&summary)?
    )?;
    Ok(())
}
