//! Bit shifts: SFTL and SFTR.

use super::operands::device_error;
use crate::device::{Device, DeviceError};
use crate::devices::Devices;
use crate::operation_error::OperationError;

/// `SFTL` (`left`) / `SFTR` S D n1 n2: the n1 bits from D move n2 places;
/// the n2 bits from S fill the freed places.
pub(super) fn bit_shift(
    devices: &mut Devices,
    left: bool,
    (src, dst): (Device, Device),
    (length, places): (u16, u16),
) -> Result<(), OperationError> {
    // Read everything first: S may overlap D.
    let incoming = read_bits(devices, src, places)?;
    let block = read_bits(devices, dst, length)?;
    let kept = usize::from(length - places);
    let shifted: Vec<bool> = if left {
        incoming.iter().chain(&block[..kept]).copied().collect()
    } else {
        block[usize::from(places)..]
            .iter()
            .chain(&incoming)
            .copied()
            .collect()
    };
    for (i, on) in (0u16..).zip(shifted) {
        let device = nth_bit(dst, i)?;
        devices
            .set_bit(device, on)
            .map_err(|e| device_error(device, e))?;
    }
    Ok(())
}

/// The bit `i` places after `first` (X, Y or M).
fn nth_bit(first: Device, i: u16) -> Result<Device, OperationError> {
    let next = |n: u16| {
        n.checked_add(i)
            .ok_or_else(|| device_error(first, DeviceError::OutOfRange))
    };
    match first {
        Device::X(n) => next(n).map(Device::X),
        Device::Y(n) => next(n).map(Device::Y),
        Device::M(n) => next(n).map(Device::M),
        other => Err(device_error(other, DeviceError::WrongKind)),
    }
}

/// `count` consecutive bits from `first`, lowest first.
fn read_bits(devices: &Devices, first: Device, count: u16) -> Result<Vec<bool>, OperationError> {
    (0..count)
        .map(|i| {
            let device = nth_bit(first, i)?;
            devices.bit(device).map_err(|e| device_error(device, e))
        })
        .collect()
}
