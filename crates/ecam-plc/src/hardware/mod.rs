//! The simulated hardware around the program: the four pulse outputs Y0–Y3
//! with their special registers, the PLSY/DPLSY pulse-train generators, the
//! high-speed counters, and wires from pulse outputs to counter inputs
//! (document 003's loopback: "Y1 pulse output terminal is connected with X0").
//!
//! Each pulse output has at most one owner ([`OutputOwner`]): the PLSY/DPLSY
//! or DECAM instruction that drives it. Only the owner's pulses reach the
//! output ([`record_pulses`]); another instruction waits until the owner
//! releases it (the FX family's rule).
//!
//! Everything here advances in hardware ticks of simulated time; the scan
//! cycle ([`crate::scan`]) and the simulator ([`crate::sim`]) drive it.

mod counter;
mod owner;
mod pulse_output;
mod pulse_train;
mod wire;

pub(crate) use counter::Counters;
pub use owner::OutputOwner;
pub(crate) use pulse_output::record_pulses;
pub(crate) use pulse_train::PulseTrain;
pub use wire::{Wire, WireError};

use crate::device::Device;
use crate::devices::Devices;
use crate::special::{M_BUSY, M_STOP};

/// Number of pulse outputs (Y0..Y3).
pub(crate) const PULSE_OUTPUTS: usize = 4;

/// Pulse outputs, generators, counters and wires of one PLC.
#[derive(Clone, Debug, Default)]
pub struct Hardware {
    /// The instruction driving each output (see [`Hardware::claim_output`]).
    owners: [Option<OutputOwner>; PULSE_OUTPUTS],
    /// Pulses were emitted on the output during the current tick.
    pulsed: [bool; PULSE_OUTPUTS],
    /// Signed pulses each output has emitted since power-up: the motor's
    /// position as a drive following the output sees it. Unlike D8140…
    /// it never wraps and a program cannot write it.
    emitted: [i64; PULSE_OUTPUTS],
    /// The running PLSY/DPLSY pulse train of each output; only ever there
    /// while its PLSY owns the output.
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

    /// Makes `owner` the one instruction that drives `output` (0..=3).
    ///
    /// Returns true when `owner` now holds the output: it was free, or
    /// `owner` held it already. False while another instruction holds it
    /// (the FX rule: the later instruction does not run, it waits and tries
    /// again) and for `output` > 3. The owner keeps the busy flag
    /// (M8147..M8150) on, even in ticks without pulses, until it releases.
    pub(crate) fn claim_output(&mut self, output: u8, owner: OutputOwner) -> bool {
        match self.owners.get_mut(usize::from(output)) {
            Some(slot @ None) => {
                *slot = Some(owner);
                true
            }
            Some(Some(held)) => *held == owner,
            None => false,
        }
    }

    /// `owner` lets go of `output`; nothing happens if another instruction
    /// holds it. A PLSY/DPLSY train of `owner` stops.
    pub(crate) fn release_output(&mut self, output: u8, owner: OutputOwner) {
        let index = usize::from(output);
        if self.owner(output) == Some(owner) {
            self.owners[index] = None;
            self.trains[index] = None;
        }
    }

    /// The instruction that holds `output`, if any.
    pub fn owner(&self, output: u8) -> Option<OutputOwner> {
        self.owners.get(usize::from(output)).copied().flatten()
    }

    /// True when `owner` may take `output` now (it is free or already held
    /// by `owner`); false for `output` > 3.
    pub(crate) fn output_free_for(&self, output: u8, owner: OutputOwner) -> bool {
        usize::from(output) < PULSE_OUTPUTS && self.owner(output).is_none_or(|o| o == owner)
    }

    /// True while the immediate-stop flag of `output` (M8145, M8146, M8152,
    /// M8153 for Y0..Y3) is on; also true for `output` > 3, which has no pulses.
    pub(crate) fn output_stopped(devices: &Devices, output: u8) -> bool {
        M_STOP
            .get(usize::from(output))
            .is_none_or(|&m| devices.m(m).unwrap_or(true))
    }

    /// Signed pulses `output` (0..=3) has emitted since power-up (0 for
    /// any other output). A drive that follows the output (`ecam serve
    /// --ethercat`) takes its position from here rather than from D8140…,
    /// which wrap at 32 bits and which a program may overwrite (`DMOV K0
    /// D8140`) without the motor moving.
    pub fn emitted(&self, output: u8) -> i64 {
        self.emitted.get(usize::from(output)).copied().unwrap_or(0)
    }

    /// Counters (set values, coils, high-speed counter inputs).
    pub(crate) fn counters(&self) -> &Counters {
        &self.counters
    }

    /// Mutable access to the counters.
    pub(crate) fn counters_mut(&mut self) -> &mut Counters {
        &mut self.counters
    }

    /// Starts (or replaces) the pulse train of PLSY/DPLSY `owner` on
    /// `output` (0..=3). Returns false, and starts nothing, while another
    /// instruction holds the output.
    pub(crate) fn start_pulse_train(
        &mut self,
        output: u8,
        owner: OutputOwner,
        train: PulseTrain,
    ) -> bool {
        if !self.claim_output(output, owner) {
            return false;
        }
        if let Some(slot) = self.trains.get_mut(usize::from(output)) {
            *slot = Some(train);
        }
        true
    }

    /// Changes the frequency of `owner`'s running pulse train (PLSY reads S1
    /// every scan).
    pub(crate) fn set_train_frequency(
        &mut self,
        output: u8,
        owner: OutputOwner,
        frequency_hz: u32,
    ) {
        if self.owner(output) != Some(owner) {
            return;
        }
        if let Some(Some(train)) = self.trains.get_mut(usize::from(output)) {
            train.set_frequency(frequency_hz);
        }
    }

    /// Stops `owner`'s pulse train on `output` and releases the output; a
    /// train of another instruction keeps running.
    pub(crate) fn stop_pulse_train(&mut self, output: u8, owner: OutputOwner) {
        self.release_output(output, owner);
    }

    /// Tick step 1: every pulse train emits the pulses due in `dt_us`
    /// (exact: the fractional pulse is carried to the next tick). A train
    /// whose output is stopped (M8145...) ends at once. A train that ends
    /// releases its output.
    pub(crate) fn tick_pulse_trains(&mut self, devices: &mut Devices, dt_us: u32) {
        for output in 0..PULSE_OUTPUTS as u8 {
            let index = usize::from(output);
            let Some(owner) = self.owners[index] else {
                continue;
            };
            let Some(train) = self.trains[index].as_mut() else {
                continue;
            };
            if Self::output_stopped(devices, output) {
                self.release_output(output, owner);
                continue;
            }
            let pulses = train.advance(dt_us);
            let finished = train.is_finished();
            if pulses > 0 {
                record_pulses(
                    devices,
                    self,
                    owner,
                    output,
                    i32::try_from(pulses).unwrap_or(i32::MAX),
                );
            }
            if finished {
                self.release_output(output, owner);
            }
        }
    }

    /// Tick's last step: high-speed counters count rising edges of their X
    /// inputs (set from outside: `--set X0=1`, Modbus), and the busy flags
    /// M8147..M8150 are updated for the tick that ends.
    pub fn end_tick(&mut self, devices: &mut Devices) {
        self.counters.sample_inputs(devices);
        for (index, &m) in M_BUSY.iter().enumerate() {
            let busy = self.pulsed[index] || self.owners[index].is_some();
            // M8147.. are in range by construction; nothing to report if not.
            let _ = devices.set_bit(Device::M(m), busy);
            self.pulsed[index] = false;
        }
    }
}
