//! The simulated hardware around the program: the four pulse outputs Y0–Y3
//! with their special registers, the PLSY/DPLSY pulse-train generators, the
//! high-speed counters, and wires from pulse outputs to counter inputs
//! (document 003's loopback: "Y1 pulse output terminal is connected with X0").
//!
//! Everything here advances in hardware ticks of simulated time; the scan
//! cycle ([`crate::scan`]) and the simulator ([`crate::sim`]) drive it.

mod counter;
mod pulse_output;
mod pulse_train;
mod wire;

pub use counter::{Counters, HIGH_SPEED_COUNTERS};
pub use pulse_output::record_pulses;
pub use pulse_train::PulseTrain;
pub use wire::{Wire, WireError};

use crate::devices::{Device, Devices};
use crate::special::{M_BUSY, M_STOP};

/// Number of pulse outputs (Y0..Y3).
pub const PULSE_OUTPUTS: usize = 4;

/// Pulse outputs, generators, counters and wires of one PLC.
#[derive(Clone, Debug, Default)]
pub struct Hardware {
    /// Busy claimed by an E-cam instance that runs (see [`Hardware::claim_output`]).
    claimed: [bool; PULSE_OUTPUTS],
    /// Pulses were emitted on the output during the current tick.
    pulsed: [bool; PULSE_OUTPUTS],
    /// The running PLSY/DPLSY pulse train of each output.
    trains: [Option<PulseTrain>; PULSE_OUTPUTS],
    /// Counter set values, coils and high-speed counter inputs.
    counters: Counters,
    /// Loopback wires.
    wires: Vec<Wire>,
}

impl Hardware {
    /// Hardware with no wires, no pulse trains, all counters idle.
    pub fn new() -> Self {
        Self::default()
    }

    /// Connects a pulse output to a counter input. The same wire given twice
    /// is still one connection: each pulse is counted once.
    pub fn add_wire(&mut self, wire: Wire) {
        if !self.wires.contains(&wire) {
            self.wires.push(wire);
        }
    }

    /// Keeps the busy flag (M8147..M8150) of `output` on while `busy`, even in
    /// ticks without pulses: an E-cam claims its output while the cam runs.
    /// No effect for `output` > 3.
    pub fn claim_output(&mut self, output: u8, busy: bool) {
        if let Some(slot) = self.claimed.get_mut(usize::from(output)) {
            *slot = busy;
        }
    }

    /// True while the immediate-stop flag of `output` (M8145, M8146, M8152,
    /// M8153 for Y0..Y3) is on; also true for `output` > 3, which has no pulses.
    pub fn output_stopped(devices: &Devices, output: u8) -> bool {
        M_STOP
            .get(usize::from(output))
            .is_none_or(|&m| devices.m(m).unwrap_or(true))
    }

    /// Counters (set values, coils, high-speed counter inputs).
    pub fn counters(&self) -> &Counters {
        &self.counters
    }

    /// Mutable access to the counters.
    pub fn counters_mut(&mut self) -> &mut Counters {
        &mut self.counters
    }

    /// The PLSY/DPLSY pulse train running on `output`, if any.
    pub fn pulse_train(&self, output: u8) -> Option<&PulseTrain> {
        self.trains
            .get(usize::from(output))
            .and_then(Option::as_ref)
    }

    /// Starts (or replaces) the pulse train of `output` (0..=3).
    pub fn start_pulse_train(&mut self, output: u8, train: PulseTrain) {
        if let Some(slot) = self.trains.get_mut(usize::from(output)) {
            *slot = Some(train);
        }
    }

    /// Changes the frequency of a running pulse train (PLSY reads S1 every scan).
    pub fn set_train_frequency(&mut self, output: u8, frequency_hz: u32) {
        if let Some(Some(train)) = self.trains.get_mut(usize::from(output)) {
            train.set_frequency(frequency_hz);
        }
    }

    /// Stops the pulse train of `output`.
    pub fn stop_pulse_train(&mut self, output: u8) {
        if let Some(slot) = self.trains.get_mut(usize::from(output)) {
            *slot = None;
        }
    }

    /// Tick step 1: every pulse train emits the pulses due in `dt_us`
    /// (exact: the fractional pulse is carried to the next tick). A train
    /// whose output is stopped (M8145...) ends at once.
    pub fn tick_pulse_trains(&mut self, devices: &mut Devices, dt_us: u32) {
        for output in 0..PULSE_OUTPUTS as u8 {
            let index = usize::from(output);
            if Self::output_stopped(devices, output) {
                self.stop_pulse_train(output);
                continue;
            }
            let Some(Some(train)) = self.trains.get_mut(index) else {
                continue;
            };
            let pulses = train.advance(dt_us);
            if train.is_finished() {
                self.trains[index] = None;
            }
            if pulses > 0 {
                record_pulses(
                    devices,
                    self,
                    output,
                    i32::try_from(pulses).unwrap_or(i32::MAX),
                );
            }
        }
    }

    /// Tick's last step: high-speed counters count rising edges of their X
    /// inputs (set from outside: `--set X0=1`, Modbus), and the busy flags
    /// M8147..M8150 are updated for the tick that ends.
    pub fn end_tick(&mut self, devices: &mut Devices) {
        self.counters.sample_inputs(devices);
        for (index, &m) in M_BUSY.iter().enumerate() {
            let busy = self.pulsed[index] || self.claimed[index] || self.trains[index].is_some();
            // M8147.. are in range by construction; nothing to report if not.
            let _ = devices.set_bit(Device::M(m), busy);
            self.pulsed[index] = false;
        }
    }
}
