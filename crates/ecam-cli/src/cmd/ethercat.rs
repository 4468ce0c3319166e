//! `ecam ethercat`: cams on CiA 402 drives over EtherCAT.
//!
//! - `ecam ethercat run CONFIG [--emulated N] [--recover]`: brings the
//!   segment of the configuration file to OP and runs its cams in
//!   ecam-ethercat's cycle driver; this thread prints status lines and
//!   faults from the driver's published image, and at the end one JSON
//!   summary line. Ctrl-C or SIGTERM end the run as `--cycles` does.
//! - `ecam ethercat emulate IFACE`: answers EtherCAT frames on an
//!   interface as a line of emulated CSP drives.
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
use ecam_ethercat::config::LineConfig;
use ecam_ethercat::driver::{self, DriverConfig};
use ecam_ethercat::emulation::{DriveBehaviour, EmulatedSegment, WireEmulation};
use ecam_ethercat::line::{CamDrive, CamLine};
use ecam_ethercat::monitor::LineMonitor;
use ecam_ethercat::summary::{status_line, summary_json};
use ecam_ethercat::{Segment, Transport};

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
    /// When the line faults, reset it once frames flow again (drives that
    /// left OP are brought back, faults reset) and start it again from
    /// where the drives stand. Without it a fault holds the line.
    #[arg(long)]
    pub recover: bool,
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

fn run_line(args: RunArgs) -> anyhow::Result<()> {
    let (config, tables) = load(&args.config)?;
    let (transport, emulation) = Transport::chosen(args.emulated, config.interface.as_deref())
        .with_context(|| args.config.display().to_string())?;
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
    let timing = config.timing();
    let segment = Segment::bring_up_with(transport, timing.segment(), config.setups())?;
    println!(
        "segment: {} drives in OP, SYNC0 every {} µs",
        segment.len(),
        config.cycle_us
    );
    for (position, info) in segment.drive_info().iter().enumerate() {
        println!("  drive {position}: {info}");
    }
    let drives = segment.len();
    let mut line = CamLine::new(segment, axes, timing.max_lost_cycles(), timing.stop())?;
    line.virtual_speed = config.master_speed;
    let monitor = Arc::new(LineMonitor::new(drives));
    // From here on a signal stops the line (decelerating, then disabling);
    // during bring-up it may end the process: nothing is enabled yet.
    let on_signal = Arc::clone(&monitor);
    crate::signals::on_signal(move || on_signal.request_stop())?;
    let done = Arc::new(AtomicBool::new(false));
    let watcher = {
        let (monitor, done) = (Arc::clone(&monitor), Arc::clone(&done));
        let every = Duration::from_millis(args.status_ms);
        std::thread::Builder::new()
            .name("ecam-status".into())
            .spawn(move || watch(&monitor, every, &done))
            .context("cannot start the status printer")?
    };
    // The cams' tables stay on this thread: it becomes the cycle.
    let summary = driver::run_here(
        line,
        DriverConfig {
            rt: config.rt(),
            cycles: args.cycles,
            enable_at_start: true,
            recover: args.recover,
            stop: timing.stop(),
            emulation,
        },
        &monitor,
        |_| {},
    );
    done.store(true, Ordering::Release);
    let _ = watcher.join();
    println!("{}", status_line(&monitor.snapshot(), Duration::ZERO));
    if let Some(e) = &summary.error {
        bail!("the cycle stopped: {e}");
    }
    println!("{}", summary_json(&summary, drives, config.cycle_us));
    Ok(())
}

/// Prints faults as they appear and a status line every `every` until
/// `done`.
fn watch(monitor: &LineMonitor, every: Duration, done: &AtomicBool) {
    let started = Instant::now();
    let mut last_status = started;
    let mut seen_faults = 0;
    let mut told = false;
    loop {
        std::thread::sleep(Duration::from_millis(20));
        if let (false, Some(scheduling)) = (told, monitor.scheduling()) {
            println!("cycle: {scheduling}");
            told = true;
        }
        let snapshot = monitor.snapshot();
        if snapshot.fault_events > seen_faults {
            let new = usize::try_from(snapshot.fault_events - seen_faults).unwrap_or(usize::MAX);
            let faults = &snapshot.faults;
            for fault in &faults[faults.len().saturating_sub(new)..] {
                println!(
                    "fault at cycle {}: {fault}; line stopped",
                    snapshot.counters.cycles
                );
            }
            seen_faults = snapshot.fault_events;
        }
        if !every.is_zero() && last_status.elapsed() >= every {
            last_status = Instant::now();
            println!("{}", status_line(&snapshot, started.elapsed()));
        }
        if done.load(Ordering::Acquire) {
            return;
        }
    }
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
