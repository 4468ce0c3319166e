//! Device views for tools: how `ecam plc run --set/--dump/--trace` name a
//! value. `D100` is a signed 16-bit word, `DD100` the signed 32-bit value in
//! D100/D101 (low word first), `DE100` the float in D100/D101, `M0`/`X17`/`Y7`
//! a bit (0/1), `C231` a counter's value, `D2001.1` one bit of a word (0/1,
//! bit 0–F), `T0` a timer's current value, `V0`…`V7`/`Z0`…`Z7` an index
//! register (signed 16-bit).

use core::fmt;

use crate::device::{C_32BIT_FIRST, D_COUNT, Device, DeviceError};
use crate::devices::Devices;

/// A named value in device memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum View {
    /// `Dn`: signed 16-bit.
    Word(u16),
    /// `DDn`: signed 32-bit in Dn (low), Dn+1 (high).
    Double(u16),
    /// `DEn`: IEEE-754 float in Dn, Dn+1.
    Float(u16),
    /// `Mn`, `Xn`, `Yn` (octal for X/Y): 0 or 1.
    Bit(Device),
    /// `Cn`: the counter's value.
    Counter(u16),
    /// `Dn.b`: bit `b` (0–15) of a word, 0 or 1.
    WordBit(u16, u8),
    /// `Tn`: the timer's current value.
    Timer(u16),
    /// `Vn`/`Zn`: an index register, signed 16-bit.
    Index(crate::index_register::IndexReg),
}

/// A value read through a [`View`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// Words, double words, bits and counters.
    Int(i64),
    /// `DEn`.
    Float(f32),
}

impl fmt::Display for Value {
    /// JSON-compatible: integers as is, floats in shortest form, NaN/∞ as `null`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Int(v) => write!(f, "{v}"),
            Self::Float(v) if v.is_finite() => write!(f, "{v}"),
            Self::Float(_) => f.write_str("null"),
        }
    }
}

/// A view name or value that cannot be used.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ViewError(String);

impl fmt::Display for ViewError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ViewError {}

fn device_message(text: &str, err: DeviceError) -> ViewError {
    let text = ecam_core::excerpt::excerpt(text);
    ViewError(match err {
        DeviceError::OutOfRange => format!(
            "device `{text}` is out of range (D0-D8511, M0-M8511, X/Y 0-377 octal, C0-C255)"
        ),
        _ => format!(
            "unknown device `{text}` (expected Dn, DDn, DEn, Mn, Xn, Yn, Cn, Tn, Vn or Zn; X/Y in octal)"
        ),
    })
}

impl View {
    /// Parses `D100`, `DD100`, `DE106`, `M0`, `X2`, `Y7`, `C231` (case-insensitive).
    ///
    /// # Errors
    /// Unknown or out-of-range device.
    ///
    /// ```
    /// use ecam_plc::View;
    /// assert_eq!(View::parse("dd2019").unwrap().to_string(), "DD2019");
    /// assert!(View::parse("DD8511").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Self, ViewError> {
        let upper = text.trim().to_ascii_uppercase();
        if let Some((word, bit)) = upper.split_once('.') {
            let n = match Device::parse(word) {
                Ok(Device::D(n)) => n,
                Ok(_) => {
                    return Err(ViewError(format!(
                        "`{text}`: only D registers have bits (Dn.b, b = 0-F)"
                    )));
                }
                Err(err) => return Err(device_message(text, err)),
            };
            let bit = u8::from_str_radix(bit, 16)
                .ok()
                .filter(|b| *b < 16 && bit.len() == 1)
                .ok_or_else(|| {
                    ViewError(format!(
                        "`{text}`: the bit is one hex digit 0-F",
                        text = ecam_core::excerpt::excerpt(text)
                    ))
                })?;
            return Ok(Self::WordBit(n, bit));
        }
        for (prefix, make) in [
            (
                'V',
                crate::index_register::IndexReg::V as fn(u8) -> crate::index_register::IndexReg,
            ),
            ('Z', crate::index_register::IndexReg::Z),
        ] {
            if let Some(number) = upper.strip_prefix(prefix)
                && !number.is_empty()
                && number.bytes().all(|b| b.is_ascii_digit())
            {
                let n = number
                    .parse::<u8>()
                    .ok()
                    .filter(|n| *n < crate::index_register::INDEX_COUNT)
                    .ok_or_else(|| {
                        ViewError(format!(
                            "index register `{text}` is out of range (V0-V7, Z0-Z7)"
                        ))
                    })?;
                return Ok(Self::Index(make(n)));
            }
        }
        if let Some(number) = upper.strip_prefix('T')
            && !number.is_empty()
            && number.bytes().all(|b| b.is_ascii_digit())
        {
            let n = number
                .parse::<u16>()
                .ok()
                .filter(|n| *n < crate::timers::T_COUNT)
                .ok_or_else(|| {
                    ViewError(format!(
                        "timer `{text}` is out of range (T0-T255)",
                        text = ecam_core::excerpt::excerpt(text)
                    ))
                })?;
            return Ok(Self::Timer(n));
        }
        for (prefix, double) in [("DD", true), ("DE", false)] {
            if let Some(rest) = upper.strip_prefix(prefix) {
                let n = match Device::parse(&format!("D{rest}")) {
                    Ok(Device::D(n)) => n,
                    Ok(_) => return Err(device_message(text, DeviceError::Syntax)),
                    Err(err) => return Err(device_message(text, err)),
                };
                if n.checked_add(1).is_none_or(|hi| hi >= D_COUNT) {
                    return Err(ViewError(format!(
                        "`{text}` needs D{n} and D{} (the last word is D8511)",
                        u32::from(n) + 1
                    )));
                }
                return Ok(if double {
                    Self::Double(n)
                } else {
                    Self::Float(n)
                });
            }
        }
        Ok(
            match Device::parse(&upper).map_err(|err| device_message(text, err))? {
                Device::D(n) => Self::Word(n),
                Device::C(n) => Self::Counter(n),
                bit => Self::Bit(bit),
            },
        )
    }

    /// The view `k` places further on (`D2019` → `D2020`, `DD2019` → `DD2021`),
    /// for `--dump DEV:COUNT`.
    ///
    /// # Errors
    /// When that device does not exist.
    pub fn nth(self, k: u16) -> Result<Self, ViewError> {
        let step = |n: u16, stride: u16| n.checked_add(k.saturating_mul(stride));
        let next = match self {
            Self::Word(n) => step(n, 1).map(Self::Word),
            Self::Double(n) => step(n, 2).map(Self::Double),
            Self::Float(n) => step(n, 2).map(Self::Float),
            Self::Counter(n) => step(n, 1).map(Self::Counter),
            Self::Timer(n) => step(n, 1)
                .filter(|n| *n < crate::timers::T_COUNT)
                .map(Self::Timer),
            Self::Index(r) => {
                use crate::index_register::IndexReg;
                step(u16::from(r.number()), 1)
                    .filter(|n| *n < u16::from(crate::index_register::INDEX_COUNT))
                    .map(|n| match r {
                        IndexReg::V(_) => Self::Index(IndexReg::V(n as u8)),
                        IndexReg::Z(_) => Self::Index(IndexReg::Z(n as u8)),
                    })
            }
            Self::WordBit(n, b) => {
                let bit = u16::from(b).checked_add(k).filter(|b| *b < 16);
                bit.map(|b| Self::WordBit(n, b as u8))
            }
            Self::Bit(Device::M(n)) => step(n, 1).map(|n| Self::Bit(Device::M(n))),
            Self::Bit(Device::X(n)) => step(n, 1).map(|n| Self::Bit(Device::X(n))),
            Self::Bit(Device::Y(n)) => step(n, 1).map(|n| Self::Bit(Device::Y(n))),
            Self::Bit(_) => None,
        };
        let out_of_range = || {
            // Name the largest count that fits: "X0:257 runs past" read as if
            // the user had typed 257.
            ViewError(format!(
                "{self}:COUNT runs past the end of the device range: at most {k} from {self}"
            ))
        };
        let next = next.ok_or_else(out_of_range)?;
        let last_word = match next {
            Self::Double(n) | Self::Float(n) => n.checked_add(1),
            Self::Word(n) | Self::WordBit(n, _) => Some(n),
            _ => Some(0),
        };
        let exists = last_word.is_some_and(|n| n < D_COUNT)
            && match next {
                Self::Bit(d) => d.check().is_ok(),
                Self::Counter(n) => Device::C(n).check().is_ok(),
                _ => true,
            };
        if exists {
            Ok(next)
        } else {
            Err(out_of_range())
        }
    }

    /// Reads the value.
    pub fn read(self, devices: &Devices) -> Value {
        match self {
            Self::Word(n) => Value::Int(devices.word(n).map_or(0, i64::from)),
            Self::Double(n) => Value::Int(devices.dword(n).map_or(0, i64::from)),
            Self::Float(n) => Value::Float(devices.float(n).unwrap_or(f32::NAN)),
            Self::Bit(d) => Value::Int(i64::from(devices.bit(d).unwrap_or(false))),
            Self::Counter(n) => Value::Int(devices.counter(n).map_or(0, i64::from)),
            Self::WordBit(n, b) => Value::Int(i64::from(devices.word_bit(n, b).unwrap_or(false))),
            Self::Timer(n) => Value::Int(devices.timers().value(n).map_or(0, i64::from)),
            Self::Index(r) => Value::Int(devices.index_register(r).map_or(0, i64::from)),
        }
    }

    /// Writes `text` (`3183`, `-5`, `1.6667`, `0`/`1` for bits).
    ///
    /// # Errors
    /// A value that does not parse or does not fit: words take -32768..65535,
    /// double words -2147483648..4294967295, bits 0 or 1, floats any finite number.
    pub fn write(self, devices: &mut Devices, text: &str) -> Result<(), ViewError> {
        let text = text.trim();
        let bad = |range: &str| {
            let text = ecam_core::excerpt::excerpt(text);
            ViewError(format!(
                "`{text}` is not a value for {self} (expected {range})"
            ))
        };
        let int = |min: i64, max: i64, range: &str| {
            text.parse::<i64>()
                .ok()
                .filter(|v| (min..=max).contains(v))
                .ok_or_else(|| bad(range))
        };
        let result = match self {
            Self::Word(n) => devices.set_word(
                n,
                int(-32768, 65535, "an integer -32768..65535")? as u16 as i16,
            ),
            Self::Double(n) => devices.set_dword(
                n,
                int(
                    i64::from(i32::MIN),
                    i64::from(u32::MAX),
                    "an integer -2147483648..4294967295",
                )? as u32 as i32,
            ),
            Self::Float(n) => {
                let v = text
                    .parse::<f32>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| bad("a finite number"))?;
                devices.set_float(n, v)
            }
            Self::Bit(d) => devices.set_bit(d, int(0, 1, "0 or 1")? == 1),
            Self::Counter(n) => {
                let value = if n < C_32BIT_FIRST {
                    int(
                        -32768,
                        32767,
                        "an integer -32768..32767 for a 16-bit counter",
                    )?
                } else {
                    int(i64::from(i32::MIN), i64::from(i32::MAX), "a 32-bit integer")?
                };
                devices.set_counter(n, value as i32)
            }
            Self::WordBit(n, b) => devices.set_word_bit(n, b, int(0, 1, "0 or 1")? == 1),
            Self::Timer(n) => devices
                .timers_mut()
                .set_value(n, int(0, 32767, "an integer 0..32767")? as i16),
            Self::Index(r) => devices.set_index_register(
                r,
                int(-32768, 65535, "an integer -32768..65535")? as u16 as i16,
            ),
        };
        result.map_err(|err| device_message(&self.to_string(), err))
    }
}

impl fmt::Display for View {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Word(n) => write!(f, "D{n}"),
            Self::Double(n) => write!(f, "DD{n}"),
            Self::Float(n) => write!(f, "DE{n}"),
            Self::Bit(d) => write!(f, "{d}"),
            Self::Counter(n) => write!(f, "C{n}"),
            Self::WordBit(n, b) => write!(f, "D{n}.{b:X}"),
            Self::Timer(n) => write!(f, "T{n}"),
            Self::Index(r) => write!(f, "{r}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_read_and_write_every_form() {
        let mut devices = Devices::new();
        View::parse("D100")
            .unwrap()
            .write(&mut devices, "3183")
            .unwrap();
        View::parse("DD102")
            .unwrap()
            .write(&mut devices, "-70000")
            .unwrap();
        View::parse("DE106")
            .unwrap()
            .write(&mut devices, "1.6667")
            .unwrap();
        View::parse("x2").unwrap().write(&mut devices, "1").unwrap();
        View::parse("C231")
            .unwrap()
            .write(&mut devices, "123456")
            .unwrap();
        View::parse("D0")
            .unwrap()
            .write(&mut devices, "65535")
            .unwrap();
        assert_eq!(
            View::parse("D100").unwrap().read(&devices),
            Value::Int(3183)
        );
        assert_eq!(
            View::parse("DD102").unwrap().read(&devices),
            Value::Int(-70000)
        );
        assert_eq!(
            View::parse("DE106").unwrap().read(&devices),
            Value::Float(1.6667)
        );
        assert_eq!(View::parse("X2").unwrap().read(&devices), Value::Int(1));
        assert_eq!(
            View::parse("C231").unwrap().read(&devices),
            Value::Int(123456)
        );
        assert_eq!(View::parse("D0").unwrap().read(&devices), Value::Int(-1));
        assert!(View::parse("M0").unwrap().write(&mut devices, "2").is_err());
        assert!(
            View::parse("D0")
                .unwrap()
                .write(&mut devices, "70000")
                .is_err()
        );
        assert!(
            View::parse("C0")
                .unwrap()
                .write(&mut devices, "40000")
                .is_err()
        );
        assert!(
            View::parse("DE0")
                .unwrap()
                .write(&mut devices, "nan")
                .is_err()
        );
    }

    #[test]
    fn nth_steps_by_width() {
        assert_eq!(View::parse("D2019").unwrap().nth(1), Ok(View::Word(2020)));
        assert_eq!(
            View::parse("DD2019").unwrap().nth(1),
            Ok(View::Double(2021))
        );
        assert_eq!(
            View::parse("Y7").unwrap().nth(1).unwrap().to_string(),
            "Y10"
        );
        assert!(View::parse("D8511").unwrap().nth(1).is_err());
        assert!(View::parse("DD8509").unwrap().nth(1).is_err());
        assert!(View::parse("C255").unwrap().nth(1).is_err());
    }

    #[test]
    fn nth_past_the_end_names_the_largest_count() {
        // `--dump X0:300` used to say "X0:257 runs past", a count nobody typed.
        let message = View::parse("X0").unwrap().nth(256).unwrap_err().to_string();
        assert!(message.contains("at most 256 from X0"), "{message}");
        assert!(!message.contains("257"), "{message}");
    }

    #[test]
    fn unknown_devices_are_errors() {
        assert!(
            View::parse("Q1")
                .unwrap_err()
                .to_string()
                .contains("unknown device")
        );
        assert!(
            View::parse("D9000")
                .unwrap_err()
                .to_string()
                .contains("out of range")
        );
        assert!(View::parse("DDX").is_err());
    }
}
