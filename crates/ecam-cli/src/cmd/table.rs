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

use anyhow::bail;
use ecam_core::CamCurve;
use ecam_core::io::{self, AnyTable, Columns, TableFile};
use ecam_core::table::Summary;
use ecam_plot::cam_table;
use serde::Serialize;

use crate::cmd::table_peaks::{self, AtSpeed, MachineArgs, Peaks, Source};
use crate::generate::{self, GenCommand};
use crate::plot;

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
    // Refuse bad extensions before the (possibly slow) generation.
    if let Some(path) = &output.output {
        io::FileFormat::of(path)?;
    }
    if let Some(path) = &output.plot {
        plot::Format::of(path)?;
    }
    let generated = generate::run(&args.generator)?;
    let file = TableFile {
        table: generated.table,
        sync: generated.sync,
        generator: Some(generated.name.to_string()),
        kinematics: generated.kinematics,
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
        eprintln!("{key}: {value}");
    }
    if let Some(path) = &output.plot {
        let exact = generated.exact.as_ref();
        plot::draw_chart(cam_table::chart(&file, exact, generated.name), path)?;
    }
    Ok(())
}

/// What `ecam table show --json` prints.
#[derive(Serialize)]
struct ShowJson<'a> {
    file: String,
    /// Only for the kinds other than point tables, whose output predates it.
    #[serde(skip_serializing_if = "Option::is_none")]
    kind: Option<&'static str>,
    points: usize,
    master_first: i64,
    master_last: i64,
    slave_first: i64,
    slave_last: i64,
    sync: Option<(i64, i64)>,
    #[serde(flatten)]
    summary: &'a Summary,
    /// The design's peaks, from a file's derivative columns.
    #[serde(skip_serializing_if = "Option::is_none")]
    design: Option<Peaks>,
    /// The peaks at `--master-speed`: the design's when known, else the
    /// table's (`of` says which).
    #[serde(skip_serializing_if = "Option::is_none")]
    at_speed: Option<AtSpeed>,
}

fn peaks(summary: &Summary) -> Peaks {
    Peaks {
        peak_velocity: summary.peak_velocity,
        peak_acceleration: summary.peak_acceleration,
    }
}

/// The design's peaks from a file's derivative columns, when it has them.
fn design_peaks(file: &TableFile) -> Option<Peaks> {
    let known = file.kinematics.as_ref()?;
    let peak = |f: fn(&ecam_core::Kinematics) -> f64| {
        known.iter().map(f).fold(0.0_f64, |m, v| m.max(v.abs()))
    };
    Some(Peaks {
        peak_velocity: peak(|k| k.v),
        peak_acceleration: peak(|k| k.a),
    })
}

fn show(args: &ShowArgs) -> anyhow::Result<()> {
    let table = io::read(&args.file)?;
    let kind = table.kind();
    match table {
        AnyTable::Points(file) => show_points(args, &file),
        AnyTable::Uniform(table) => {
            let values = table.values().len();
            // Document 002: N values make N − 1 pieces over CamCounts.
            let spacing = table.cam_counts() as f64 / (values.saturating_sub(1)).max(1) as f64;
            let what = format!(
                "evenly spaced table, a value every {} counts",
                short(spacing)
            );
            show_curve(args, kind, &what, values, &table, Source::UniformPieces)
        }
        AnyTable::Profile(profile) => {
            let key_points = profile.segments().len().saturating_add(1);
            let what = "segment profile, key points joined by motion laws, evaluated exactly";
            show_curve(args, kind, what, key_points, &profile, Source::ProfileLaws)
        }
    }
}

/// `show` for an evenly spaced table or a segment profile: its summary is
/// measured on the curve itself, not on a sampled point table. `points` is
/// the number of values (key points) the file holds.
fn show_curve(
    args: &ShowArgs,
    kind: &'static str,
    what: &str,
    points: usize,
    curve: &(impl CamCurve + ecam_core::table::steps::Corners),
    source: Source,
) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    let summary = Summary::of(curve);
    let table = peaks(&summary);
    if args.json {
        let json = ShowJson {
            file: args.file.display().to_string(),
            kind: Some(kind),
            points,
            master_first: curve.master_first(),
            master_last: curve.master_last(),
            slave_first: curve.slave_first(),
            slave_last: curve.slave_last(),
            sync: None,
            summary: &summary,
            design: None,
            at_speed: args.machine.at_speed(&table, source),
        };
        writeln!(out, "{}", serde_json::to_string(&json)?)?;
        return Ok(());
    }
    writeln!(out, "file:              {}", args.file.display())?;
    writeln!(out, "kind:              {kind} ({what})")?;
    writeln!(out, "points:            {points}")?;
    write_summary(
        &mut out,
        &summary,
        (curve.master_first(), curve.master_last()),
        (curve.slave_first(), curve.slave_last()),
    )?;
    table_peaks::write(&mut out, None, (&table, source), None, &args.machine)?;
    writeln!(out, "continuity:        {}", summary.continuity)?;
    Ok(())
}

fn show_points(args: &ShowArgs, file: &TableFile) -> anyhow::Result<()> {
    // Written through a handle, not `println!`, so a closed pipe
    // (`ecam table show t.csv | head -1`) is an error, not a panic.
    let mut out = std::io::stdout().lock();
    let summary = Summary::of(&file.table);
    let table = peaks(&summary);
    let design = design_peaks(file);
    let points = file.table.points();
    let (first, last) = match (points.first(), points.last()) {
        (Some(f), Some(l)) => (*f, *l),
        _ => bail!("the table has no points"),
    };
    if args.json {
        let json = ShowJson {
            file: args.file.display().to_string(),
            kind: None,
            points: points.len(),
            master_first: first.master,
            master_last: last.master,
            slave_first: first.slave,
            slave_last: last.slave,
            sync: file.sync,
            summary: &summary,
            design,
            at_speed: match &design {
                Some(design) => args.machine.at_speed(design, Source::DesignColumns),
                None => args.machine.at_speed(&table, Source::SampledTable),
            },
        };
        writeln!(out, "{}", serde_json::to_string(&json)?)?;
        return Ok(());
    }
    writeln!(out, "file:              {}", args.file.display())?;
    if let Some(generator) = &file.generator {
        writeln!(out, "generator:         {generator}")?;
    }
    writeln!(out, "points:            {}", points.len())?;
    write_summary(
        &mut out,
        &summary,
        (first.master, last.master),
        (first.slave, last.slave),
    )?;
    let shortest = points
        .windows(2)
        .filter_map(|w| match w {
            [a, b] => b.master.checked_sub(a.master),
            _ => None,
        })
        .min();
    table_peaks::write(
        &mut out,
        design.as_ref().map(|d| (d, Source::DesignColumns)),
        (&table, Source::SampledTable),
        shortest,
        &args.machine,
    )?;
    writeln!(out, "continuity:        {}", summary.continuity)?;
    if let Some((lo, hi)) = file.sync {
        writeln!(out, "sync zone:         master {lo} .. {hi}")?;
    }
    Ok(())
}

/// The lines every table kind shares, from `sections` to `slave`.
fn write_summary(
    out: &mut impl Write,
    summary: &Summary,
    (master_first, master_last): (i64, i64),
    (slave_first, slave_last): (i64, i64),
) -> anyhow::Result<()> {
    writeln!(out, "sections:          {}", summary.sections)?;
    writeln!(
        out,
        "master:            {master_first} .. {master_last} (span {})",
        summary.master_span
    )?;
    writeln!(
        out,
        "slave:             {slave_first} .. {slave_last} (stroke {}, range {} .. {})",
        summary.stroke, summary.slave_min, summary.slave_max
    )?;
    Ok(())
}

use table_peaks::short;

fn plot_file(args: &PlotArgs) -> anyhow::Result<()> {
    plot::Format::of(&args.output)?;
    let chart = match io::read(&args.file)? {
        AnyTable::Points(mut file) => {
            if args.sync.is_some() {
                file.sync = args.sync;
            }
            let name = file
                .generator
                .clone()
                .unwrap_or_else(|| display_name(&args.file));
            cam_table::chart(&file, None, &name)
        }
        AnyTable::Uniform(table) => {
            cam_table::uniform_chart(&table, args.sync, &display_name(&args.file))
        }
        AnyTable::Profile(profile) => {
            cam_table::profile_chart(&profile, args.sync, &display_name(&args.file))
        }
    };
    let chart = match args.machine.master_speed {
        Some(master_hz) => {
            let unit = match (args.machine.units, args.machine.unit_per_pulse) {
                (Some(unit), Some(per)) => Some((unit.symbol(), per)),
                _ => None,
            };
            cam_table::at_speed(chart, cam_table::Machine { master_hz, unit })
        }
        None => chart,
    };
    plot::draw_chart(chart, &args.output)
}

fn display_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}
