//! Device memory of the PLC: the values of the D, M, X, Y and C devices
//! ([`crate::device::Device`]), the index registers V/Z and the timers.
//!
//! Every access is checked: an address outside a device's range is a
//! [`DeviceError`], never a silent zero.

use crate::device::{C_32BIT_FIRST, C_COUNT, D_COUNT, Device, DeviceError, M_COUNT, XY_COUNT};
use crate::index_register::{INDEX_COUNT, IndexReg};
use crate::timers::Timers;

/// All device memory of one PLC.
#[derive(Debug, PartialEq, Eq)]
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

impl Clone for Devices {
    fn clone(&self) -> Self {
        Self {
            d: self.d.clone(),
            m: self.m.clone(),
            x: self.x.clone(),
            y: self.y.clone(),
            c: self.c.clone(),
            index: self.index,
            timers: self.timers.clone(),
        }
    }

    /// Copies into the memory already there (a server publishes device
    /// memory after every scan period: no allocation then).
    fn clone_from(&mut self, source: &Self) {
        self.d.clone_from(&source.d);
        self.m.clone_from(&source.m);
        self.x.clone_from(&source.x);
        self.y.clone_from(&source.y);
        self.c.clone_from(&source.c);
        self.index = source.index;
        self.timers.clone_from(&source.timers);
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
    pub fn index_register(&self, register: IndexReg) -> Result<i16, DeviceError> {
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
        register: IndexReg,
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
        use IndexReg;
        let low = self.index_register(IndexReg::Z(n))? as u16;
        let high = self.index_register(IndexReg::V(n))? as u16;
        Ok(((u32::from(high) << 16) | u32::from(low)) as i32)
    }

    /// Writes the pair Vn:Zn (Zn the low word).
    ///
    /// # Errors
    /// [`DeviceError::OutOfRange`] past 7 (nothing written).
    pub fn set_index_pair(&mut self, n: u8, value: i32) -> Result<(), DeviceError> {
        use IndexReg;
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
    pub(crate) fn timers_mut(&mut self) -> &mut Timers {
        &mut self.timers
    }

    /// The raw word image of D0…D8511 (for the Modbus face and state files).
    pub fn words(&self) -> &[u16] {
        &self.d
    }
}

/// Slot of Vn/Zn in the index array: V0–V7, then Z0–Z7.
fn index_slot(register: IndexReg) -> Result<usize, DeviceError> {
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
        use IndexReg;
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
    fn sixteen_bit_counters_wrap() {
        let mut dev = Devices::new();
        dev.set_counter(0, 40000).unwrap();
        assert_eq!(dev.counter(0), Ok(40000 - 65536));
        dev.set_counter(231, 40000).unwrap();
        assert_eq!(dev.counter(231), Ok(40000));
    }
}
