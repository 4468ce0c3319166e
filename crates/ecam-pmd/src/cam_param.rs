//! The `SetCam`/`GetCam` parameters of document 002 and their rules.

use crate::{BufferId, PmdError};

/// Largest `CamCounts` (2^29, document 002).
pub const MAX_CAM_COUNTS: i64 = 1 << 29;

/// A cam parameter, by its document 002 enumeration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CamParam {
    /// 0: the buffer holding the table.
    CamBufferId,
    /// 1: length of the table in master counts, 2 to 2^29.
    CamCounts,
    /// 2: where in the table the cam starts, 0 to `CamCounts`.
    CamStartCount,
    /// 3: the input: bits 7:0 source axis, bits 15:8 register (0 actual, 1 commanded, 2 time).
    CamSource,
    /// 4: offset added to table values (read only).
    CamOutputOffset,
    /// 5: offset added to the input before the table lookup (read only).
    CamInputOffset,
}

impl CamParam {
    /// All parameters in enumeration order.
    pub const ALL: [CamParam; 6] = [
        Self::CamBufferId,
        Self::CamCounts,
        Self::CamStartCount,
        Self::CamSource,
        Self::CamOutputOffset,
        Self::CamInputOffset,
    ];

    /// The document's name (`CamBufferID`, `CamCounts`, …).
    pub const fn name(self) -> &'static str {
        match self {
            Self::CamBufferId => "CamBufferID",
            Self::CamCounts => "CamCounts",
            Self::CamStartCount => "CamStartCount",
            Self::CamSource => "CamSource",
            Self::CamOutputOffset => "CamOutputOffset",
            Self::CamInputOffset => "CamInputOffset",
        }
    }

    /// The document's enumeration value.
    pub const fn number(self) -> u16 {
        match self {
            Self::CamBufferId => 0,
            Self::CamCounts => 1,
            Self::CamStartCount => 2,
            Self::CamSource => 3,
            Self::CamOutputOffset => 4,
            Self::CamInputOffset => 5,
        }
    }

    /// Looks a parameter up by number (`0`…`5`) or by name (any letter case);
    /// `None` for anything else.
    pub fn parse(text: &str) -> Option<CamParam> {
        if let Ok(n) = text.parse::<u16>() {
            return Self::ALL.into_iter().find(|p| p.number() == n);
        }
        Self::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(text))
    }

    /// Whether `SetCam` may write it.
    pub const fn writable(self) -> bool {
        !matches!(self, Self::CamOutputOffset | Self::CamInputOffset)
    }
}

/// Which register of the source axis feeds the cam.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SourceRegister {
    /// 0: actual (encoder) position.
    Actual,
    /// 1: commanded position.
    Commanded,
    /// 2: the processor's time base, one count per cycle.
    Time,
}

/// A decoded `CamSource` word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CamSource {
    /// Source axis, numbered from 0.
    pub axis: u8,
    /// Source register.
    pub register: SourceRegister,
}

impl CamSource {
    /// Decodes bits 7:0 (axis) and 15:8 (register) of `word` for a processor
    /// with `axis_count` axes.
    ///
    /// # Errors
    /// [`PmdError::OutOfRange`] for bits above 15, an axis past the last one,
    /// or a register other than 0, 1 or 2.
    pub fn decode(word: i64, axis_count: u8) -> Result<Self, PmdError> {
        let bad = |allowed| PmdError::OutOfRange {
            what: "CamSource",
            value: word,
            allowed,
        };
        let word = u16::try_from(word)
            .map_err(|_| bad("bits 7:0 source axis and 15:8 register; no other bits"))?;
        let [axis, register] = word.to_le_bytes();
        if axis >= axis_count {
            return Err(bad("source axis (bits 7:0) past the last axis"));
        }
        let register = match register {
            0 => SourceRegister::Actual,
            1 => SourceRegister::Commanded,
            2 => SourceRegister::Time,
            _ => {
                return Err(bad(
                    "source register (bits 15:8) must be 0 actual, 1 commanded or 2 time",
                ));
            }
        };
        Ok(Self { axis, register })
    }

    /// The word `GetCam CamSource` returns.
    pub fn encode(self) -> i64 {
        let register: u8 = match self.register {
            SourceRegister::Actual => 0,
            SourceRegister::Commanded => 1,
            SourceRegister::Time => 2,
        };
        i64::from(u16::from_le_bytes([self.axis, register]))
    }
}

/// The cam parameters of one axis; `Default` is the document's defaults (all 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CamSettings {
    /// `CamBufferID`.
    pub buffer: BufferId,
    /// Whether `CamBufferID` was set since the axis entered cam mode
    /// (document 002: a cam cannot start before it is).
    pub buffer_defined: bool,
    /// `CamCounts`; 0 until set.
    pub counts: i64,
    /// `CamStartCount`.
    pub start_count: i64,
    /// `CamSource`.
    pub source: CamSource,
    /// `CamOutputOffset` (last computed).
    pub output_offset: i64,
    /// `CamInputOffset` (last computed).
    pub input_offset: i64,
}

impl Default for CamSettings {
    fn default() -> Self {
        Self {
            buffer: BufferId::ZERO,
            buffer_defined: false,
            counts: 0,
            start_count: 0,
            source: CamSource {
                axis: 0,
                register: SourceRegister::Actual,
            },
            output_offset: 0,
            input_offset: 0,
        }
    }
}

impl CamSettings {
    /// The value `GetCam param` returns.
    pub fn get(&self, param: CamParam) -> i64 {
        match param {
            CamParam::CamBufferId => i64::from(self.buffer.get()),
            CamParam::CamCounts => self.counts,
            CamParam::CamStartCount => self.start_count,
            CamParam::CamSource => self.source.encode(),
            CamParam::CamOutputOffset => self.output_offset,
            CamParam::CamInputOffset => self.input_offset,
        }
    }

    /// `SetCam param value`: checks, then writes; nothing changes on error.
    ///
    /// `CamStartCount` is checked against `CamCounts` when that is already
    /// set (else against 2^29); the start re-checks it.
    ///
    /// # Errors
    /// [`PmdError::ReadOnly`] for the offsets, [`PmdError::OutOfRange`] for
    /// values outside the document's ranges.
    pub fn set(&mut self, param: CamParam, value: i64, axis_count: u8) -> Result<(), PmdError> {
        match param {
            CamParam::CamBufferId => {
                self.buffer = BufferId::new(value)?;
                self.buffer_defined = true;
            }
            CamParam::CamCounts => {
                if !(2..=MAX_CAM_COUNTS).contains(&value) {
                    return Err(PmdError::OutOfRange {
                        what: "CamCounts",
                        value,
                        allowed: "2 to 2^29 (536870912) master counts",
                    });
                }
                self.counts = value;
            }
            CamParam::CamStartCount => {
                let limit = if self.counts == 0 {
                    MAX_CAM_COUNTS
                } else {
                    self.counts
                };
                if !(0..=limit).contains(&value) {
                    return Err(PmdError::OutOfRange {
                        what: "CamStartCount",
                        value,
                        allowed: "0 to CamCounts",
                    });
                }
                self.start_count = value;
            }
            CamParam::CamSource => self.source = CamSource::decode(value, axis_count)?,
            CamParam::CamOutputOffset | CamParam::CamInputOffset => {
                return Err(PmdError::ReadOnly {
                    param: param.name(),
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn parameters_by_number_and_name() {
        for p in CamParam::ALL {
            assert_eq!(CamParam::parse(&p.number().to_string()), Some(p));
            assert_eq!(CamParam::parse(p.name()), Some(p));
        }
        assert_eq!(CamParam::parse("cambufferid"), Some(CamParam::CamBufferId));
        assert_eq!(CamParam::parse("6"), None);
        assert_eq!(CamParam::parse("CamSpeed"), None);
    }

    #[test]
    fn source_word_fields() {
        let s = CamSource::decode(0x0001, 4).unwrap();
        assert_eq!(
            s,
            CamSource {
                axis: 1,
                register: SourceRegister::Actual
            }
        );
        let s = CamSource::decode(0x0203, 4).unwrap();
        assert_eq!(s.register, SourceRegister::Time);
        assert_eq!(s.encode(), 0x0203);
        assert!(CamSource::decode(0x0004, 4).is_err());
        assert!(CamSource::decode(0x0300, 4).is_err());
        assert!(CamSource::decode(0x10000, 4).is_err());
        assert!(CamSource::decode(-1, 4).is_err());
    }

    #[test]
    fn ranges_and_defaults() {
        let mut s = CamSettings::default();
        for p in CamParam::ALL {
            assert_eq!(s.get(p), 0);
        }
        assert!(s.set(CamParam::CamCounts, 1, 4).is_err());
        assert!(s.set(CamParam::CamCounts, MAX_CAM_COUNTS + 1, 4).is_err());
        s.set(CamParam::CamCounts, MAX_CAM_COUNTS, 4).unwrap();
        s.set(CamParam::CamCounts, 2, 4).unwrap();
        assert!(s.set(CamParam::CamStartCount, 3, 4).is_err());
        s.set(CamParam::CamStartCount, 2, 4).unwrap();
        assert!(s.set(CamParam::CamStartCount, -1, 4).is_err());
        assert_eq!(
            s.set(CamParam::CamOutputOffset, 5, 4),
            Err(PmdError::ReadOnly {
                param: "CamOutputOffset"
            })
        );
        let before = s;
        assert!(s.set(CamParam::CamBufferId, 99, 4).is_err());
        assert_eq!(s, before);
    }
}
