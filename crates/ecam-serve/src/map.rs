//! The Modbus TCP address map (the **contract** in `docs/architecture.md`):
//!
//! | device | Modbus object | address |
//! |---|---|---|
//! | D0 … D8511 | holding register (input register mirrors it) | n |
//! | M0 … M8511 | coil (discrete input mirrors it) | n |
//! | X0 … X377 (octal; X17 = index 15) | coil, writable (simulates the input) | 10000 + index |
//! | Y0 … Y377 (octal) | coil, read only | 12000 + index |
//!
//! A request must stay inside one area: a range that runs past an area's
//! end or starts in a gap (8512…9999, 10256…11999, 12256…) is illegal
//! (exception 02). Writing a Y coil is exception 02 as well: for this
//! server a read-only address is not an allowable address *for writing*.

use ecam_plc::{D_COUNT, Device, M_COUNT, XY_COUNT};

use crate::pdu::Exception;

/// Coil address of X0.
pub const X_COIL_BASE: u16 = 10000;
/// Coil address of Y0.
pub const Y_COIL_BASE: u16 = 12000;

/// The bit-device area a coil address falls in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CoilArea {
    /// Auxiliary relays M0…M8511 at 0…8511.
    M,
    /// Inputs X at 10000 + index.
    X,
    /// Outputs Y at 12000 + index (read only).
    Y,
}

impl CoilArea {
    /// The device at `index` in this area.
    pub const fn device(self, index: u16) -> Device {
        match self {
            Self::M => Device::M(index),
            Self::X => Device::X(index),
            Self::Y => Device::Y(index),
        }
    }

    /// Whether a client may write this area.
    pub const fn is_writable(self) -> bool {
        !matches!(self, Self::Y)
    }
}

/// `quantity` consecutive coils in one area, from device index `first`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CoilRange {
    /// The area.
    pub area: CoilArea,
    /// Device index of the first coil (`X17` → 15).
    pub first: u16,
    /// Number of coils (≥ 1).
    pub quantity: u16,
}

impl CoilRange {
    /// The devices of the range, in address order.
    pub fn devices(self) -> impl Iterator<Item = Device> {
        // `coil_range` checked first + quantity ≤ the area's size, so no overflow.
        (self.first..self.first + self.quantity).map(move |n| self.area.device(n))
    }
}

/// `quantity` consecutive data registers from `D{first}`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RegisterRange {
    /// Index of the first register.
    pub first: u16,
    /// Number of registers (≥ 1).
    pub quantity: u16,
}

impl RegisterRange {
    /// The register numbers of the range.
    pub fn registers(self) -> impl Iterator<Item = u16> {
        self.first..self.first + self.quantity
    }
}

/// Whether `[address, address + quantity)` lies inside `[base, base + size)`;
/// gives the offset of `address` in the area.
fn inside(address: u16, quantity: u16, base: u16, size: u16) -> Option<u16> {
    let offset = address.checked_sub(base)?;
    let end = u32::from(offset) + u32::from(quantity);
    (offset < size && end <= u32::from(size)).then_some(offset)
}

/// The coils a request for `quantity` coils at `address` covers.
///
/// # Errors
/// [`Exception::IllegalDataAddress`] when the range is not wholly inside
/// one area, [`Exception::IllegalDataValue`] for quantity 0.
pub fn coil_range(address: u16, quantity: u16) -> Result<CoilRange, Exception> {
    if quantity == 0 {
        return Err(Exception::IllegalDataValue);
    }
    [
        (CoilArea::M, 0, M_COUNT),
        (CoilArea::X, X_COIL_BASE, XY_COUNT),
        (CoilArea::Y, Y_COIL_BASE, XY_COUNT),
    ]
    .into_iter()
    .find_map(|(area, base, size)| {
        inside(address, quantity, base, size).map(|first| CoilRange {
            area,
            first,
            quantity,
        })
    })
    .ok_or(Exception::IllegalDataAddress)
}

/// The coils a write of `quantity` coils at `address` covers.
///
/// # Errors
/// As [`coil_range`], and [`Exception::IllegalDataAddress`] for the read-only Y area.
pub fn writable_coil_range(address: u16, quantity: u16) -> Result<CoilRange, Exception> {
    let range = coil_range(address, quantity)?;
    if range.area.is_writable() {
        Ok(range)
    } else {
        Err(Exception::IllegalDataAddress)
    }
}

/// The data registers a request for `quantity` registers at `address` covers.
///
/// # Errors
/// [`Exception::IllegalDataAddress`] past D8511, [`Exception::IllegalDataValue`] for quantity 0.
pub fn register_range(address: u16, quantity: u16) -> Result<RegisterRange, Exception> {
    if quantity == 0 {
        return Err(Exception::IllegalDataValue);
    }
    inside(address, quantity, 0, D_COUNT)
        .map(|first| RegisterRange { first, quantity })
        .ok_or(Exception::IllegalDataAddress)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The Modbus coil address of a bit device, if it has one (`X17` → 10015).
    fn coil_address(device: Device) -> Option<u16> {
        match device {
            Device::M(n) if n < M_COUNT => Some(n),
            Device::X(n) if n < XY_COUNT => Some(X_COIL_BASE + n),
            Device::Y(n) if n < XY_COUNT => Some(Y_COIL_BASE + n),
            _ => None,
        }
    }

    #[test]
    fn areas_sit_where_the_contract_puts_them() {
        assert_eq!(
            coil_range(0, 1),
            Ok(CoilRange {
                area: CoilArea::M,
                first: 0,
                quantity: 1
            })
        );
        assert_eq!(coil_range(8511, 1).map(|r| r.area), Ok(CoilArea::M));
        assert_eq!(
            coil_range(10015, 1),
            Ok(CoilRange {
                area: CoilArea::X,
                first: 15,
                quantity: 1
            })
        );
        assert_eq!(coil_range(12000, 256).map(|r| r.area), Ok(CoilArea::Y));
        assert_eq!(coil_address(Device::parse("X17").unwrap()), Some(10015));
        assert_eq!(coil_address(Device::parse("Y7").unwrap()), Some(12007));
        assert_eq!(coil_address(Device::D(0)), None);
        assert_eq!(
            register_range(8511, 1),
            Ok(RegisterRange {
                first: 8511,
                quantity: 1
            })
        );
    }

    #[test]
    fn gaps_and_overruns_are_illegal_addresses() {
        for (address, quantity) in [
            (8511, 2),
            (8512, 1),
            (9999, 1),
            (10255, 2),
            (10256, 1),
            (11999, 2),
            (12256, 1),
            (65535, 1),
            (65535, 2000),
        ] {
            assert_eq!(
                coil_range(address, quantity),
                Err(Exception::IllegalDataAddress),
                "{address}+{quantity}"
            );
        }
        assert_eq!(register_range(8511, 2), Err(Exception::IllegalDataAddress));
        assert_eq!(register_range(10000, 1), Err(Exception::IllegalDataAddress));
        assert_eq!(register_range(0, 0), Err(Exception::IllegalDataValue));
    }

    #[test]
    fn outputs_are_read_only() {
        assert_eq!(
            writable_coil_range(12007, 1),
            Err(Exception::IllegalDataAddress)
        );
        assert_eq!(writable_coil_range(10000, 256).map(|r| r.quantity), Ok(256));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        /// Every range the map accepts names only devices that exist, and
        /// the address of each device maps back to it.
        #[test]
        fn accepted_ranges_name_existing_devices(address: u16, quantity in 1u16..=2000) {
            if let Ok(range) = coil_range(address, quantity) {
                for (k, device) in range.devices().enumerate() {
                    prop_assert!(device.check().is_ok());
                    prop_assert_eq!(coil_address(device), Some(address + k as u16));
                }
            }
            if let Ok(range) = register_range(address, quantity) {
                prop_assert!(u32::from(range.first) + u32::from(range.quantity) <= u32::from(D_COUNT));
            }
        }
    }
}
