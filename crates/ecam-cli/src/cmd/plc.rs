//! `ecam plc run`: runs an instruction-list program in simulated time and
//! prints the dumped devices as one JSON object (the **contract** in
//! `docs/architecture.md`: key order = order of `--dump`, words signed 16-bit,
//! `DDn` signed 32-bit, `DEn` float, bits 0/1, counters their value).

use std::collections::{BTreeSet, HashSet};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;

use anyhow::{Context as _, bail};
use ecam_plc::Plc;
use ecam_plc::View;
use ecam_plc::Wire;
use ecam_plc::sim::{self, RunLength, Timing};

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
    #[arg(long = "set", value_name = "DEV=VALUE")]
    pub sets: Vec<String>,
    /// Wire a pulse output to a counter input, e.g. Y1:X0.
    #[arg(long = "wire", value_name = "Yn:Xm")]
    pub wires: Vec<String>,
    /// Load a point table (CSV or JSON file) into a DECAM block before the
    /// first scan, as its register image: D2000=table.csv writes D2038 (the
    /// point count), D2039 and the points from D2040.
    #[arg(long = "load", value_name = "Dn=FILE")]
    pub loads: Vec<String>,
    /// Print a device (or COUNT consecutive ones) after the run: D2000, D2019:2, DD2019, Y7, D2001.1, T0, Z0:8.
    #[arg(long = "dump", value_name = "DEV[:COUNT]")]
    pub dumps: Vec<String>,
    /// Write one CSV row per scan (header `t_us,DEV...`) to this file.
    #[arg(long, value_name = "FILE.csv", requires = "trace_dev", value_parser = crate::paths::csv)]
    pub trace: Option<PathBuf>,
    /// Devices for the trace columns.
    #[arg(long = "trace-dev", value_name = "DEV", num_args = 1.., requires = "trace")]
    pub trace_dev: Vec<String>,
}

/// Runs `ecam plc`.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Run(args) => run_program(&args),
    }
}

fn run_program(args: &RunArgs) -> anyhow::Result<()> {
    let dumps = dump_views(&args.dumps)?;
    let trace_views = args
        .trace_dev
        .iter()
        .map(|text| View::parse(text))
        .collect::<Result<Vec<_>, _>>()
        .context("--trace-dev")?;
    let file = args.program.display().to_string();
    let source =
        std::fs::read_to_string(&args.program).with_context(|| format!("cannot read {file}"))?;
    let program = ecam_plc::Program::parse(&source, &file)?;
    let mut plc = Plc::new(program)?;
    for wire in &args.wires {
        plc.hardware_mut()
            .add_wire(Wire::parse(wire).context("--wire")?);
    }
    for set in &args.sets {
        let (name, value) = set
            .split_once('=')
            .with_context(|| format!("--set `{set}`: expected DEV=VALUE, e.g. D100=3183"))?;
        View::parse(name)
            .and_then(|view| view.write(plc.devices_mut(), value))
            .with_context(|| format!("--set `{set}`"))?;
    }
    for load in &args.loads {
        load_table(plc.devices_mut(), load).with_context(|| format!("--load `{load}`"))?;
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
        for view in &trace_views {
            let _ = write!(trace, ",{view}");
        }
        trace.push('\n');
    }
    let tracing = args.trace.is_some();
    let errors = sim::run(&mut plc, timing, length, |plc| {
        if tracing {
            let _ = write!(trace, "{}", plc.now_us());
            for view in &trace_views {
                let _ = write!(trace, ",{}", view.read(plc.devices()));
            }
            trace.push('\n');
        }
    })?;
    if let Some(path) = &args.trace {
        std::fs::write(path, trace).with_context(|| format!("cannot write {}", path.display()))?;
    }

    // Operation errors are the program's business (D8067/M8067), not a
    // failure of the command: report each distinct one once as a warning.
    let mut seen = BTreeSet::new();
    for e in errors {
        if seen.insert((e.line, e.error.code)) {
            eprintln!(
                "ecam: warning: {file}:{}: {} (D8067={}, M8067=1)",
                e.line, e.error, e.error.code
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

/// Expands `--dump` arguments in order, dropping repeats (a JSON object has
/// each key once).
fn dump_views(dumps: &[String]) -> anyhow::Result<Vec<View>> {
    let mut views: Vec<View> = Vec::new();
    let mut seen = HashSet::new();
    for dump in dumps {
        let (name, count) = match dump.split_once(':') {
            Some((name, count)) => {
                let count: u16 = count.parse().ok().filter(|&c| c >= 1).with_context(|| {
                    format!("--dump `{dump}`: COUNT must be a whole number from 1 to 65535")
                })?;
                (name, count)
            }
            None => (dump.as_str(), 1),
        };
        let first = View::parse(name).with_context(|| format!("--dump `{dump}`"))?;
        for k in 0..count {
            let view = first.nth(k).with_context(|| format!("--dump `{dump}`"))?;
            if seen.insert(view) {
                views.push(view);
            }
        }
    }
    Ok(views)
}

/// `--load Dn=FILE`: the file's point table written as the block's image.
fn load_table(devices: &mut ecam_plc::Devices, load: &str) -> anyhow::Result<()> {
    let (block, file) = load
        .split_once('=')
        .context("expected Dn=FILE, e.g. D2000=table.csv")?;
    let block = match ecam_plc::Device::parse(block.trim()) {
        Ok(ecam_plc::Device::D(n)) => n,
        _ => bail!("`{block}` is not a D register (the DECAM block's first word, e.g. D2000)"),
    };
    let table = match ecam_core::io::read(std::path::Path::new(file.trim()))? {
        ecam_core::io::AnyTable::Points(file) => file.table,
        _ => bail!("a DECAM table is a point table: give a CSV or JSON of master,slave points"),
    };
    ecam_plc::decam::load_table(devices, block, &table)?;
    Ok(())
}
