//! Coils: OUT, SET and RST on bits, PLS/PLF, the timer and counter coils,
//! and ZRST (RST over a range).

use super::machine::{Machine, Memory};
use super::operands::{device_error, read_source, write_bit_ref};
use crate::device::{C_32BIT_FIRST, Device};
use crate::il::{BitDest, BitRef, Source, Width, ZoneDevice};
use crate::operation_error::{CODE_OPERAND, OperationError};

/// `OUT`: the coil follows the power flow.
pub(super) fn out(
    machine: &mut Machine<'_>,
    dest: BitRef,
    power: bool,
) -> Result<(), OperationError> {
    write_bit_ref(machine.devices, dest, power)
}

/// `SET`: on while the power flow is on, kept after.
pub(super) fn set(
    machine: &mut Machine<'_>,
    dest: BitRef,
    power: bool,
) -> Result<(), OperationError> {
    if !power {
        return Ok(());
    }
    write_bit_ref(machine.devices, dest, true)
}

/// `RST`: a bit off, a register or counter to 0, a timer back to its start.
pub(super) fn reset(
    machine: &mut Machine<'_>,
    dest: BitRef,
    power: bool,
) -> Result<(), OperationError> {
    if !power {
        return Ok(());
    }
    match dest {
        BitRef::Device(device) => reset_device(machine, device),
        BitRef::Timer(n) => machine
            .devices
            .timers_mut()
            .reset(n)
            .map_err(|e| device_error(format!("T{n}"), e)),
        bit @ (BitRef::WordBit(_) | BitRef::Indexed(..)) => {
            write_bit_ref(machine.devices, bit, false)
        }
        // The parser allows an indexed timer in contacts only.
        BitRef::IndexedTimer(..) => Ok(()),
    }
}

/// `PLS` (`rising`) / `PLF`: the coil is on for one scan on the edge.
pub(super) fn pulse(
    machine: &mut Machine<'_>,
    (rising, dest): (bool, BitDest),
    power: bool,
    memory: &mut Memory,
) -> Result<(), OperationError> {
    let edge = if rising {
        power && !memory.previous
    } else {
        !power && memory.previous
    };
    memory.previous = power;
    machine
        .devices
        .set_bit(dest.0, edge)
        .map_err(|e| device_error(dest.0, e))
}

/// `OUT Tn K/D`: the timer times while the power flow is on.
pub(super) fn timer(
    machine: &mut Machine<'_>,
    (timer, preset): (u16, Source),
    power: bool,
) -> Result<(), OperationError> {
    let devices = &mut *machine.devices;
    let preset = read_source(devices, preset, Width::Word)?;
    // A register set value reads as -32768..=32767; FX timers count
    // only up to 0..=32767, so a negative one is an operand error.
    let preset = i16::try_from(preset)
        .ok()
        .filter(|p| *p >= 0)
        .ok_or_else(|| {
            OperationError::new(
                CODE_OPERAND,
                format!("T{timer} set value {preset} is negative (K0 to K32767)"),
            )
        })?;
    devices
        .timers_mut()
        .drive(timer, power, preset, machine.now_us)
        .map_err(|e| device_error(format!("T{timer}"), e))
}

/// `OUT Cn K/D`: the counter coil with its set value (16 bit for C0–C199,
/// 32 bit from C200).
pub(super) fn counter(
    machine: &mut Machine<'_>,
    (counter, set_value): (u16, Source),
    power: bool,
) -> Result<(), OperationError> {
    let width = if counter >= C_32BIT_FIRST {
        Width::Double
    } else {
        Width::Word
    };
    let set_value = read_source(machine.devices, set_value, width)?;
    machine
        .hardware
        .counters_mut()
        .drive_coil(machine.devices, counter, power, set_value);
    Ok(())
}

/// `ZRST D1 D2`: RST of every device from `first` to `last`.
pub(super) fn zone_reset(
    machine: &mut Machine<'_>,
    kind: ZoneDevice,
    (first, last): (u16, u16),
) -> Result<(), OperationError> {
    for n in first..=last {
        let device = match kind {
            ZoneDevice::M => Device::M(n),
            ZoneDevice::Y => Device::Y(n),
            ZoneDevice::D => Device::D(n),
            ZoneDevice::C => Device::C(n),
        };
        reset_device(machine, device)?;
    }
    Ok(())
}

/// RST of one device: bits off, words and counters to 0.
fn reset_device(machine: &mut Machine<'_>, device: Device) -> Result<(), OperationError> {
    let devices = &mut *machine.devices;
    match device {
        Device::D(n) => devices.set_word(n, 0),
        Device::C(n) => {
            // The latched contact goes off with the value.
            Device::C(n).check().map_err(|e| device_error(device, e))?;
            machine.hardware.counters_mut().reset(devices, n);
            Ok(())
        }
        bit => devices.set_bit(bit, false),
    }
    .map_err(|e| device_error(device, e))
}
