//! Comparisons into bits: CMP/DCMP and ZCP/DZCP (the comparison contacts
//! are in `contacts.rs`).

use super::operands::{device_error, read_source};
use crate::device::Device;
use crate::devices::Devices;
use crate::il::{Source, Width};
use crate::operation_error::OperationError;

/// `CMP` S1 S2 D: D = S1>S2, D+1 = S1=S2, D+2 = S1<S2.
pub(super) fn compare(
    devices: &mut Devices,
    width: Width,
    (s1, s2): (Source, Source),
    dst: Device,
) -> Result<(), OperationError> {
    let a = read_source(devices, s1, width)?;
    let b = read_source(devices, s2, width)?;
    set_three(devices, dst, [a > b, a == b, a < b])
}

/// `ZCP` S1 S2 S3 D: D = S3 below the zone, D+1 inside, D+2 above.
pub(super) fn zone_compare(
    devices: &mut Devices,
    width: Width,
    (low, high, value): (Source, Source, Source),
    dst: Device,
) -> Result<(), OperationError> {
    let low = read_source(devices, low, width)?;
    // FX3U: a lower limit above the upper one counts as both.
    let high = read_source(devices, high, width)?.max(low);
    let value = read_source(devices, value, width)?;
    set_three(
        devices,
        dst,
        [value < low, (low..=high).contains(&value), value > high],
    )
}

/// Writes the three result bits of CMP/ZCP from `dst` on (the parser
/// checked that all three exist).
fn set_three(devices: &mut Devices, dst: Device, bits: [bool; 3]) -> Result<(), OperationError> {
    for (offset, on) in (0u16..).zip(bits) {
        let device = match dst {
            Device::M(n) => Device::M(n.saturating_add(offset)),
            Device::Y(n) => Device::Y(n.saturating_add(offset)),
            other => other,
        };
        devices
            .set_bit(device, on)
            .map_err(|e| device_error(device, e))?;
    }
    Ok(())
}
