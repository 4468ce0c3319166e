//! Reading and writing operands at run time.

use crate::devices::{C_32BIT_FIRST, Device, DeviceError, Devices};
use crate::hardware::Hardware;
use crate::il::{BitRef, Source, Width};
use crate::operation_error::{CODE_DEVICE_RANGE, OperationError};

/// A device error at run time (the parser checks ranges, so this is rare).
pub(crate) fn device_error(device: impl core::fmt::Display, err: DeviceError) -> OperationError {
    OperationError::new(CODE_DEVICE_RANGE, format!("{device}: {err}"))
}

/// State of a bit operand: X/Y/M, or a counter's contact.
pub(crate) fn read_bit(devices: &Devices, hardware: &Hardware, device: Device) -> bool {
    match device {
        Device::C(n) => hardware.counters().contact(devices, n),
        Device::D(_) => false,
        bit => devices.bit(bit).unwrap_or(false),
    }
}

/// State of a contact operand: a bit device, a counter contact or `Dn.b`.
pub(crate) fn read_bit_ref(devices: &Devices, hardware: &Hardware, bit: BitRef) -> bool {
    match bit {
        BitRef::Device(device) => read_bit(devices, hardware, device),
        BitRef::WordBit(b) => devices.word_bit(b.register, b.bit).unwrap_or(false),
        BitRef::Timer(n) => devices.timers().contact(n).unwrap_or(false),
    }
}

/// Drives a coil operand: Y, M or `Dn.b` (read-modify-write of the word).
pub(crate) fn write_bit_ref(
    devices: &mut Devices,
    bit: BitRef,
    on: bool,
) -> Result<(), OperationError> {
    match bit {
        BitRef::Device(device) => devices
            .set_bit(device, on)
            .map_err(|e| device_error(device, e)),
        BitRef::WordBit(b) => devices
            .set_word_bit(b.register, b.bit, on)
            .map_err(|e| device_error(b, e)),
        // The parser lets no OUT/SET name a timer without its set value.
        BitRef::Timer(n) => Err(device_error(format!("T{n}"), DeviceError::WrongKind)),
    }
}

/// Value of a source operand at the instruction's width (16-bit reads are sign-extended).
pub(crate) fn read_source(
    devices: &Devices,
    source: Source,
    width: Width,
) -> Result<i32, OperationError> {
    let value = match source {
        Source::Constant(v) => return Ok(v),
        Source::Register(n) => match width {
            Width::Word => devices.word(n).map(i32::from),
            Width::Double => devices.dword(n),
        }
        .map_err(|e| device_error(Device::D(n), e))?,
        Source::Counter(n) => devices
            .counter(n)
            .map_err(|e| device_error(Device::C(n), e))?,
        Source::Timer(n) => devices
            .timers()
            .value(n)
            .map(i32::from)
            .map_err(|e| device_error(format!("T{n}"), e))?,
        Source::Group(group) => return read_group(devices, group, width),
    };
    Ok(match width {
        Width::Word => i32::from(value as i16),
        Width::Double => value,
    })
}

/// The number a word group holds: its n × 4 bits, lowest first. A group as
/// wide as the instruction (K4 at 16 bit, K8 at 32 bit) is signed, a
/// shorter one is positive (the FX fills the upper bits with 0).
fn read_group(
    devices: &Devices,
    group: crate::il::WordGroup,
    width: Width,
) -> Result<i32, OperationError> {
    let mut value: u32 = 0;
    for i in 0..u16::from(group.digits) * 4 {
        let device = group
            .bit(i)
            .ok_or_else(|| device_error(group, DeviceError::OutOfRange))?;
        if devices.bit(device).map_err(|e| device_error(device, e))? {
            value |= 1 << i;
        }
    }
    Ok(if group.digits == 4 && width == Width::Word {
        i32::from(value as u16 as i16)
    } else {
        value as i32
    })
}

/// Writes a D or C destination at the instruction's width.
pub(crate) fn write_word(
    devices: &mut Devices,
    dst: Device,
    width: Width,
    value: i32,
) -> Result<(), OperationError> {
    match (dst, width) {
        (Device::D(n), Width::Word) => devices.set_word(n, value as i16),
        (Device::D(n), Width::Double) => devices.set_dword(n, value),
        (Device::C(n), Width::Word) if n < C_32BIT_FIRST => devices.set_counter(n, value),
        (Device::C(n), Width::Word) => devices.set_counter(n, i32::from(value as i16)),
        (Device::C(n), Width::Double) => devices.set_counter(n, value),
        (other, _) => Err(DeviceError::WrongKind).map_err(|e| device_error(other, e))?,
    }
    .map_err(|e| device_error(dst, e))
}
