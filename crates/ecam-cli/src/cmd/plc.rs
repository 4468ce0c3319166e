//! `ecam plc run`: runs an instruction-list program in simulated time and
//! prints the dumped devices as one JSON object (the **contract** in
//! `docs/architecture.md`: key order = order of `--dump`, words signed 16-bit,
//! `DDn` signed 32-bit, `DEn` float, bits 0/1, counters their value).

use std::collections::{BTreeSet, HashSet};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use ecam_plc::sim::{self, RunLength, Timing};
use ecam_plc::{Plc, View, Wire};

use crate::progress::Progress;
use crate::values;

/// Subcommands of `ecam plc`.
#[derive(clap::Subcommand)]
pub enum Command {
    /// Run an IL program in simulated time and print devices as JSON.
    Run(RunArgs),
}

/// Arguments of `ecam plc run`.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("length").required(true).args(["scans", "ms"])))]
pub struct RunArgs {
    /// The instruction-list program (`;` comments, one instruction per line).
    #[arg(value_hint = clap::ValueHint::FilePath)]
    pub program: PathBuf,
    /// Scan period in microseconds of simulated time.
    #[arg(long, value_name = "US", default_value_t = sim::DEFAULT_SCAN_US)]
    pub scan_us: u32,
    /// Hardware tick (pulse outputs, E-cam engine, counters) in microseconds.
    #[arg(long, value_name = "US", default_value_t = sim::DEFAULT_TICK_US)]
    pub tick_us: u32,
    /// Run this many scans.
    #[arg(long, value_name = "N")]
    pub scans: Option<u64>,
    /// Run this many milliseconds of simulated time.
    #[arg(long, value_name = "T")]
    pub ms: Option<u64>,
    /// Set a device before the first scan: D100=3183, DD100=3183, DE106=1.6667, M0=1, X2=1, C231=0, D200.F=1, T0=5, Z0=5.
    #[arg(long = "set", value_name = "DEV=VALUE", value_parser = values::set)]
    pub sets: Vec<(View, String)>,
    /// Wire a pulse output to a counter input, e.g. Y1:X0.
    #[arg(long = "wire", value_name = "Yn:Xm", value_parser = values::wire)]
    pub wires: Vec<Wire>,
    /// Load a point table (CSV or JSON file) into a DECAM block before the
    /// first scan, as its register image: D2000=table.csv writes D2038 (the
    /// point count), D2039 and the points from D2040.
    #[arg(long = "load", value_name = "Dn=FILE", value_parser = values::load)]
    pub loads: Vec<(u16, PathBuf)>,
    /// Print a device (or COUNT consecutive ones) after the run: D2000, D2019:2, DD2019, Y7, D2001.1, T0, Z0:8.
    #[arg(long = "dump", value_name = "DEV[:COUNT]", value_parser = values::dump)]
    pub dumps: Vec<Vec<View>>,
    /// Write one CSV row per scan (header `t_us,DEV...`) to this file.
    #[arg(long, value_name = "FILE.csv", requires = "trace_dev", value_parser = crate::paths::csv)]
    pub trace: Option<PathBuf>,
    /// Devices for the trace columns.
    #[arg(long = "trace-dev", value_name = "DEV", num_args = 1.., requires = "trace", value_parser = values::device)]
    pub trace_dev: Vec<View>,
}

/// Runs `ecam plc`.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Run(args) => run_program(&args),
    }
}

fn run_program(args: &RunArgs) -> anyhow::Result<()> {
    // Each key once, in the order of the `--dump`s (a JSON object).
    let mut seen = HashSet::new();
    let dumps: Vec<View> = args
        .dumps
        .iter()
        .flatten()
        .copied()
        .filter(|v| seen.insert(*v))
        .collect();
    let trace_views = args.trace_dev.as_slice();
    let file = args.program.display().to_string();
    let source =
        std::fs::read_to_string(&args.program).with_context(|| format!("cannot read {file}"))?;
    let program = ecam_plc::Program::parse(&source, &file)?;
    tracing::debug!("{file}: {} lines", source.lines().count());
    let mut plc = Plc::new(program)?;
    for &wire in &args.wires {
        plc.hardware_mut().add_wire(wire);
    }
    for (view, value) in &args.sets {
        view.write(plc.devices_mut(), value)
            .with_context(|| format!("--set {view}={value}"))?;
    }
    for (block, path) in &args.loads {
        load_table(plc.devices_mut(), *block, path)
            .with_context(|| format!("--load D{block}={}", path.display()))?;
    }
    let length = match (args.scans, args.ms) {
        (Some(n), _) => RunLength::Scans(n),
        (None, Some(ms)) => RunLength::Millis(ms),
        (None, None) => bail!("give --scans N or --ms T"),
    };
    let timing = Timing {
        scan_us: args.scan_us,
        tick_us: args.tick_us,
    };
    let mut trace = String::new();
    if args.trace.is_some() {
        trace.push_str("t_us");
        for view in trace_views {
            let _ = write!(trace, ",{view}");
        }
        trace.push('\n');
    }
    let tracing = args.trace.is_some();
    // The simulated time the run covers, for the progress bar (the run's
    // own budget check refuses one too long).
    let run_us = match length {
        RunLength::Scans(n) => n.saturating_mul(u64::from(timing.scan_us)),
        RunLength::Millis(ms) => ms.saturating_mul(1000),
    };
    let progress = Progress::new("running", run_us);
    let errors = sim::run(&mut plc, timing, length, |plc| {
        progress.at(plc.now_us());
        if tracing {
            let _ = write!(trace, "{}", plc.now_us());
            for view in trace_views {
                let _ = write!(trace, ",{}", view.read(plc.devices()));
            }
            trace.push('\n');
        }
    })?;
    progress.finish();
    if let Some(path) = &args.trace {
        std::fs::write(path, trace).with_context(|| format!("cannot write {}", path.display()))?;
    }

    // Operation errors are the program's business (D8067/M8067), not a
    // failure of the command: report each distinct one once as a warning.
    let mut seen = BTreeSet::new();
    for e in errors {
        if seen.insert((e.line, e.error.code)) {
            tracing::warn!(
                "{file}:{}: {} (D8067={}, M8067=1)",
                e.line,
                e.error,
                e.error.code
            );
        }
    }
    // The watchdog stopped the program: the PLC's business too (D8061).
    if let Some(fault) = plc.fault() {
        let (line, code) = (fault.line(), fault.code());
        eprintln!("ecam: warning: {file}:{line}: {fault} (D8061={code}, M8061=1)");
    }

    let mut json = String::from("{");
    for (i, view) in dumps.iter().enumerate() {
        if i > 0 {
            json.push_str(", ");
        }
        let _ = write!(json, "\"{view}\": {}", view.read(plc.devices()));
    }
    json.push('}');
    let mut stdout = std::io::stdout().lock();
    writeln!(stdout, "{json}")?;
    Ok(())
}

/// `--load Dn=FILE`: the file's point table written as the block's image.
fn load_table(devices: &mut ecam_plc::Devices, block: u16, file: &Path) -> anyhow::Result<()> {
    let table = match ecam_core::io::read(file)? {
        ecam_core::io::AnyTable::Points(file) => file.table,
        _ => bail!("a DECAM table is a point table: give a CSV or JSON of master,slave points"),
    };
    ecam_plc::decam::load_table(devices, block, &table)?;
    Ok(())
}
