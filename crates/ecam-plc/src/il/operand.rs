//! Operand tokens: devices (`D100`, `X17`, `C231`), constants (`K-5`, `H1F`)
//! and float constants (`E1.6667`).

use super::instruction::{GroupKind, INDEX_COUNT, IndexReg, WordBit, WordGroup};
use crate::devices::{Device, DeviceError};

/// A lexed operand before the instruction checks its kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Operand {
    /// A device.
    Device(Device),
    /// Timer Tn: its contact, its current value, or its coil.
    Timer(u16),
    /// A bit of a data register, `Dn.b`.
    WordBit(WordBit),
    /// K constant (decimal).
    Decimal(i64),
    /// H constant (hexadecimal bit pattern).
    Hex(u64),
    /// E constant.
    Float(f32),
    /// A word group `KnM`/`KnX`/`KnY`.
    Group(WordGroup),
    /// An index register `Vn`/`Zn` itself.
    Index(IndexReg),
    /// An operand modified by an index register: `D10V0`, `K4M0Z1`, `K10Z0`.
    Indexed(Modified, IndexReg),
}

/// The part of an index-modified operand before its modifier.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Modified {
    /// A device D, M, X, Y or C.
    Device(Device),
    /// Timer Tn (current value, or contact).
    Timer(u16),
    /// K constant.
    Decimal(i64),
    /// H constant.
    Hex(u64),
    /// Word group.
    Group(WordGroup),
}

impl Operand {
    /// Parses one token; the message says what was expected.
    pub(crate) fn parse(token: &str) -> Result<Self, String> {
        let upper = token.to_ascii_uppercase();
        if let Some(register) = Self::index_register(token, &upper) {
            return register.map(Self::Index);
        }
        if let Some((word, bit)) = upper.split_once('.') {
            if index_suffix(word).is_some() {
                return Err(format!(
                    "`{token}`: a bit of an index-modified register is not allowed (the FX refuses Dn.b with V/Z); use D(n+offset).b or a word group"
                ));
            }
            if word.starts_with(['D', 'M', 'X', 'Y', 'C']) {
                return Self::word_bit(token, word, bit);
            }
        }
        if let Some((base, by)) = index_suffix(&upper) {
            return Self::modified(token, base, by);
        }
        Self::plain(token, &upper)
    }

    /// `Vn`/`Zn` standing alone: `None` when the token is not shaped so.
    fn index_register(token: &str, upper: &str) -> Option<Result<IndexReg, String>> {
        let (kind, digits) = match upper.split_at_checked(1)? {
            ("V", d) => (IndexReg::V as fn(u8) -> IndexReg, d),
            ("Z", d) => (IndexReg::Z as fn(u8) -> IndexReg, d),
            _ => return None,
        };
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        Some(
            digits
                .parse::<u8>()
                .ok()
                .filter(|n| *n < INDEX_COUNT)
                .map(kind)
                .ok_or_else(|| {
                    format!(
                        "index register `{token}` is out of range (V0-V7, Z0-Z7)",
                        token = ecam_core::excerpt::excerpt(token)
                    )
                }),
        )
    }

    /// `D10V0`: checks what an index register may modify.
    fn modified(token: &str, base: &str, by: &str) -> Result<Self, String> {
        let by = match Self::index_register(by, by) {
            Some(Ok(reg)) => reg,
            Some(Err(m)) => {
                return Err(format!(
                    "`{token}`: {m}",
                    token = ecam_core::excerpt::excerpt(token)
                ));
            }
            None => {
                return Err(format!(
                    "`{token}`: the modifier must be an index register V0-V7 or Z0-Z7"
                ));
            }
        };
        if index_suffix(base).is_some() {
            return Err(format!(
                "`{token}`: an operand takes one index modifier; an index register cannot modify {base}"
            ));
        }
        let modified = match Self::plain(token, base)? {
            Self::Device(d) => Modified::Device(d),
            Self::Timer(n) => Modified::Timer(n),
            Self::Decimal(v) => Modified::Decimal(v),
            Self::Hex(v) => Modified::Hex(v),
            Self::Group(g) => Modified::Group(g),
            Self::Float(_) => {
                return Err(format!(
                    "`{token}`: an E constant cannot be index-modified (K and H constants can)"
                ));
            }
            Self::Index(_) | Self::Indexed(..) | Self::WordBit(_) => {
                return Err(format!(
                    "`{token}`: an index register cannot modify {base} (the FX modifies D, C, T, X, Y, M, word groups and K/H constants)"
                ));
            }
        };
        Ok(Self::Indexed(modified, by))
    }

    /// An operand without index modifier.
    fn plain(token: &str, upper: &str) -> Result<Self, String> {
        if Self::index_register(upper, upper).is_some() {
            return Err(format!(
                "`{token}`: an index register cannot be index-modified"
            ));
        }
        if let Some(group) = Self::group(token, upper) {
            return group;
        }
        let mut chars = upper.chars();
        let prefix = chars.next().unwrap_or(' ');
        let rest = chars.as_str();
        match prefix {
            'K' => rest
                .parse::<i64>()
                .map(Self::Decimal)
                .map_err(|_| format!("`{token}` is not a K constant (expected K and a decimal integer, e.g. K100)", token = ecam_core::excerpt::excerpt(token))),
            'H' => u64::from_str_radix(rest, 16)
                .ok()
                .filter(|_| !rest.starts_with('+'))
                .map(Self::Hex)
                .ok_or_else(|| format!("`{token}` is not an H constant (expected H and hex digits, e.g. H1F)", token = ecam_core::excerpt::excerpt(token))),
            'T' if !rest.is_empty() && rest.bytes().all(|b| b.is_ascii_digit()) => rest
                .parse::<u16>()
                .ok()
                .filter(|n| *n < crate::timers::T_COUNT)
                .map(Self::Timer)
                .ok_or_else(|| format!("device `{token}` is out of range (timers T0-T255)", token = ecam_core::excerpt::excerpt(token))),
            'E' => rest
                .parse::<f32>()
                .ok()
                .filter(|v| v.is_finite())
                .map(Self::Float)
                .ok_or_else(|| format!("`{token}` is not an E constant (expected E and a finite decimal number, e.g. E1.6667)", token = ecam_core::excerpt::excerpt(token))),
            _ => Device::parse(upper).map(Self::Device).map_err(|err| match err {
                DeviceError::OutOfRange => format!("device `{token}` is out of range (D0-D8511, M0-M8511, X0-X377 and Y0-Y377 octal, C0-C255)", token = ecam_core::excerpt::excerpt(token)),
                _ => format!("unknown device `{token}` (expected D, M, X, Y, C, T and a number, X/Y in octal, or a K/H/E constant)", token = ecam_core::excerpt::excerpt(token)),
            }),
        }
    }

    /// `Dn.b`: only data registers have addressable bits here, and b is one
    /// hex digit 0–F as in the FX3 programming manual.
    fn word_bit(token: &str, word: &str, bit: &str) -> Result<Self, String> {
        let register = match Device::parse(word) {
            Ok(Device::D(n)) => n,
            Ok(_) => {
                return Err(format!(
                    "`{token}`: only data registers D have addressable bits (Dn.b, b = 0-F)"
                ));
            }
            Err(DeviceError::OutOfRange) => {
                return Err(format!(
                    "device `{token}` is out of range (D0-D8511)",
                    token = ecam_core::excerpt::excerpt(token)
                ));
            }
            Err(_) => {
                return Err(format!(
                    "`{token}` is not a bit of a word (expected Dn.b with b = 0-F, e.g. D2001.0)"
                ));
            }
        };
        let bit = match bit.as_bytes() {
            [digit] => char::from(*digit).to_digit(16),
            _ => None,
        }
        .ok_or_else(|| {
            format!(
                "`{token}`: the bit number must be one hex digit 0-F (e.g. D2001.F)",
                token = ecam_core::excerpt::excerpt(token)
            )
        })?;
        Ok(Self::WordBit(WordBit {
            register,
            bit: bit as u8,
        }))
    }

    /// `Kn` followed by an X, Y or M device: a word group (`None` when the
    /// token is not shaped so, e.g. a K constant).
    fn group(token: &str, upper: &str) -> Option<Result<Self, String>> {
        let rest = upper.strip_prefix('K')?;
        let digit = rest.bytes().next().filter(u8::is_ascii_digit)?;
        let device = rest.get(1..)?;
        if !device.starts_with(['X', 'Y', 'M']) {
            return None;
        }
        let digits = digit - b'0';
        if !(1..=8).contains(&digits) {
            return Some(Err(format!(
                "`{token}`: a word group has 1 to 8 digits (K1M0 to K8M0)"
            )));
        }
        let (kind, first, count) = match Device::parse(device) {
            Ok(Device::X(n)) => (GroupKind::X, n, crate::devices::XY_COUNT),
            Ok(Device::Y(n)) => (GroupKind::Y, n, crate::devices::XY_COUNT),
            Ok(Device::M(n)) => (GroupKind::M, n, crate::devices::M_COUNT),
            _ => {
                return Some(Err(format!(
                    "`{token}` is not a word group (expected Kn and an X, Y or M device, e.g. K4M0)"
                )));
            }
        };
        if u32::from(first) + 4 * u32::from(digits) > u32::from(count) {
            return Some(Err(format!(
                "word group `{token}` runs past the last {} device",
                device.get(..1).unwrap_or("")
            )));
        }
        Some(Ok(Self::Group(WordGroup {
            kind,
            first,
            digits,
        })))
    }

    /// How the operand reads in messages.
    pub(crate) fn describe(&self) -> String {
        match self {
            Self::Device(d) => d.to_string(),
            Self::WordBit(b) => b.to_string(),
            Self::Timer(n) => format!("T{n}"),
            Self::Decimal(v) => format!("K{v}"),
            Self::Hex(v) => format!("H{v:X}"),
            Self::Float(v) => format!("E{v}"),
            Self::Group(g) => g.to_string(),
            Self::Index(r) => r.to_string(),
            Self::Indexed(base, by) => {
                let base = match base {
                    Modified::Device(d) => d.to_string(),
                    Modified::Timer(n) => format!("T{n}"),
                    Modified::Decimal(v) => format!("K{v}"),
                    Modified::Hex(v) => format!("H{v:X}"),
                    Modified::Group(g) => g.to_string(),
                };
                format!("{base}{by}")
            }
        }
    }
}

/// Splits `D10V0` into (`D10`, `V0`) when the token ends with an index
/// modifier: V or Z and digits after a base that is not empty. `V0` alone
/// is no modifier; neither is anything without digits before the V/Z.
fn index_suffix(upper: &str) -> Option<(&str, &str)> {
    let at = upper.rfind(['V', 'Z'])?;
    let (base, by) = upper.split_at(at);
    let digits = by.get(1..)?;
    let base_ends_in_digit = base.bytes().last().is_some_and(|b| b.is_ascii_hexdigit());
    (at > 0
        && base_ends_in_digit
        && !digits.is_empty()
        && digits.bytes().all(|b| b.is_ascii_digit()))
    .then_some((base, by))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_constants_and_devices() {
        assert_eq!(Operand::parse("K-5"), Ok(Operand::Decimal(-5)));
        assert_eq!(Operand::parse("hff"), Ok(Operand::Hex(255)));
        assert_eq!(Operand::parse("E1.6667"), Ok(Operand::Float(1.6667)));
        assert_eq!(Operand::parse("x17"), Ok(Operand::Device(Device::X(15))));
        assert!(Operand::parse("Q1").unwrap_err().contains("unknown device"));
        assert!(
            Operand::parse("D9000")
                .unwrap_err()
                .contains("out of range")
        );
        assert!(Operand::parse("K1.5").is_err());
        assert!(Operand::parse("H+1").is_err());
        assert!(Operand::parse("Einf").is_err());
        assert!(Operand::parse("X8").unwrap_err().contains("unknown device"));
        assert_eq!(
            Operand::parse("d2001.f"),
            Ok(Operand::WordBit(WordBit {
                register: 2001,
                bit: 15
            }))
        );
        assert!(
            Operand::parse("D0.G")
                .unwrap_err()
                .contains("one hex digit")
        );
        assert!(
            Operand::parse("D0.10")
                .unwrap_err()
                .contains("one hex digit")
        );
        assert!(Operand::parse("D0.").unwrap_err().contains("one hex digit"));
        assert!(
            Operand::parse("M0.1")
                .unwrap_err()
                .contains("only data registers")
        );
        assert!(
            Operand::parse("D8512.0")
                .unwrap_err()
                .contains("out of range")
        );
        assert!(
            Operand::parse("D.1")
                .unwrap_err()
                .contains("not a bit of a word")
        );
    }
}
