//! Operand tokens: devices (`D100`, `X17`, `C231`), constants (`K-5`, `H1F`)
//! and float constants (`E1.6667`).

use super::instruction::{GroupKind, WordBit, WordGroup};
use crate::device::{Device, DeviceError};
use crate::il::error::TokenError;
use crate::index_register::{INDEX_COUNT, IndexReg};

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
    pub(crate) fn parse(token: &str) -> Result<Self, TokenError> {
        let upper = token.to_ascii_uppercase();
        if let Some(register) = Self::index_register(token, &upper) {
            return register.map(Self::Index);
        }
        if let Some((word, bit)) = upper.split_once('.') {
            if index_suffix(word).is_some() {
                return Err(TokenError::BitOfIndexed(token.to_string()));
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
    fn index_register(token: &str, upper: &str) -> Option<Result<IndexReg, TokenError>> {
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
                .ok_or_else(|| TokenError::IndexRegisterRange(token.to_string())),
        )
    }

    /// `D10V0`: checks what an index register may modify.
    fn modified(token: &str, base: &str, by: &str) -> Result<Self, TokenError> {
        let by = match Self::index_register(by, by) {
            Some(Ok(reg)) => reg,
            Some(Err(_)) => {
                return Err(TokenError::ModifierRange {
                    token: token.to_string(),
                    by: by.to_string(),
                });
            }
            None => return Err(TokenError::NotModifier(token.to_string())),
        };
        if index_suffix(base).is_some() {
            return Err(TokenError::TwoModifiers {
                token: token.to_string(),
                base: base.to_string(),
            });
        }
        let modified = match Self::plain(token, base)? {
            Self::Device(d) => Modified::Device(d),
            Self::Timer(n) => Modified::Timer(n),
            Self::Decimal(v) => Modified::Decimal(v),
            Self::Hex(v) => Modified::Hex(v),
            Self::Group(g) => Modified::Group(g),
            Self::Float(_) => return Err(TokenError::FloatModified(token.to_string())),
            Self::Index(_) | Self::Indexed(..) | Self::WordBit(_) => {
                return Err(TokenError::CannotModify {
                    token: token.to_string(),
                    base: base.to_string(),
                });
            }
        };
        Ok(Self::Indexed(modified, by))
    }

    /// An operand without index modifier.
    fn plain(token: &str, upper: &str) -> Result<Self, TokenError> {
        if Self::index_register(upper, upper).is_some() {
            return Err(TokenError::IndexRegisterModified(token.to_string()));
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
                .map_err(|_| TokenError::NotK(token.to_string())),
            'H' => u64::from_str_radix(rest, 16)
                .ok()
                .filter(|_| !rest.starts_with('+'))
                .map(Self::Hex)
                .ok_or_else(|| TokenError::NotH(token.to_string())),
            'T' if !rest.is_empty() && rest.bytes().all(|b| b.is_ascii_digit()) => rest
                .parse::<u16>()
                .ok()
                .filter(|n| *n < crate::timers::T_COUNT)
                .map(Self::Timer)
                .ok_or_else(|| TokenError::TimerRange(token.to_string())),
            'E' => rest
                .parse::<f32>()
                .ok()
                .filter(|v| v.is_finite())
                .map(Self::Float)
                .ok_or_else(|| TokenError::NotE(token.to_string())),
            _ => Device::parse(upper)
                .map(Self::Device)
                .map_err(|err| match err {
                    DeviceError::OutOfRange => TokenError::DeviceRange(token.to_string()),
                    _ => TokenError::UnknownDevice(token.to_string()),
                }),
        }
    }

    /// `Dn.b`: only data registers have addressable bits here, and b is one
    /// hex digit 0–F as in the FX3 programming manual.
    fn word_bit(token: &str, word: &str, bit: &str) -> Result<Self, TokenError> {
        let register = match Device::parse(word) {
            Ok(Device::D(n)) => n,
            Ok(_) => return Err(TokenError::BitOfNonRegister(token.to_string())),
            Err(DeviceError::OutOfRange) => {
                return Err(TokenError::WordBitRange(token.to_string()));
            }
            Err(_) => return Err(TokenError::NotWordBit(token.to_string())),
        };
        let bit = match bit.as_bytes() {
            [digit] => char::from(*digit).to_digit(16),
            _ => None,
        }
        .ok_or_else(|| TokenError::BitNumber(token.to_string()))?;
        Ok(Self::WordBit(WordBit {
            register,
            bit: bit as u8,
        }))
    }

    /// `Kn` followed by an X, Y or M device: a word group (`None` when the
    /// token is not shaped so, e.g. a K constant).
    fn group(token: &str, upper: &str) -> Option<Result<Self, TokenError>> {
        let rest = upper.strip_prefix('K')?;
        let digit = rest.bytes().next().filter(u8::is_ascii_digit)?;
        let device = rest.get(1..)?;
        if !device.starts_with(['X', 'Y', 'M']) {
            return None;
        }
        let digits = digit - b'0';
        if !(1..=8).contains(&digits) {
            return Some(Err(TokenError::GroupDigits(token.to_string())));
        }
        let (kind, first, count) = match Device::parse(device) {
            Ok(Device::X(n)) => (GroupKind::X, n, crate::device::XY_COUNT),
            Ok(Device::Y(n)) => (GroupKind::Y, n, crate::device::XY_COUNT),
            Ok(Device::M(n)) => (GroupKind::M, n, crate::device::M_COUNT),
            _ => return Some(Err(TokenError::NotGroup(token.to_string()))),
        };
        if u32::from(first) + 4 * u32::from(digits) > u32::from(count) {
            return Some(Err(TokenError::GroupPastEnd {
                token: token.to_string(),
                kind: device.get(..1).unwrap_or("").to_string(),
            }));
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
        assert!(
            Operand::parse("Q1")
                .unwrap_err()
                .to_string()
                .contains("unknown device")
        );
        assert!(
            Operand::parse("D9000")
                .unwrap_err()
                .to_string()
                .contains("out of range")
        );
        assert!(Operand::parse("K1.5").is_err());
        assert!(Operand::parse("H+1").is_err());
        assert!(Operand::parse("Einf").is_err());
        assert!(
            Operand::parse("X8")
                .unwrap_err()
                .to_string()
                .contains("unknown device")
        );
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
                .to_string()
                .contains("one hex digit")
        );
        assert!(
            Operand::parse("D0.10")
                .unwrap_err()
                .to_string()
                .contains("one hex digit")
        );
        assert!(
            Operand::parse("D0.")
                .unwrap_err()
                .to_string()
                .contains("one hex digit")
        );
        assert!(
            Operand::parse("M0.1")
                .unwrap_err()
                .to_string()
                .contains("only data registers")
        );
        assert!(
            Operand::parse("D8512.0")
                .unwrap_err()
                .to_string()
                .contains("out of range")
        );
        assert!(
            Operand::parse("D.1")
                .unwrap_err()
                .to_string()
                .contains("not a bit of a word")
        );
    }
}
