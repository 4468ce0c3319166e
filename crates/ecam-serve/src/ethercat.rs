//! `ecam serve --ethercat CONFIG` (feature `ethercat`): the PLC's pulse
//! outputs on CiA 402 drives. ecam-ethercat's cycle driver runs the drives; at the end of
//! every cycle whose frame came back it wakes the PLC's thread, which runs
//! exactly one cycle time of scans (ecam-serve's `scan_on_bus_ticks`) and
//! publishes the pulse totals the drives follow next. The cycle shares no
//! lock with the PLC, Modbus or HTTP: its status goes out through the
//! driver's published image, which the adapter in `source.rs` turns into this
//! crate's [`crate::BusSnapshot`] when a client asks.
//!
//! The dependency points from the server to the fieldbus: ecam-ethercat
//! knows nothing of Modbus or the PLC, and this adapter implements this
//! crate's [`crate::BusSource`] over its cycle driver.

mod error;
mod source;

pub use error::BusError;

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use ecam_ethercat::config::FollowConfig;
use ecam_ethercat::driver::{self, DriverConfig, Following, PulseTotals};
use ecam_ethercat::emulation::EmulatedSegment;
use ecam_ethercat::follow::FollowLine;
use ecam_ethercat::monitor::LineMonitor;
use ecam_ethercat::summary::summary_json;
use ecam_ethercat::supervisor::LineState;
use ecam_ethercat::{Segment, Transport};
use ecam_plc::Device;
use serde_json::Value;

use crate::{BusFace, BusTicks, Shared};
use source::Source;

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

fn relay(file: &str, name: Option<&str>, key: &'static str) -> Result<Option<u16>, BusError> {
    let Some(name) = name else { return Ok(None) };
    match Device::parse(name) {
        Ok(Device::M(n)) if n < 8000 => Ok(Some(n)),
        _ => Err(BusError::Relay {
            file: file.to_string(),
            key,
            name: name.to_string(),
        }),
    }
}

/// Reads the configuration, checks it against the PLC's timing and brings
/// the segment to OP.
///
/// # Errors
/// An unreadable or invalid file, a cycle that is not a whole number of
/// scan periods, no interface, or a failed bring-up.
pub fn bring_up(path: &Path, emulated: Option<u16>, scan_us: u32) -> Result<Bus, BusError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|error| BusError::Read {
        file: file.clone(),
        error,
    })?;
    let config_error = |error| BusError::Config {
        file: file.clone(),
        error,
    };
    let config = FollowConfig::parse(&text).map_err(config_error)?;
    if scan_us == 0 || config.cycle_us % scan_us != 0 {
        return Err(BusError::CycleNotWholeScans {
            file,
            cycle_us: config.cycle_us,
            scan_us,
        });
    }
    let relays = [
        relay(&file, config.fault_relay.as_deref(), "fault_relay")?,
        relay(&file, config.running_relay.as_deref(), "running_relay")?,
    ];
    let followers = config.followers().map_err(config_error)?;
    let (transport, emulation) =
        Transport::chosen(emulated, config.interface.as_deref()).map_err(|error| {
            BusError::NoInterface {
                file: file.clone(),
                error,
            }
        })?;
    let transport_name = transport.describe();
    let timing = config.timing();
    let segment = Segment::bring_up_with(transport, timing.segment(), config.setups())?;
    let line = FollowLine::new(segment, followers, timing.max_lost_cycles(), timing.stop())
        .map_err(|error| BusError::Follow { file, error })?;
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
    ) -> Result<JoinHandle<Value>, BusError> {
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
            .map_err(|error| BusError::Thread {
                what: "the fieldbus cycle",
                error,
            })?
        };
        let scans = cycle_us / shared.info.timing.scan_us;
        let relays = self.relays;
        {
            let (shared, stop, monitor) =
                (Arc::clone(&shared), Arc::clone(&stop), Arc::clone(&monitor));
            std::thread::Builder::new()
                .name("plc-scan".into())
                .spawn(move || {
                    crate::scan_on_bus_ticks(
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
                .map_err(|error| BusError::Thread {
                    what: "the PLC thread",
                    error,
                })?;
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
            .map_err(|error| BusError::Thread {
                what: "the fieldbus watcher",
                error,
            })
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
