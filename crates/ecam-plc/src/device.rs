//! A device of the PLC by name: word devices D, bit devices M, X, Y, and the
//! counters C, addressed the FX-family way (X and Y numbered in octal), the
//! size of each range, and what a device keeps through a power cycle.
//!
//! Every address is checked: one outside a device's range is a
//! [`DeviceError`], never a silent zero, because a PLC programmer who mistypes
//! `D85110` deserves to be told.

use core::fmt;

/// Number of data registers D0…D8511.
pub const D_COUNT: u16 = 8512;
/// Number of auxiliary relays M0…M8511.
pub const M_COUNT: u16 = 8512;
/// Number of inputs X0…X377 (octal), and of outputs Y0…Y377.
pub const XY_COUNT: u16 = 256;
/// Number of counters C0…C255. C0–C199 are 16-bit, C200–C255 are 32-bit.
pub const C_COUNT: u16 = 256;
/// First 32-bit counter.
pub const C_32BIT_FIRST: u16 = 200;

/// A bit or word device, by kind and index (X/Y indices are the decimal
/// value of their octal names: `X17` is `Device::X(15)`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Device {
    /// Data register (16-bit word).
    D(u16),
    /// Auxiliary relay (bit).
    M(u16),
    /// Input (bit), index decoded from octal.
    X(u16),
    /// Output (bit), index decoded from octal.
    Y(u16),
    /// Counter (current value; 16 or 32 bits by number).
    C(u16),
}

impl Device {
    /// Parses `D2000`, `M8002`, `X17` (octal), `Y7`, `C231`.
    ///
    /// # Errors
    /// [`DeviceError::Syntax`] for an unknown prefix or a malformed number,
    /// [`DeviceError::OutOfRange`] for an index past the device's end.
    pub fn parse(text: &str) -> Result<Self, DeviceError> {
        let text = text.trim();
        let mut chars = text.chars();
        let prefix = chars
            .next()
            .ok_or(DeviceError::Syntax)?
            .to_ascii_uppercase();
        let digits = chars.as_str();
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(DeviceError::Syntax);
        }
        let radix = if matches!(prefix, 'X' | 'Y') { 8 } else { 10 };
        let index = u32::from_str_radix(digits, radix).map_err(|_| DeviceError::Syntax)?;
        let index = u16::try_from(index).map_err(|_| DeviceError::OutOfRange)?;
        let device = match prefix {
            'D' => Self::D(index),
            'M' => Self::M(index),
            'X' => Self::X(index),
            'Y' => Self::Y(index),
            'C' => Self::C(index),
            _ => return Err(DeviceError::Syntax),
        };
        device.check()?;
        Ok(device)
    }

    /// Checks the index against the device's range.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`].
    pub fn check(self) -> Result<Self, DeviceError> {
        let (index, count) = match self {
            Self::D(n) => (n, D_COUNT),
            Self::M(n) => (n, M_COUNT),
            Self::X(n) | Self::Y(n) => (n, XY_COUNT),
            Self::C(n) => (n, C_COUNT),
        };
        if index < count {
            Ok(self)
        } else {
            Err(DeviceError::OutOfRange)
        }
    }

    /// What the device is, in the manual's words: `data register`,
    /// `auxiliary relay`, `input`, `output`, `counter`.
    pub const fn kind(self) -> &'static str {
        match self {
            Self::D(_) => "data register",
            Self::M(_) => "auxiliary relay",
            Self::X(_) => "input",
            Self::Y(_) => "output",
            Self::C(_) => "counter",
        }
    }

    /// True for the bit devices M, X, Y.
    pub const fn is_bit(self) -> bool {
        matches!(self, Self::M(_) | Self::X(_) | Self::Y(_))
    }
}

/// What a device holds through a power cycle of the PLC: the FX3U's
/// default latched (battery-backed) ranges, which the LX3V follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Retention {
    /// The PLC's own special device (D8000–D8511, M8000–M8511): set up
    /// afresh by the PLC at power-up, never kept.
    Special,
    /// Kept through power loss: M500–M7679, D200–D7999, and the values of
    /// counters C100–C199 and C220–C255.
    Latched,
    /// Cleared at power-up: M0–M499, M7680–M7999 (past the FX3U's M range),
    /// D0–D199, C0–C99, C200–C219, and the I/O images X and Y.
    Cleared,
}

/// First special D and M device (D8000, M8000).
pub const SPECIAL_FIRST: u16 = 8000;
/// Latched data registers: D200–D7999 (FX3U default).
pub const D_LATCHED: core::ops::Range<u16> = 200..SPECIAL_FIRST;
/// Latched auxiliary relays: M500–M7679 (FX3U default; the FX3U has no
/// M7680–M7999).
pub const M_LATCHED: core::ops::Range<u16> = 500..7680;
/// Latched counters: C100–C199 (16-bit) and C220–C255 (32-bit, including
/// the high-speed counters), FX3U default.
pub const C_LATCHED: [core::ops::Range<u16>; 2] = [100..200, 220..C_COUNT];

impl Device {
    /// What this device holds through a power cycle (see [`Retention`]).
    ///
    /// ```
    /// use ecam_plc::{Device, Retention};
    /// assert_eq!(Device::D(100).retention(), Retention::Cleared);
    /// assert_eq!(Device::D(2000).retention(), Retention::Latched);
    /// assert_eq!(Device::M(8145).retention(), Retention::Special);
    /// ```
    pub fn retention(self) -> Retention {
        let latched = match self {
            Self::D(n) | Self::M(n) if n >= SPECIAL_FIRST => return Retention::Special,
            Self::D(n) => D_LATCHED.contains(&n),
            Self::M(n) => M_LATCHED.contains(&n),
            Self::C(n) => C_LATCHED.iter().any(|r| r.contains(&n)),
            Self::X(_) | Self::Y(_) => false,
        };
        if latched {
            Retention::Latched
        } else {
            Retention::Cleared
        }
    }
}

impl fmt::Display for Device {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::D(n) => write!(f, "D{n}"),
            Self::M(n) => write!(f, "M{n}"),
            Self::X(n) => write!(f, "X{n:o}"),
            Self::Y(n) => write!(f, "Y{n:o}"),
            Self::C(n) => write!(f, "C{n}"),
        }
    }
}

/// A device address that cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeviceError {
    /// Not a device name (unknown prefix, missing or non-digit number, 8 or 9 in an X/Y name).
    Syntax,
    /// The index is past the end of the device's range.
    OutOfRange,
    /// A bit was asked of a word device, or a word of a bit device.
    WrongKind,
}

impl fmt::Display for DeviceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Syntax => {
                "not a device name (expected D, M, X, Y or C and a number; X/Y in octal)"
            }
            Self::OutOfRange => "device number out of range (D/M 0-8511, X/Y 0-377 octal, C 0-255)",
            Self::WrongKind => "wrong kind of device for this access (bit vs word)",
        })
    }
}

impl std::error::Error for DeviceError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_octal_x_and_y() {
        assert_eq!(Device::parse("X17"), Ok(Device::X(15)));
        assert_eq!(Device::parse("Y7"), Ok(Device::Y(7)));
        assert_eq!(Device::parse("X8"), Err(DeviceError::Syntax));
        assert_eq!(Device::parse("X400"), Err(DeviceError::OutOfRange));
        assert_eq!(Device::X(15).to_string(), "X17");
    }

    #[test]
    fn parses_words_and_rejects_out_of_range() {
        assert_eq!(Device::parse("D2000"), Ok(Device::D(2000)));
        assert_eq!(Device::parse("D8512"), Err(DeviceError::OutOfRange));
        assert_eq!(Device::parse("Q1"), Err(DeviceError::Syntax));
        assert_eq!(Device::parse("D"), Err(DeviceError::Syntax));
    }

    #[test]
    fn retention_follows_the_fx3u_defaults() {
        use Retention::{Cleared, Latched, Special};
        for (device, expected) in [
            (Device::D(0), Cleared),
            (Device::D(199), Cleared),
            (Device::D(200), Latched),
            (Device::D(7999), Latched),
            (Device::D(8000), Special),
            (Device::D(8140), Special),
            (Device::D(8511), Special),
            (Device::M(0), Cleared),
            (Device::M(499), Cleared),
            (Device::M(500), Latched),
            (Device::M(7679), Latched),
            (Device::M(7680), Cleared),
            (Device::M(7999), Cleared),
            (Device::M(8000), Special),
            (Device::M(8145), Special),
            (Device::M(8511), Special),
            (Device::C(99), Cleared),
            (Device::C(100), Latched),
            (Device::C(199), Latched),
            (Device::C(200), Cleared),
            (Device::C(219), Cleared),
            (Device::C(220), Latched),
            (Device::C(231), Latched),
            (Device::C(255), Latched),
            (Device::X(0), Cleared),
            (Device::Y(7), Cleared),
        ] {
            assert_eq!(device.retention(), expected, "{device}");
        }
    }
}
