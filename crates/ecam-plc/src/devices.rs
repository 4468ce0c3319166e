//! Device memory of the PLC: word devices D, bit devices M, X, Y, and the
//! counters C, addressed the FX-family way (X and Y numbered in octal).
//!
//! Every access is checked: an address outside a device's range is an
//! [`DeviceError`], never a silent zero, because a PLC programmer who mistypes
//! `D85110` deserves to be told.

use core::fmt;

use crate::timers::Timers;

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

/// All device memory of one PLC.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Devices {
    d: Vec<u16>,
    m: Vec<bool>,
    x: Vec<bool>,
    y: Vec<bool>,
    c: Vec<i32>,
    /// V0–V7 then Z0–Z7, 16 bits each.
    index: [u16; 16],
    timers: Timers,
}

impl Default for Devices {
    fn default() -> Self {
        Self::new()
    }
}

impl Devices {
    /// Memory with every device at zero / off.
    pub fn new() -> Self {
        Self {
            d: vec![0; usize::from(D_COUNT)],
            m: vec![false; usize::from(M_COUNT)],
            x: vec![false; usize::from(XY_COUNT)],
            y: vec![false; usize::from(XY_COUNT)],
            c: vec![0; usize::from(C_COUNT)],
            index: [0; 16],
            timers: Timers::new(),
        }
    }

    /// Data register `Dn` as a signed 16-bit value.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`].
    pub fn word(&self, n: u16) -> Result<i16, DeviceError> {
        self.d
            .get(usize::from(n))
            .map(|&w| w as i16)
            .ok_or(DeviceError::OutOfRange)
    }

    /// Sets `Dn`.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`].
    pub fn set_word(&mut self, n: u16, value: i16) -> Result<(), DeviceError> {
        let slot = self
            .d
            .get_mut(usize::from(n))
            .ok_or(DeviceError::OutOfRange)?;
        *slot = value as u16;
        Ok(())
    }

    /// The 32-bit value in `Dn` (low word) and `Dn+1` (high word).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] if either word is past D8511.
    pub fn dword(&self, n: u16) -> Result<i32, DeviceError> {
        let lo = self.word(n)? as u16;
        let hi = self.word(n.checked_add(1).ok_or(DeviceError::OutOfRange)?)? as u16;
        Ok(((u32::from(hi) << 16) | u32::from(lo)) as i32)
    }

    /// Writes a 32-bit value into `Dn` (low word) and `Dn+1` (high word).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] if either word is past D8511 (nothing is written then).
    pub fn set_dword(&mut self, n: u16, value: i32) -> Result<(), DeviceError> {
        let hi_index = n.checked_add(1).ok_or(DeviceError::OutOfRange)?;
        if usize::from(hi_index) >= self.d.len() {
            return Err(DeviceError::OutOfRange);
        }
        let bits = value as u32;
        self.d[usize::from(n)] = bits as u16;
        self.d[usize::from(hi_index)] = (bits >> 16) as u16;
        Ok(())
    }

    /// The IEEE-754 single-precision float held in `Dn`, `Dn+1` (low word first).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`].
    pub fn float(&self, n: u16) -> Result<f32, DeviceError> {
        Ok(f32::from_bits(self.dword(n)? as u32))
    }

    /// Writes a float into `Dn`, `Dn+1` (low word first).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`].
    pub fn set_float(&mut self, n: u16, value: f32) -> Result<(), DeviceError> {
        self.set_dword(n, value.to_bits() as i32)
    }

    /// The state of a bit device (M, X or Y).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`], or [`DeviceError::WrongKind`] for D and C.
    pub fn bit(&self, device: Device) -> Result<bool, DeviceError> {
        let (bits, n) = match device {
            Device::M(n) => (&self.m, n),
            Device::X(n) => (&self.x, n),
            Device::Y(n) => (&self.y, n),
            Device::D(_) | Device::C(_) => return Err(DeviceError::WrongKind),
        };
        bits.get(usize::from(n))
            .copied()
            .ok_or(DeviceError::OutOfRange)
    }

    /// Sets a bit device (M, X or Y).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`], or [`DeviceError::WrongKind`] for D and C.
    pub fn set_bit(&mut self, device: Device, on: bool) -> Result<(), DeviceError> {
        let (bits, n) = match device {
            Device::M(n) => (&mut self.m, n),
            Device::X(n) => (&mut self.x, n),
            Device::Y(n) => (&mut self.y, n),
            Device::D(_) | Device::C(_) => return Err(DeviceError::WrongKind),
        };
        let slot = bits
            .get_mut(usize::from(n))
            .ok_or(DeviceError::OutOfRange)?;
        *slot = on;
        Ok(())
    }

    /// Bit `bit` (0–15) of `Dn`, the FX3 family's `Dn.b`.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] for a register past D8511 or a bit past 15.
    pub fn word_bit(&self, n: u16, bit: u8) -> Result<bool, DeviceError> {
        let word = self.word(n)? as u16;
        let mask = 1u16.checked_shl(u32::from(bit)).filter(|_| bit < 16);
        Ok(word & mask.ok_or(DeviceError::OutOfRange)? != 0)
    }

    /// Sets or clears bit `bit` (0–15) of `Dn`, leaving the other bits.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] for a register past D8511 or a bit past 15.
    pub fn set_word_bit(&mut self, n: u16, bit: u8, on: bool) -> Result<(), DeviceError> {
        let mask = 1u16
            .checked_shl(u32::from(bit))
            .filter(|_| bit < 16)
            .ok_or(DeviceError::OutOfRange)?;
        let word = self.word(n)? as u16;
        let word = if on { word | mask } else { word & !mask };
        self.set_word(n, word as i16)
    }

    /// Shorthand for `bit(Device::M(n))`.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`].
    pub fn m(&self, n: u16) -> Result<bool, DeviceError> {
        self.bit(Device::M(n))
    }

    /// Shorthand for `set_bit(Device::M(n), on)`.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`].
    pub fn set_m(&mut self, n: u16, on: bool) -> Result<(), DeviceError> {
        self.set_bit(Device::M(n), on)
    }

    /// Current value of counter `Cn` (16-bit counters hold values in i16 range).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`].
    pub fn counter(&self, n: u16) -> Result<i32, DeviceError> {
        self.c
            .get(usize::from(n))
            .copied()
            .ok_or(DeviceError::OutOfRange)
    }

    /// Sets counter `Cn`; a 16-bit counter (C0–C199) keeps the low 16 bits, sign-extended.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`].
    pub fn set_counter(&mut self, n: u16, value: i32) -> Result<(), DeviceError> {
        let slot = self
            .c
            .get_mut(usize::from(n))
            .ok_or(DeviceError::OutOfRange)?;
        *slot = if n < C_32BIT_FIRST {
            i32::from(value as i16)
        } else {
            value
        };
        Ok(())
    }

    /// Index register Vn or Zn as a signed 16-bit word.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past V7/Z7.
    pub fn index_register(&self, register: crate::il::IndexReg) -> Result<i16, DeviceError> {
        self.index
            .get(index_slot(register)?)
            .map(|&w| w as i16)
            .ok_or(DeviceError::OutOfRange)
    }

    /// Sets Vn or Zn.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past V7/Z7.
    pub fn set_index_register(
        &mut self,
        register: crate::il::IndexReg,
        value: i16,
    ) -> Result<(), DeviceError> {
        let slot = self
            .index
            .get_mut(index_slot(register)?)
            .ok_or(DeviceError::OutOfRange)?;
        *slot = value as u16;
        Ok(())
    }

    /// The pair Vn (high word) : Zn (low word) as one 32-bit value, as a
    /// 32-bit FX3U instruction reads `Zn`.
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past 7.
    pub fn index_pair(&self, n: u8) -> Result<i32, DeviceError> {
        use crate::il::IndexReg;
        let low = self.index_register(IndexReg::Z(n))? as u16;
        let high = self.index_register(IndexReg::V(n))? as u16;
        Ok(((u32::from(high) << 16) | u32::from(low)) as i32)
    }

    /// Writes the pair Vn:Zn (Zn the low word).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past 7 (nothing written).
    pub fn set_index_pair(&mut self, n: u8, value: i32) -> Result<(), DeviceError> {
        use crate::il::IndexReg;
        let bits = value as u32;
        self.index_register(IndexReg::V(n))?;
        self.set_index_register(IndexReg::Z(n), bits as u16 as i16)?;
        self.set_index_register(IndexReg::V(n), (bits >> 16) as u16 as i16)
    }

    /// Timers T0–T255 (values and contacts).
    pub fn timers(&self) -> &Timers {
        &self.timers
    }

    /// Timers, to drive or reset.
    pub fn timers_mut(&mut self) -> &mut Timers {
        &mut self.timers
    }

    /// The raw word image of D0…D8511 (for the Modbus face and state files).
    pub fn words(&self) -> &[u16] {
        &self.d
    }
}

/// Slot of Vn/Zn in the index array: V0–V7, then Z0–Z7.
fn index_slot(register: crate::il::IndexReg) -> Result<usize, DeviceError> {
    use crate::il::{INDEX_COUNT, IndexReg};
    match register {
        IndexReg::V(n) if n < INDEX_COUNT => Ok(usize::from(n)),
        IndexReg::Z(n) if n < INDEX_COUNT => Ok(usize::from(INDEX_COUNT + n)),
        _ => Err(DeviceError::OutOfRange),
    }
}

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
    fn dwords_are_low_word_first() {
        let mut dev = Devices::new();
        dev.set_dword(100, 0x0001_0002).unwrap();
        assert_eq!(dev.word(100), Ok(2));
        assert_eq!(dev.word(101), Ok(1));
        assert_eq!(dev.dword(100), Ok(0x0001_0002));
        dev.set_dword(100, -3).unwrap();
        assert_eq!(dev.dword(100), Ok(-3));
        assert_eq!(dev.set_dword(8511, 1), Err(DeviceError::OutOfRange));
    }

    #[test]
    fn word_bits_touch_one_bit() {
        let mut dev = Devices::new();
        dev.set_word(5, 0x00F0).unwrap();
        dev.set_word_bit(5, 15, true).unwrap();
        dev.set_word_bit(5, 4, false).unwrap();
        assert_eq!(dev.word(5), Ok(0x80E0u16 as i16));
        assert_eq!(dev.word_bit(5, 15), Ok(true));
        assert_eq!(dev.word_bit(5, 4), Ok(false));
        assert_eq!(dev.word_bit(5, 16), Err(DeviceError::OutOfRange));
        assert_eq!(
            dev.set_word_bit(8512, 0, true),
            Err(DeviceError::OutOfRange)
        );
    }

    #[test]
    fn index_pair_is_z_low_v_high() {
        use crate::il::IndexReg;
        let mut dev = Devices::new();
        dev.set_index_pair(0, 70000).unwrap();
        assert_eq!(dev.index_register(IndexReg::Z(0)), Ok(4464));
        assert_eq!(dev.index_register(IndexReg::V(0)), Ok(1));
        assert_eq!(dev.index_pair(0), Ok(70000));
        assert_eq!(dev.index_pair(8), Err(DeviceError::OutOfRange));
        assert_eq!(
            dev.set_index_register(IndexReg::V(8), 1),
            Err(DeviceError::OutOfRange)
        );
    }

    #[test]
    fn floats_round_trip() {
        let mut dev = Devices::new();
        dev.set_float(106, 1.6667).unwrap();
        assert_eq!(dev.float(106), Ok(1.6667));
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

    #[test]
    fn sixteen_bit_counters_wrap() {
        let mut dev = Devices::new();
        dev.set_counter(0, 40000).unwrap();
        assert_eq!(dev.counter(0), Ok(40000 - 65536));
        dev.set_counter(231, 40000).unwrap();
        assert_eq!(dev.counter(231), Ok(40000));
    }
}
