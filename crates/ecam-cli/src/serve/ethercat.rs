//! `ecam serve --ethercat CONFIG`: the PLC's pulse outputs on CiA 402
//! drives. ecam-ethercat's cycle driver runs the drives; at the end of
//! every cycle whose frame came back it wakes the PLC's thread, which runs
//! exactly one cycle time of scans (ecam-serve's `scan_on_bus_ticks`) and
//! publishes the pulse totals the drives follow next. The cycle shares no
//! lock with the PLC, Modbus or HTTP: its status goes out through the
//! driver's published image, which [`Source`] turns into ecam-serve's
//! [`BusSnapshot`] when a client asks.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use anyhow::{Context as _, bail};
use ecam_ethercat::Segment;
use ecam_ethercat::cia402::error_code_text;
use ecam_ethercat::config::FollowConfig;
use ecam_ethercat::driver::{self, DriverConfig, Following, PulseTotals};
use ecam_ethercat::emulation::EmulatedSegment;
use ecam_ethercat::follow::FollowLine;
use ecam_ethercat::monitor::{LineCommand, LineMonitor};
use ecam_ethercat::summary::summary_json;
use ecam_ethercat::supervisor::{LineState, al_state_code};
use ecam_plc::Device;
use ecam_serve::{
    BusCommand, BusFace, BusLineState, BusSnapshot, BusSource, BusTicks, DriveView, Shared,
};
use serde_json::Value;

/// The tracing target of the bus cycle's messages.
const LOG: &str = "ecam::ethercat";

/// A segment brought up for the server, not yet cycling.
pub struct Bus {
    config: FollowConfig,
    line: FollowLine,
    emulation: Option<Arc<Mutex<EmulatedSegment>>>,
    transport: String,
    relays: [Option<u16>; 2],
}

fn relay(name: Option<&str>, key: &str) -> anyhow::Result<Option<u16>> {
    let Some(name) = name else { return Ok(None) };
    match Device::parse(name) {
        Ok(Device::M(n)) if n < 8000 => Ok(Some(n)),
        _ => bail!("{key} = \"{name}\": name an M relay below M8000 (e.g. \"M100\")"),
    }
}

/// Reads the configuration, checks it against the PLC's timing and brings
/// the segment to OP.
///
/// # Errors
/// An unreadable or invalid file, a cycle that is not a whole number of
/// scan periods, no interface, or a failed bring-up.
pub fn bring_up(path: &Path, emulated: Option<u16>, scan_us: u32) -> anyhow::Result<Bus> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let config = FollowConfig::parse(&text).with_context(|| format!("{}", path.display()))?;
    let file = path.display().to_string();
    if config.cycle_us % scan_us != 0 {
        bail!(
            "{file}: cycle_us = {} is not a whole number of scan periods (--scan-us {scan_us}): \
             each bus cycle runs the PLC for exactly one cycle time",
            config.cycle_us
        );
    }
    let relays = [
        relay(config.fault_relay.as_deref(), "fault_relay").context(file.clone())?,
        relay(config.running_relay.as_deref(), "running_relay").context(file.clone())?,
    ];
    let followers = config.followers().context(file.clone())?;
    let (transport, emulation) =
        crate::cmd::ethercat::transport(emulated, config.interface.as_deref(), path)?;
    let transport_name = transport.describe();
    let timing = config.timing();
    let segment = Segment::bring_up_with(transport, timing.segment(), config.setups())?;
    let line = FollowLine::new(segment, followers, timing.max_lost_cycles(), timing.stop())
        .context(file)?;
    tracing::info!(
        target: LOG,
        "{} drives in OP on {transport_name}, SYNC0 every {} µs",
        line.segment().len(),
        config.cycle_us
    );
    for f in line.followers() {
        tracing::info!(
            target: LOG,
            "  drive {} ({}) follows Y{} at {}/{} counts per pulse",
            f.drive,
            line.segment().drive_name(f.drive).unwrap_or_default(),
            f.output,
            f.scale.num(),
            f.scale.den()
        );
    }
    Ok(Bus {
        config,
        line,
        emulation,
        transport: transport_name,
        relays,
    })
}

impl Bus {
    /// Starts the cycle driver and the PLC thread it paces; the returned
    /// thread ends with the summary line once `stop` is set and the drives
    /// have been stopped and disabled.
    ///
    /// # Errors
    /// A thread could not be started.
    pub fn spawn(
        self,
        shared: Arc<Shared>,
        stop: Arc<AtomicBool>,
    ) -> anyhow::Result<JoinHandle<Value>> {
        let drives = self.line.segment().len();
        let monitor = Arc::new(LineMonitor::new(drives));
        let source = Source {
            monitor: Arc::clone(&monitor),
            transport: self.transport.clone(),
            cycle_us: self.config.cycle_us,
            max_lost: self.line.supervisor().max_lost_cycles(),
            names: (0..drives)
                .map(|p| self.line.segment().drive_name(p).unwrap_or_default())
                .collect(),
            outputs: (0..drives).map(|p| self.line.output_of(p)).collect(),
        };
        // Set before any client is served, so the bus areas answer at once.
        let _ = shared.bus.set(BusFace::new(source));
        let pulses = Arc::new(PulseTotals::new());
        let ticks = Arc::new(BusTicks::new());
        let timing = self.config.timing();
        let cycle_us = self.config.cycle_us;
        let cycle = {
            let ticks = Arc::clone(&ticks);
            driver::spawn(
                Following {
                    line: self.line,
                    pulses: Arc::clone(&pulses),
                },
                DriverConfig {
                    rt: self.config.rt(),
                    cycles: None,
                    enable_at_start: self.config.enable_at_start,
                    recover: false,
                    stop: timing.stop(),
                    emulation: self.emulation,
                },
                Arc::clone(&monitor),
                move |f: &Following| {
                    if f.line.advanced() {
                        ticks.tick();
                    }
                },
            )
            .context("cannot start the fieldbus cycle")?
        };
        let scans = cycle_us / shared.info.timing.scan_us;
        let relays = self.relays;
        {
            let (shared, stop, monitor) =
                (Arc::clone(&shared), Arc::clone(&stop), Arc::clone(&monitor));
            std::thread::Builder::new()
                .name("plc-scan".into())
                .spawn(move || {
                    ecam_serve::scan_on_bus_ticks(
                        &shared,
                        &ticks,
                        scans,
                        &stop,
                        |shared| set_relays(shared, relays, monitor.snapshot().state),
                        |shared| {
                            pulses.publish(shared.with_plc(|plc| {
                                let hardware = plc.hardware();
                                [0, 1, 2, 3].map(|y| hardware.emitted(y))
                            }));
                        },
                    );
                })
                .context("cannot start the PLC thread")?;
        }
        std::thread::Builder::new()
            .name("ecam-bus-watch".into())
            .spawn(move || {
                let mut seen = 0;
                while !cycle.is_finished() {
                    if stop.load(Ordering::Relaxed) {
                        monitor.request_stop();
                    }
                    std::thread::sleep(Duration::from_millis(20));
                    seen = log_faults(&monitor, seen);
                }
                match cycle.join() {
                    Ok(summary) => {
                        tracing::info!(target: LOG, "cycle: {}", summary.setup);
                        summary_json(&summary, drives, cycle_us)
                    }
                    Err(_) => serde_json::json!({"error": "the fieldbus cycle panicked"}),
                }
            })
            .context("cannot start the fieldbus watcher")
    }
}

/// Logs the faults first seen since `seen` (of the fault events).
fn log_faults(monitor: &LineMonitor, seen: u64) -> u64 {
    let snapshot = monitor.snapshot();
    let new = usize::try_from(snapshot.fault_events.saturating_sub(seen)).unwrap_or(usize::MAX);
    let faults = &snapshot.faults;
    for fault in &faults[faults.len().saturating_sub(new)..] {
        tracing::error!(
            target: LOG,
            "{fault}: every drive brakes on its quick-stop ramp; \
             clear it with a fault reset (coil 14001 or POST /api/ethercat/reset)"
        );
    }
    snapshot.fault_events
}

/// `fault_relay` and `running_relay` from the line's state.
fn set_relays(shared: &Shared, relays: [Option<u16>; 2], state: Option<LineState>) {
    shared.with_plc(|plc| {
        let devices = plc.devices_mut();
        for (relay, on) in relays.into_iter().zip([
            state == Some(LineState::Faulted),
            state == Some(LineState::Running),
        ]) {
            if let Some(m) = relay {
                let _ = devices.set_bit(Device::M(m), on);
            }
        }
    });
}

/// The driver's published image as ecam-serve's snapshot, and its
/// commands as the driver's.
struct Source {
    monitor: Arc<LineMonitor>,
    transport: String,
    cycle_us: u32,
    max_lost: u32,
    names: Vec<String>,
    outputs: Vec<Option<u8>>,
}

impl BusSource for Source {
    fn snapshot(&self) -> BusSnapshot {
        let s = self.monitor.snapshot();
        let c = s.counters;
        let drives = s
            .drives
            .iter()
            .enumerate()
            .map(|(position, d)| DriveView {
                position,
                name: self.names.get(position).cloned().unwrap_or_default(),
                state_code: d.state.code(),
                state: d.state.to_string(),
                statusword: d.statusword,
                error_code: d.error_code,
                error: error_code_text(d.error_code).to_string(),
                reachable: d.reachable,
                enabled: d.enabled,
                fault: s
                    .faults
                    .iter()
                    .find(|f| f.drive == Some(position))
                    .map(|f| f.cause.to_string()),
                actual: d.actual,
                target: self
                    .outputs
                    .get(position)
                    .copied()
                    .flatten()
                    .map(|_| d.target),
                following_error: d.following_error,
                output: self.outputs.get(position).copied().flatten(),
                al_state_code: al_state_code(d.al_state),
                al_state: d.al_state.name().to_string(),
                missed_cycles: d.missed,
            })
            .collect();
        BusSnapshot {
            transport: self.transport.clone(),
            cycle_us: self.cycle_us,
            state: match s.state {
                None | Some(LineState::Stopped) => BusLineState::Stopped,
                Some(LineState::Enabling) => BusLineState::Enabling,
                Some(LineState::Running) => BusLineState::Running,
                Some(LineState::Faulted) => BusLineState::Faulted,
                Some(LineState::Stopping) => BusLineState::Stopping,
                Some(LineState::Recovering) => BusLineState::Recovering,
            },
            faults: s.faults.iter().map(ToString::to_string).collect(),
            cycles: c.cycles,
            working_counter_errors: c.working_counter_errors,
            lateness_max_us: c.lateness_max_ns as f64 / 1000.0,
            lateness_mean_us: c.lateness_mean_ns as f64 / 1000.0,
            overruns: c.overruns,
            lost_cycles: c.lost_cycles,
            lost_in_a_row_max: c.lost_in_a_row_max,
            max_lost_cycles: self.max_lost,
            late_replies: c.late_replies,
            sync0_lead_us: c.sync0_lead_ns as f64 / 1000.0,
            drives,
        }
    }

    fn command(&self, command: BusCommand) -> bool {
        self.monitor.command(match command {
            BusCommand::Enable => LineCommand::Enable,
            BusCommand::Disable => LineCommand::Disable,
            BusCommand::Reset => LineCommand::Reset,
            BusCommand::EmulateFault { drive, code } => LineCommand::InjectFault { drive, code },
        })
    }
}
