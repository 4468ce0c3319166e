//! `ecam ethercat`: cams on CiA 402 drives over EtherCAT.
//!
//! - `ecam ethercat run CONFIG [--emulated N]`: brings the segment of the
//!   configuration file to OP, enables the drives, runs the cams in the
//!   real-time cycle and prints status; at the end one JSON summary line
//!   (drives, cycles, faults, lateness histogram). Ctrl-C or SIGTERM ends
//!   the run the same way: the drives are disabled first.
//! - `ecam ethercat emulate IFACE`: answers EtherCAT frames on an
//!   interface as a line of emulated CSP drives (to try the raw-socket
//!   path without hardware, e.g. on one end of a veth pair).
//!
//! The configuration file and the behaviour are described in
//! docs/ethercat.md; the work is ecam-ethercat's.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use anyhow::{Context, bail};
use ecam_core::CamCurve;
use ecam_engine::CamAxis;
use ecam_engine::drive::AxisDrive;
use ecam_ethercat::config::LineConfig;
use ecam_ethercat::emulation::{DriveBehaviour, EmulatedSegment, WireEmulation};
use ecam_ethercat::line::{CamDrive, CamLine, LineState};
use ecam_ethercat::rt::{BUCKETS_US, CycleClock, LatenessHistogram, configure_current_thread};
use ecam_ethercat::{Segment, SegmentConfig, Transport};
use serde_json::json;

/// `ecam ethercat` subcommands.
#[derive(clap::Subcommand, Debug)]
pub enum Command {
    /// Run the cams of a configuration file on its segment.
    Run(RunArgs),
    /// Emulate a line of CSP drives on a network interface.
    Emulate(EmulateArgs),
}

/// Arguments of `ecam ethercat run`.
#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Configuration file (TOML; see docs/ethercat.md).
    pub config: PathBuf,
    /// Run against N emulated drives in this process instead of the
    /// configuration's interface.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=64))]
    pub emulated: Option<u16>,
    /// Stop after this many cycles (default: run until interrupted).
    #[arg(long, value_name = "N")]
    pub cycles: Option<u64>,
    /// Print a status line this often, ms (0: only at the end).
    #[arg(long, value_name = "MS", default_value_t = 1000)]
    pub status_ms: u64,
}

/// Arguments of `ecam ethercat emulate`.
#[derive(clap::Args, Debug)]
pub struct EmulateArgs {
    /// Network interface to answer on.
    pub interface: String,
    /// Number of drives in the line.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u16).range(1..=64))]
    pub drives: u16,
    /// Cycles each drive lags its target position.
    #[arg(long, default_value_t = 2)]
    pub lag: usize,
}

/// Runs `ecam ethercat`.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Run(args) => run_line(args),
        Command::Emulate(args) => emulate(args),
    }
}

fn load(path: &Path) -> anyhow::Result<(LineConfig, Vec<Box<dyn CamCurve>>)> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let config = LineConfig::parse(&text).with_context(|| format!("{}", path.display()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    let tables = config
        .axes
        .iter()
        .map(|a| {
            ecam_design::load_table(&a.table, base)
                .with_context(|| format!("{}: [axis.table] of drive {}", path.display(), a.drive))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    Ok((config, tables))
}

/// The frames' way: `emulated` drives in this process, or the
/// configuration's interface; the emulated segment is handed back too, for
/// fault injection.
///
/// # Errors
/// Neither is given.
pub(crate) fn open_transport(
    emulated: Option<u16>,
    interface: Option<&str>,
    config: &Path,
) -> anyhow::Result<(Transport, Option<Arc<Mutex<EmulatedSegment>>>)> {
    match (emulated, interface) {
        (Some(n), _) => {
            let segment = Arc::new(Mutex::new(EmulatedSegment::new(
                usize::from(n),
                DriveBehaviour::default(),
            )));
            Ok((Transport::Emulated(Arc::clone(&segment)), Some(segment)))
        }
        (None, Some(interface)) => Ok((Transport::Interface(interface.to_string()), None)),
        (None, None) => bail!(
            "{}: no interface; set interface = \"...\" or pass --emulated N",
            config.display()
        ),
    }
}

/// The lateness part of a summary line: mean, worst, overruns and the
/// histogram as `[upper bound µs (null: open), count]` pairs.
pub(crate) fn lateness_json(lateness: &LatenessHistogram) -> serde_json::Value {
    let histogram: Vec<serde_json::Value> = lateness
        .counts
        .iter()
        .enumerate()
        .map(|(i, n)| json!([BUCKETS_US.get(i), n]))
        .collect();
    json!({
        "mean_us": lateness.mean().as_secs_f64() * 1e6,
        "max_us": lateness.max.as_secs_f64() * 1e6,
        "overruns": lateness.overruns,
        "histogram_us": histogram,
    })
}

/// A flag that Ctrl-C or SIGTERM sets, so a cycle loop can leave the
/// drives disabled before the process ends.
pub(crate) fn stop_on_signal() -> anyhow::Result<Arc<AtomicBool>> {
    let flag = Arc::new(AtomicBool::new(false));
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .context("cannot start the signal watcher")?;
    let set = Arc::clone(&flag);
    std::thread::Builder::new()
        .name("ecam-signals".into())
        .spawn(move || {
            runtime.block_on(crate::cmd::serve::shutdown_signal());
            set.store(true, Ordering::Relaxed);
        })
        .context("cannot start the signal watcher")?;
    Ok(flag)
}

fn run_line(args: RunArgs) -> anyhow::Result<()> {
    let (config, tables) = load(&args.config)?;
    let (transport, _) = open_transport(args.emulated, config.interface.as_deref(), &args.config)?;
    let mut axes = Vec::with_capacity(tables.len());
    for (spec, table) in config.axes.iter().zip(tables) {
        let axis = CamAxis::new(table, spec.axis_config())
            .with_context(|| format!("cam of drive {}", spec.drive))?;
        axes.push(CamDrive {
            axis,
            drive: spec.drive,
            master: spec.master(),
        });
    }
    let segment = Segment::bring_up(
        transport,
        SegmentConfig {
            cycle: config.cycle(),
            // The frame thread runs just above the cycle that waits on it.
            link_fifo_priority: config.fifo_priority.map(|p| p.saturating_add(1).min(99)),
            ..SegmentConfig::default()
        },
    )?;
    println!(
        "segment: {} drives in OP, SYNC0 every {} µs",
        segment.len(),
        config.cycle_us
    );
    for position in 0..segment.len() {
        println!(
            "  drive {position}: {}",
            segment.drive_name(position).unwrap_or_default()
        );
    }
    let mut line = CamLine::new(segment, axes)?;
    line.virtual_speed = config.master_speed;
    // From here on a signal must not end the process with drives enabled
    // (during bring-up it may: nothing is enabled yet).
    let interrupted = stop_on_signal()?;
    line.start()?;
    let setup = configure_current_thread(&config.rt());
    println!("cycle: {setup}");

    let mut lateness = LatenessHistogram::default();
    let mut clock = CycleClock::start(config.cycle()).context("monotonic clock")?;
    let status_every = Duration::from_millis(args.status_ms);
    let started = Instant::now();
    let mut last_status = started;
    let mut faults = Vec::new();
    let mut wkc_errors = 0u64;
    let mut cycles = 0u64;
    while args.cycles.is_none_or(|n| cycles < n) && !interrupted.load(Ordering::Relaxed) {
        clock.wait(&mut lateness).context("clock_nanosleep")?;
        let report = line.cycle()?;
        cycles += 1;
        if report.bus.working_counter_error() {
            wkc_errors += 1;
        }
        for fault in &report.new_faults {
            println!("fault at cycle {cycles}: {fault}; line stopped");
            faults.push(fault.to_string());
        }
        if !status_every.is_zero() && last_status.elapsed() >= status_every {
            last_status = Instant::now();
            println!("{}", status_line(&line, started.elapsed()));
        }
    }
    println!("{}", status_line(&line, started.elapsed()));
    // Leave the drives disabled, and make sure they hear it.
    line.stop();
    for _ in 0..5 {
        clock
            .wait(&mut LatenessHistogram::default())
            .context("clock_nanosleep")?;
        line.cycle()?;
    }
    let summary = json!({
        "drives": line.segment().len(),
        "cycles": cycles,
        "cycle_us": config.cycle_us,
        "virtual_master": line.virtual_master(),
        "state": line.state().name(),
        "faults": faults,
        "working_counter_errors": wkc_errors,
        "actual": line.segment().drives().iter().map(|d| d.actual()).collect::<Vec<_>>(),
        "scheduling": setup.to_string(),
        "lateness": lateness_json(&lateness),
    });
    println!("{summary}");
    Ok(())
}

fn status_line<C: CamCurve>(line: &CamLine<C>, t: Duration) -> String {
    let mut s = format!(
        "t={:.3}s master={} {}",
        t.as_secs_f64(),
        line.virtual_master(),
        match line.state() {
            LineState::Running => "running",
            LineState::Enabling => "enabling",
            LineState::Stopped => "stopped",
            LineState::Faulted => "FAULTED",
        }
    );
    for (i, d) in line.segment().drives().iter().enumerate() {
        let status = d.status();
        s.push_str(&format!(
            " | d{i} {} actual={} ferr={}",
            d.state(),
            status.actual,
            status.following_error
        ));
        if let Some(fault) = status.fault {
            s.push_str(&format!(" ({fault})"));
        }
    }
    s
}

fn emulate(args: EmulateArgs) -> anyhow::Result<()> {
    let segment = Arc::new(Mutex::new(EmulatedSegment::new(
        usize::from(args.drives),
        DriveBehaviour {
            lag_cycles: args.lag,
            ..DriveBehaviour::default()
        },
    )));
    let _wire =
        WireEmulation::spawn(&args.interface, None, Arc::clone(&segment)).with_context(|| {
            format!(
                "cannot answer on {} (needs root or CAP_NET_RAW)",
                args.interface
            )
        })?;
    println!(
        "emulating {} CSP drives on {} (Ctrl-C to stop)",
        args.drives, args.interface
    );
    loop {
        std::thread::sleep(Duration::from_secs(1));
    }
}
