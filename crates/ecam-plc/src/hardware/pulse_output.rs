//! Pulse bookkeeping shared by PLSY/DPLSY and DECAM.

use super::{Hardware, OutputOwner};
use crate::device::Device;
use crate::devices::Devices;
use crate::special::{D_PULSE_COUNT, M_BUSY};

/// Pulses that `owner` emits on output Y0..=Y3 (`output` 0..=3) this tick,
/// signed (negative = reverse).
///
/// Returns the pulses actually emitted: 0 when `output` > 3, its stop flag
/// (M8145, M8146, M8152, M8153) is on, or `owner` does not hold the output
/// ([`Hardware::claim_output`]: one instruction drives an output at a
/// time) — the caller keeps its backlog. Adds
/// them (wrapping, 32-bit) to D8140/41, D8142/43, D8150/51 or D8152/53, which
/// count down in reverse (document 003, "Special address"), turns the busy
/// flag M8147..M8150 on for this tick, and hands their number to every wire
/// from this output: a one-phase counter input sees pulses, not direction.
pub(crate) fn record_pulses(
    devices: &mut Devices,
    hardware: &mut Hardware,
    owner: OutputOwner,
    output: u8,
    pulses: i32,
) -> i32 {
    let index = usize::from(output);
    let (Some(&count_register), Some(&busy)) = (D_PULSE_COUNT.get(index), M_BUSY.get(index)) else {
        return 0;
    };
    if pulses == 0
        || hardware.owner(output) != Some(owner)
        || Hardware::output_stopped(devices, output)
    {
        return 0;
    }
    let count = devices
        .dword(count_register)
        .unwrap_or(0)
        .wrapping_add(pulses);
    // D8140..D8153 and M8147..M8150 exist in every device memory.
    let _ = devices.set_dword(count_register, count);
    let _ = devices.set_bit(Device::M(busy), true);
    if let Some(flag) = hardware.pulsed.get_mut(index) {
        *flag = true;
    }
    if let Some(total) = hardware.emitted.get_mut(index) {
        *total = total.saturating_add(i64::from(pulses));
    }
    let magnitude = pulses.unsigned_abs();
    let Hardware {
        wires, counters, ..
    } = hardware;
    for wire in wires.iter().filter(|w| w.output() == output) {
        counters.feed(devices, wire.input(), magnitude);
    }
    pulses
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_owner_pulses_an_output() {
        let mut devices = Devices::new();
        let mut hardware = Hardware::new();
        let (cam, plsy) = (OutputOwner::Cam(1), OutputOwner::PulseTrain(4));
        assert!(hardware.claim_output(1, cam));
        assert_eq!(record_pulses(&mut devices, &mut hardware, cam, 1, -3), -3);
        assert_eq!(devices.dword(8142), Ok(-3));
        assert_eq!(hardware.emitted(1), -3);
        assert_eq!(devices.m(8148), Ok(true));
        // Y1 is the cam's: another instruction can neither take it nor pulse it.
        assert!(!hardware.claim_output(1, plsy));
        assert_eq!(record_pulses(&mut devices, &mut hardware, plsy, 1, 5), 0);
        assert_eq!(devices.dword(8142), Ok(-3));
    }
}
