//! `ecam table`: generate, summarise and plot cam tables.
//!
//! - `ecam table gen GENERATOR [params] [-o FILE.csv|.json] [--plot FILE.svg|.png]`
//! - `ecam table show FILE`
//! - `ecam table plot FILE -o OUT.svg|.png`
//!
//! `show` and `plot` take every table kind `ecam_core` stores: point tables,
//! evenly spaced tables and segment profiles (the last two in its JSON).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;
use ecam_core::io::{self, AnyTable, Columns, TableFile};
use ecam_design::{Machine, TableReport, Unit};
use ecam_plot::cam_table;

use crate::generate::{self, GenCommand};

/// Subcommands of `ecam table`.
#[derive(clap::Subcommand, Debug)]
pub enum Command {
    /// Generate a table (the PLC's ECAMTBX generators, key points, or a function of the master).
    Gen(GenArgs),
    /// Summarise a table file: sections, stroke, peak ratios, continuity.
    Show(ShowArgs),
    /// Plot a table file: displacement, velocity, acceleration, jerk.
    Plot(PlotArgs),
}

/// Arguments of `ecam table gen`.
#[derive(clap::Args, Debug)]
pub struct GenArgs {
    /// Which generator, with its parameters.
    #[command(subcommand)]
    pub generator: GenCommand,
}

/// Arguments of `ecam table show`.
#[derive(clap::Args, Debug)]
pub struct ShowArgs {
    /// Table file (CSV or JSON).
    pub file: PathBuf,
    /// Print the summary as one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// The machine, for peaks in physical units.
    #[command(flatten)]
    pub machine: MachineArgs,
    /// Check the cam against a drive (TOML: `[mechanics]`, `[limits]`; see
    /// docs/design.md): motor speed, torque and RMS torque at
    /// --master-speed, and the fastest machine speed the drive allows.
    #[arg(long, value_name = "FILE.toml")]
    pub drive: Option<PathBuf>,
}

/// Arguments of `ecam table plot`.
#[derive(clap::Args, Debug)]
pub struct PlotArgs {
    /// Table file (CSV or JSON).
    pub file: PathBuf,
    /// The picture to write (SVG or PNG by extension).
    #[arg(short = 'o', long = "output", value_name = "OUT.svg|png", value_parser = crate::paths::picture)]
    pub output: PathBuf,
    /// Shade this master range as the synchronised zone (`LOW:HIGH`);
    /// a JSON table's own `sync` is used when absent.
    #[arg(long, value_name = "LOW:HIGH", value_parser = parse_range)]
    pub sync: Option<(i64, i64)>,
    /// The machine, for panels in physical units (Hz, Hz/s; mm/s, mm/s²).
    #[command(flatten)]
    pub machine: MachineArgs,
}

fn parse_range(text: &str) -> Result<(i64, i64), String> {
    let (lo, hi) = text
        .split_once(':')
        .ok_or_else(|| format!("expected LOW:HIGH, got {text:?}"))?;
    let lo: i64 = lo.trim().parse().map_err(|e| format!("LOW {lo:?}: {e}"))?;
    let hi: i64 = hi.trim().parse().map_err(|e| format!("HIGH {hi:?}: {e}"))?;
    if hi < lo {
        return Err(format!("LOW {lo} is above HIGH {hi}"));
    }
    Ok((lo, hi))
}

/// Runs `ecam table`.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Gen(args) => generate_table(args),
        Command::Show(args) => show(&args),
        Command::Plot(args) => plot_file(&args),
    }
}

fn generate_table(args: GenArgs) -> anyhow::Result<()> {
    let output = args.generator.output().clone();
    let generated = generate::run(&args.generator)?;
    tracing::debug!(
        "{}: {} points",
        generated.name,
        generated.table.points().len()
    );
    let file = TableFile {
        table: generated.table,
        sync: generated.sync,
        generator: Some(generated.name.to_string()),
        kinematics: generated.kinematics,
        segments: generated.segments.map(Box::new),
    };
    let columns = if output.minimal {
        Columns::Minimal
    } else {
        Columns::Full
    };
    match output.output.as_deref() {
        Some(path) => io::write(&file, path, columns)?,
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(file.to_csv(columns).as_bytes())?;
            out.flush()?;
        }
    }
    for (key, value) in &generated.outputs {
        tracing::info!("{key}: {value}");
    }
    if let Some(path) = &output.plot {
        let chart = match &file.segments {
            Some(cam) => cam_table::segment_cam_chart(cam, file.sync, generated.name),
            None => cam_table::chart(&file, generated.exact.as_ref(), generated.name),
        };
        ecam_plot::draw_chart(&chart, path)?;
    }
    Ok(())
}

fn show(args: &ShowArgs) -> anyhow::Result<()> {
    let table = io::read(&args.file)?;
    tracing::debug!("{}: a {} table", args.file.display(), table.kind());
    let drive = match &args.drive {
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .with_context(|| format!("cannot read drive file {}", path.display()))?;
            let report = ecam_design::check_table(&table, &text, args.machine.master_speed)
                .with_context(|| format!("drive file {}", path.display()))?;
            Some(report)
        }
        None => None,
    };
    let report = TableReport::of(&args.file.display().to_string(), &table)
        .at(args.machine.into())
        .with_drive(drive);
    // A handle, not `println!`: a closed pipe is an error, not a panic.
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string(&report)?)?;
    } else {
        report.write_text(&mut out)?;
    }
    Ok(())
}

/// `--master-speed`, `--units`, `--unit-per-pulse`: the machine the table
/// runs on, for peaks in physical units.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct MachineArgs {
    /// Master speed in counts per second (the master encoder's frequency,
    /// Hz): adds the slave's peak speed in Hz (pulses/s) and acceleration in
    /// Hz/s.
    #[arg(long, value_name = "COUNTS_PER_S", value_parser = positive)]
    pub master_speed: Option<f64>,
    /// The slave's length unit, for speeds in mm/s or deg/s (needs
    /// --unit-per-pulse and --master-speed).
    #[arg(long, value_name = "UNIT", value_parser = unit(),
        requires = "unit_per_pulse", requires = "master_speed")]
    pub units: Option<Unit>,
    /// Slave units per slave pulse: 0.01 for 100 pulses per mm, 0.036 for
    /// 10000 pulses per turn in degrees (needs --units).
    #[arg(long, value_name = "UNITS", value_parser = positive, requires = "units")]
    pub unit_per_pulse: Option<f64>,
}

impl From<MachineArgs> for Machine {
    fn from(m: MachineArgs) -> Self {
        Self {
            master_speed: m.master_speed,
            unit: m.units.zip(m.unit_per_pulse),
        }
    }
}

/// `--units`: one of [`Unit::NAMES`] (completions offer them).
fn unit() -> impl clap::builder::TypedValueParser<Value = Unit> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(Unit::NAMES)
        .map(|name| Unit::from_name(&name).unwrap_or(Unit::Mm))
}

fn positive(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        Ok(_) => Err(format!("{text} must be a number above 0")),
        Err(e) => Err(format!("{text:?} is not a number: {e}")),
    }
}

fn plot_file(args: &PlotArgs) -> anyhow::Result<()> {
    let table = io::read(&args.file)?;
    tracing::debug!("{}: a {} table", args.file.display(), table.kind());
    let chart = match table {
        AnyTable::Points(mut file) => {
            if args.sync.is_some() {
                file.sync = args.sync;
            }
            let name = file
                .generator
                .clone()
                .unwrap_or_else(|| display_name(&args.file));
            match &file.segments {
                Some(cam) => cam_table::segment_cam_chart(cam, file.sync, &name),
                None => cam_table::chart(&file, None, &name),
            }
        }
        AnyTable::Uniform(table) => {
            cam_table::uniform_chart(&table, args.sync, &display_name(&args.file))
        }
        AnyTable::Profile(profile) => {
            cam_table::profile_chart(&profile, args.sync, &display_name(&args.file))
        }
    };
    let machine = Machine::from(args.machine);
    let chart = match machine.master_speed {
        Some(master_hz) => {
            let unit = machine.unit.map(|(unit, per)| (unit.symbol(), per));
            cam_table::at_speed(chart, cam_table::Machine { master_hz, unit })
        }
        None => chart,
    };
    Ok(ecam_plot::draw_chart(&chart, &args.output)?)
}

fn display_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}
