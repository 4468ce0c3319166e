//! `ecam serve`: runs the PLC in real time behind Modbus TCP and HTTP.
//!
//! The first two lines on stdout are the bound addresses, `modbus ADDR` and
//! `http ADDR` (so `--modbus 127.0.0.1:0` can be used and the port read
//! back); with `--ethercat`, one JSON summary line follows at exit;
//! everything else goes to stderr. See `docs/modbus.md`.

use std::io::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use anyhow::Context as _;
use ecam_plc::Plc;
use ecam_plc::Wire;
use ecam_plc::sim::{self, Timing};
use ecam_serve::{
    Event, Journal, JournalError, LatchedImage, Notice, NoticeLevel, OnDamage, ServeInfo, Shared,
};
use tokio::net::TcpListener;

use crate::serve::assets;
use ecam_serve::ethercat;
use ecam_serve::net::{http, modbus};

/// Default Modbus TCP address (5020: the Modbus port 502 needs root).
pub const DEFAULT_MODBUS: &str = "127.0.0.1:5020";
/// Default HTTP address.
pub const DEFAULT_HTTP: &str = "127.0.0.1:8080";

/// Arguments of `ecam serve`.
#[derive(clap::Args)]
pub struct Args {
    /// Modbus TCP address to listen on (port 0 picks a free one).
    #[arg(long, value_name = "ADDR", default_value = DEFAULT_MODBUS)]
    pub modbus: String,
    /// HTTP address to listen on (API and designer page).
    #[arg(long, value_name = "ADDR", default_value = DEFAULT_HTTP)]
    pub http: String,
    /// Keep every value written from outside (except to special devices
    /// D/M8000-8511) and the latched devices' values in this directory,
    /// durably (created if missing); without it nothing survives a restart.
    #[arg(long, value_name = "DIR")]
    pub state: Option<PathBuf>,
    /// When the state directory's files are damaged, start from the last
    /// consistent state instead of refusing to: every snapshot record whose
    /// checksum matches and the journal up to its first damaged record.
    /// Says on stderr what was dropped and keeps the damaged files as
    /// *.damaged.
    #[arg(long, requires = "state")]
    pub recover_state: bool,
    /// Log every Modbus request and answer on stderr, like a Modbus
    /// monitor's communication window: client, transaction, unit, function,
    /// addresses, values or the exception (same as
    /// RUST_LOG=ecam::modbus::traffic=trace).
    #[arg(long)]
    pub trace_modbus: bool,
    /// Instruction-list program to run; without one the PLC runs an empty
    /// program (device memory, special relays and clocks only).
    #[arg(long, value_name = "FILE.il")]
    pub program: Option<PathBuf>,
    /// Scan period in microseconds.
    #[arg(long, value_name = "US", default_value_t = sim::DEFAULT_SCAN_US,
          value_parser = clap::value_parser!(u32).range(1..))]
    pub scan_us: u32,
    /// Hardware tick (pulse outputs, E-cam engine, counters) in microseconds.
    #[arg(long, value_name = "US", default_value_t = sim::DEFAULT_TICK_US,
          value_parser = clap::value_parser!(u32).range(1..))]
    pub tick_us: u32,
    /// Wire a pulse output to a counter input, e.g. Y1:X0.
    #[arg(long = "wire", value_name = "Yn:Xm")]
    pub wires: Vec<String>,
    /// Most connections each listener (Modbus, HTTP with its live views)
    /// keeps at once; at the cap the idlest makes room for the newcomer.
    #[arg(long, value_name = "N", default_value_t = 64,
          value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub max_connections: u32,
    /// Seconds a Modbus connection may stay without a request before it is
    /// closed; also caps every other client deadline (the rest of a
    /// half-sent request, a request body, a live view's answer to pings).
    #[arg(long, value_name = "S", default_value_t = 60,
          value_parser = clap::value_parser!(u32).range(1..=86_400))]
    pub idle_timeout: u32,
    /// Seconds a design request (table generators, laws, key points) may
    /// compute before it is answered 503 and its work stopped.
    #[arg(long, value_name = "S", default_value_t = 30,
          value_parser = clap::value_parser!(u32).range(1..=3600))]
    pub design_timeout: u32,
    /// Another name the HTTP face answers to (the `Host` header), e.g. the
    /// machine's name when it listens beyond loopback; repeatable. The bound
    /// address, localhost and 127.0.0.1 are always accepted.
    #[arg(long = "http-name", value_name = "NAME")]
    pub http_names: Vec<String>,
    /// A file holding a token that HTTP writes must present
    /// (`Authorization: Bearer TOKEN`): use it when listening beyond loopback.
    #[arg(long, value_name = "FILE")]
    pub token_file: Option<PathBuf>,
    /// Put the pulse outputs on CiA 402 drives over EtherCAT, as the
    /// configuration file maps them (see docs/ethercat.md); the bus cycle
    /// then paces the PLC instead of the wall-clock scan loop.
    #[arg(long, value_name = "CONFIG.toml")]
    pub ethercat: Option<PathBuf>,
    /// With --ethercat: N emulated drives in this process instead of the
    /// configuration's interface.
    #[arg(long, value_name = "N", requires = "ethercat",
          value_parser = clap::value_parser!(u16).range(1..=64))]
    pub emulated: Option<u16>,
}

/// Runs `ecam serve` until Ctrl-C or SIGTERM.
///
/// # Errors
/// An unreadable program, a bad wire, an unusable state directory, or an
/// address that cannot be bound.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (program, program_name) = match &args.program {
        Some(path) => {
            let file = path.display().to_string();
            let source =
                std::fs::read_to_string(path).with_context(|| format!("cannot read {file}"))?;
            (ecam_plc::Program::parse(&source, &file)?, Some(file))
        }
        None => (ecam_plc::Program::parse("", "(no program)")?, None),
    };
    let mut plc = Plc::new(program)?;
    for wire in &args.wires {
        plc.hardware_mut()
            .add_wire(Wire::parse(wire).context("--wire")?);
    }
    let (journal, restored) = match &args.state {
        Some(dir) => {
            let on_damage = if args.recover_state {
                OnDamage::Recover
            } else {
                OnDamage::Refuse
            };
            let (journal, recovery) = match Journal::open_with(dir, on_damage) {
                Ok(opened) => opened,
                Err(err @ JournalError::Corrupt { .. }) => anyhow::bail!(
                    "state directory {}: {err}\n\
                     fix the file, or start with --recover-state to restore the last \
                     consistent state (what is dropped is listed, the damaged files kept)",
                    dir.display()
                ),
                Err(err) => {
                    return Err(err).with_context(|| format!("state directory {}", dir.display()));
                }
            };
            log_notices(ecam_serve::open_notices(dir, &recovery, &journal));
            journal.restore_into(plc.devices_mut());
            let restored = journal.persisted().clone();
            (Some(journal), Some((dir.clone(), recovery, restored)))
        }
        None => {
            tracing::warn!(target: LOG, "no --state DIR: writes are not kept across restarts");
            (None, None)
        }
    };
    let token = match &args.token_file {
        Some(path) => Some(
            ecam_serve::read_token(path)
                .with_context(|| format!("--token-file {}", path.display()))?,
        ),
        None => None,
    };
    let timing = Timing {
        scan_us: args.scan_us,
        tick_us: args.tick_us,
    };
    let bus = match &args.ethercat {
        Some(config) => Some(ethercat::bring_up(config, args.emulated, args.scan_us)?),
        None => None,
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .context("cannot start the async runtime")?;
    runtime.block_on(async move {
        let modbus_listener = TcpListener::bind(&args.modbus)
            .await
            .with_context(|| format!("--modbus {}: cannot listen", args.modbus))?;
        let http_listener = TcpListener::bind(&args.http)
            .await
            .with_context(|| format!("--http {}: cannot listen", args.http))?;
        let info = ServeInfo {
            program: program_name,
            timing,
            modbus: modbus_listener.local_addr()?,
            http: http_listener.local_addr()?,
            state_dir: args.state.clone(),
            limits: ecam_serve::Limits::new(
                args.max_connections as usize,
                Duration::from_secs(u64::from(args.idle_timeout)),
                Duration::from_secs(u64::from(args.design_timeout)),
            ),
        };
        {
            let mut stdout = std::io::stdout().lock();
            // The address lines are the interface for scripts and tests.
            writeln!(stdout, "modbus {}", info.modbus)?;
            writeln!(stdout, "http {}", info.http)?;
            stdout.flush()?;
        }
        tracing::info!(target: LOG, "designer page at http://{}/", info.http);
        let shared = Arc::new(Shared::new(plc, journal, info, report));
        // The first scan runs before any client is served, so whatever it
        // changes of the restored values is the program's (or hardware's) doing.
        ecam_serve::scan_period(&shared);
        if let Some((dir, recovery, restored)) = &restored {
            log_notices(ecam_serve::restore_notices(
                &shared, dir, recovery, restored,
            ));
        }
        let stop = Arc::new(AtomicBool::new(false));
        let scan_loop = match bus {
            // The bus cycle paces the PLC.
            Some(bus) => Pacer::Bus(bus.spawn(Arc::clone(&shared), Arc::clone(&stop))?),
            None => {
                let (shared, stop) = (Arc::clone(&shared), Arc::clone(&stop));
                Pacer::Clock(
                    std::thread::Builder::new()
                        .name("plc-scan".into())
                        .spawn(move || ecam_serve::scan_loop(&shared, &stop))
                        .context("cannot start the scan loop")?,
                )
            }
        };
        let saver = match &restored {
            Some(_) => {
                let (shared, stop) = (Arc::clone(&shared), Arc::clone(&stop));
                let saver = std::thread::Builder::new()
                    .name("latched-save".into())
                    .spawn(move || ecam_serve::save_latched_periodically(&shared, &stop))
                    .context("cannot start the latched-value saver")?;
                Some(saver)
            }
            None => None,
        };
        let access = ecam_serve::Access::new(shared.info.http, &args.http_names, token.clone());
        let router = http::router(Arc::clone(&shared), access, assets::PAGE);
        let served: anyhow::Result<()> = tokio::select! {
            () = modbus::serve(modbus_listener, Arc::clone(&shared)) => Ok(()),
            () = http::serve(http_listener, router, Arc::clone(&shared)) => Ok(()),
            () = crate::signals::shutdown_signal() => Ok(()),
        };
        stop.store(true, Ordering::Relaxed);
        match scan_loop {
            Pacer::Clock(thread) => {
                let _ = thread.join();
            }
            Pacer::Bus(thread) => {
                // The drives are disabled; the summary is for scripts.
                if let Ok(summary) = thread.join() {
                    println!("{summary}");
                }
            }
        }
        if let Some(saver) = saver {
            let _ = saver.join();
            // The scan loop has stopped: this image is the PLC's last state.
            match shared.save_latched(&mut LatchedImage::new()) {
                Ok(saved) => tracing::info!(target: LOG, "stopped; {saved} latched values saved"),
                Err(err) => {
                    tracing::error!(target: LOG, "stopped; cannot save latched values: {err}")
                }
            }
        }
        served
    })
}

/// What paces the PLC: the wall clock, or the fieldbus cycle (whose
/// thread ends with the bus summary line).
enum Pacer {
    Clock(std::thread::JoinHandle<()>),
    Bus(std::thread::JoinHandle<serde_json::Value>),
}

/// The tracing target of the server's own messages (start, state, stop).
const LOG: &str = "ecam::serve";

/// Logs what the server's operator should hear.
fn report(event: Event) {
    match event {
        Event::OperationError(text) => tracing::warn!(target: "ecam::plc", "{text}"),
        Event::WriteRefused(err) => {
            tracing::error!(target: "ecam::journal", "write refused: {err}")
        }
        Event::CompactionFailed(err) => {
            tracing::error!(target: "ecam::journal", "journal compaction failed (will retry): {err}");
        }
        Event::LatchedSaveFailing(err) => {
            tracing::error!(target: "ecam::journal", "cannot save latched values (will retry): {err}");
        }
        Event::LatchedSavesResumed => {
            tracing::info!(target: "ecam::journal", "latched values saved again")
        }
        Event::ProgramStopped(text) => tracing::error!(target: "ecam::plc", "{text}"),
    }
}

/// Logs the server's notices about its state directory.
fn log_notices(notices: Vec<Notice>) {
    for Notice { level, text } in notices {
        match level {
            NoticeLevel::Info => tracing::info!(target: LOG, "{text}"),
            NoticeLevel::Warn => tracing::warn!(target: LOG, "{text}"),
            NoticeLevel::Error => tracing::error!(target: LOG, "{text}"),
        }
    }
}
