//! `ecam serve --ethercat CONFIG`: the PLC's pulse outputs on CiA 402
//! drives. The fieldbus cycle replaces the wall-clock scan loop: each
//! cycle runs the PLC for exactly one cycle time (a whole number of scan
//! periods), then sends every mapped drive the pulses its output has
//! emitted ([`ecam_ethercat::follow`]), so the drives see the PLC's motion
//! cycle by cycle, without the beat a free-running scan loop would give
//! against the bus. Status goes to [`ecam_serve::BusFace`] (Modbus input
//! registers from 20000, `GET /api/ethercat`); commands come from it.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use anyhow::{Context as _, bail};
use ecam_engine::drive::AxisDrive;
use ecam_ethercat::cia402::DriveState;
use ecam_ethercat::config::FollowConfig;
use ecam_ethercat::emulation::EmulatedSegment;
use ecam_ethercat::follow::{FollowLine, PULSE_OUTPUTS};
use ecam_ethercat::rt::{CycleClock, LatenessHistogram, configure_current_thread};
use ecam_ethercat::supervisor::LineState;
use ecam_ethercat::{Segment, SegmentConfig};
use ecam_plc::Device;
use ecam_serve::{BusCommand, BusFace, BusLineState, BusSnapshot, DriveView, Shared};
use serde_json::{Value, json};

use crate::cmd::ethercat::{lateness_json, open_transport};

/// The tracing target of the bus cycle's messages.
const LOG: &str = "ecam::ethercat";

/// Cycles the drives are given to hear "disable" before the server exits.
const GOODBYE_CYCLES: u32 = 5;

/// A segment brought up for the server, not yet cycling.
pub struct Bus {
    config: FollowConfig,
    line: FollowLine,
    emulated: Option<Arc<Mutex<EmulatedSegment>>>,
    transport: String,
    relays: Relays,
}

/// The M relays the server keeps for the program.
#[derive(Clone, Copy, Debug, Default)]
struct Relays {
    fault: Option<u16>,
    running: Option<u16>,
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
    let file = path.display();
    if config.cycle_us % scan_us != 0 {
        bail!(
            "{file}: cycle_us = {} is not a whole number of scan periods (--scan-us {scan_us}): \
             each bus cycle runs the PLC for exactly one cycle time",
            config.cycle_us
        );
    }
    let relays = Relays {
        fault: relay(config.fault_relay.as_deref(), "fault_relay").context(file.to_string())?,
        running: relay(config.running_relay.as_deref(), "running_relay")
            .context(file.to_string())?,
    };
    let followers = config.followers().with_context(|| file.to_string())?;
    let (transport, emulated_segment) =
        open_transport(emulated, config.interface.as_deref(), path)?;
    let transport_name = match (&emulated_segment, &config.interface) {
        (Some(_), _) => format!("emulated ({} drives)", emulated.unwrap_or(0)),
        (None, Some(interface)) => interface.clone(),
        (None, None) => String::new(),
    };
    let segment = Segment::bring_up(
        transport,
        SegmentConfig {
            cycle: config.cycle(),
            link_fifo_priority: config.fifo_priority.map(|p| p.saturating_add(1).min(99)),
            ..SegmentConfig::default()
        },
    )?;
    let line = FollowLine::new(segment, followers).with_context(|| file.to_string())?;
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
        emulated: emulated_segment,
        transport: transport_name,
        relays,
    })
}

impl Bus {
    /// Starts the cycle thread; it runs the PLC and the drives until
    /// `stop`, then disables the drives and returns the summary line.
    ///
    /// # Errors
    /// The thread could not be started.
    pub fn spawn(
        mut self,
        shared: Arc<Shared>,
        stop: Arc<AtomicBool>,
    ) -> anyhow::Result<JoinHandle<Value>> {
        // Set before any client is served, so the bus areas answer at once.
        let _ = shared.bus.set(BusFace::new());
        if self.config.enable_at_start {
            self.line.start()?;
        }
        std::thread::Builder::new()
            .name("ecam-bus".into())
            .spawn(move || self.run(&shared, &stop))
            .context("cannot start the fieldbus cycle")
    }

    fn run(mut self, shared: &Shared, stop: &AtomicBool) -> Value {
        let setup = configure_current_thread(&self.config.rt());
        tracing::info!(target: LOG, "cycle: {setup}");
        shared.stats.scanning.store(true, Ordering::Relaxed);
        let scans = self.config.cycle_us / shared.info.timing.scan_us;
        let mut lateness = LatenessHistogram::default();
        let mut counters = Counters::default();
        let mut clock = match CycleClock::start(self.config.cycle()) {
            Ok(clock) => clock,
            Err(e) => {
                tracing::error!(target: LOG, "monotonic clock: {e}; the drives stay disabled");
                shared.stats.scanning.store(false, Ordering::Relaxed);
                return json!({"error": format!("monotonic clock: {e}")});
            }
        };
        let mut goodbye = None;
        loop {
            if let Err(e) = clock.wait(&mut lateness) {
                tracing::error!(target: LOG, "clock_nanosleep: {e}; stopping");
                break;
            }
            if goodbye.is_none() && stop.load(Ordering::Relaxed) {
                self.line.stop();
                goodbye = Some(GOODBYE_CYCLES);
            }
            if let Some(face) = shared.bus.get() {
                for command in face.take_commands() {
                    self.obey(command);
                }
            }
            let emitted = self.step_plc(shared, scans);
            self.exchange(&emitted, &mut counters);
            if let Some(face) = shared.bus.get() {
                face.publish(self.snapshot(&counters, &lateness));
            }
            match &mut goodbye {
                Some(0) => break,
                Some(n) => *n -= 1,
                None => {}
            }
        }
        shared.stats.scanning.store(false, Ordering::Relaxed);
        let drives = self.line.segment().drives();
        json!({
            "drives": drives.len(),
            "cycles": counters.cycles,
            "cycle_us": self.config.cycle_us,
            "state": self.line.state().name(),
            "faults": counters.faults,
            "working_counter_errors": counters.wkc_errors,
            "exchange_errors": counters.exchange_errors,
            "actual": drives.iter().map(|d| d.actual()).collect::<Vec<_>>(),
            "scheduling": setup.to_string(),
            "lateness": lateness_json(&lateness),
        })
    }

    /// Sets the relays, runs the PLC for one cycle time and reads what the
    /// pulse outputs have emitted.
    fn step_plc(&self, shared: &Shared, scans: u32) -> [i64; PULSE_OUTPUTS as usize] {
        let state = self.line.state();
        shared.with_plc(|plc| {
            let devices = plc.devices_mut();
            if let Some(m) = self.relays.fault {
                let _ = devices.set_bit(Device::M(m), state == LineState::Faulted);
            }
            if let Some(m) = self.relays.running {
                let _ = devices.set_bit(Device::M(m), state == LineState::Running);
            }
        });
        for _ in 0..scans {
            ecam_serve::scan_period(shared);
        }
        shared.with_plc(|plc| {
            let hardware = plc.hardware();
            [0, 1, 2, 3].map(|y| hardware.emitted(y))
        })
    }

    fn exchange(&mut self, emitted: &[i64; PULSE_OUTPUTS as usize], counters: &mut Counters) {
        counters.cycles += 1;
        match self.line.cycle(emitted) {
            Ok(report) => {
                if report.bus.working_counter_error() {
                    counters.wkc_errors += 1;
                }
                for fault in &report.new_faults {
                    tracing::error!(
                        target: LOG,
                        "{fault}: every drive brakes on its quick-stop ramp; \
                         clear it with a fault reset (coil 14001 or POST /api/ethercat/reset)"
                    );
                    counters.faults.push(fault.to_string());
                }
            }
            Err(e) => {
                // One lost exchange: the drives keep their last target.
                counters.exchange_errors += 1;
                if counters.exchange_errors == 1 || counters.exchange_errors.is_power_of_two() {
                    tracing::error!(
                        target: LOG,
                        "exchange failed ({} so far): {e}",
                        counters.exchange_errors
                    );
                }
            }
        }
    }

    fn obey(&mut self, command: BusCommand) {
        let done = match command {
            BusCommand::Enable => self.line.start().map_err(|e| e.to_string()),
            BusCommand::Disable => {
                self.line.stop();
                Ok(())
            }
            BusCommand::Reset => match self.line.reset() {
                // Nothing to clear is not worth a warning.
                Err(_) if self.line.state() != LineState::Faulted => Ok(()),
                other => other.map_err(|e| e.to_string()),
            },
            BusCommand::EmulateFault { drive, code } => match &self.emulated {
                Some(segment) => {
                    let mut segment = segment.lock().unwrap_or_else(|p| p.into_inner());
                    match segment.esc_mut(drive) {
                        Some(esc) => {
                            esc.drive_mut().inject_fault(code);
                            Ok(())
                        }
                        None => Err(format!("no emulated drive {drive}")),
                    }
                }
                None => Err("faults can only be injected into emulated drives".into()),
            },
        };
        match done {
            Ok(()) => tracing::info!(target: LOG, "{command:?}: done"),
            Err(e) => tracing::warn!(target: LOG, "{command:?} refused: {e}"),
        }
    }

    fn snapshot(&self, counters: &Counters, lateness: &LatenessHistogram) -> BusSnapshot {
        let segment = self.line.segment();
        let drives = segment
            .drives()
            .iter()
            .enumerate()
            .map(|(position, d)| {
                let status = d.status();
                let state = d.state();
                DriveView {
                    position,
                    name: segment.drive_name(position).unwrap_or_default(),
                    state_code: state_code(state),
                    state: state.to_string(),
                    statusword: d.inputs().statusword,
                    error_code: d.inputs().error_code,
                    reachable: d.reachable(),
                    enabled: status.enabled,
                    fault: status.fault.map(|f| f.to_string()),
                    actual: status.actual,
                    target: self.line.target_of(position),
                    following_error: status.following_error,
                    output: self.line.output_of(position),
                }
            })
            .collect();
        BusSnapshot {
            transport: self.transport.clone(),
            cycle_us: self.config.cycle_us,
            state: match self.line.state() {
                LineState::Stopped => BusLineState::Stopped,
                LineState::Enabling => BusLineState::Enabling,
                LineState::Running => BusLineState::Running,
                LineState::Faulted => BusLineState::Faulted,
            },
            faults: self.line.faults().iter().map(ToString::to_string).collect(),
            cycles: counters.cycles,
            working_counter_errors: counters.wkc_errors,
            lateness_max_us: lateness.max.as_secs_f64() * 1e6,
            lateness_mean_us: lateness.mean().as_secs_f64() * 1e6,
            overruns: lateness.overruns,
            drives,
        }
    }
}

/// What the cycle counts for the summary.
#[derive(Debug, Default)]
struct Counters {
    cycles: u64,
    wkc_errors: u64,
    exchange_errors: u64,
    faults: Vec<String>,
}

/// The state's code in the input registers (see `ecam_serve::DRIVE_WORDS`).
fn state_code(state: DriveState) -> u16 {
    DriveState::ALL
        .iter()
        .position(|&s| s == state)
        .map_or(0, |i| u16::try_from(i).unwrap_or(0))
}
