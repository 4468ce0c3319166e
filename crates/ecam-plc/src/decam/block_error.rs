//! What can be wrong with a DECAM register block, mapped onto document 003's
//! codes, the error register (offset 2) and the flag bits.

use core::fmt;

use ecam_core::{CODE_PARAMETER, CODE_SECTION_COUNT, CODE_TABLE};

use super::{flags, offsets};
use crate::operation_error::OperationError;

/// A register block the cam refuses to start from (the running cam, if any,
/// keeps running unchanged).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BlockError {
    /// A register holds a value out of its range (6781).
    Parameter {
        /// Offset of the offending register in the block.
        offset: u16,
        /// What is wrong and what is allowed.
        reason: &'static str,
    },
    /// Table point `section` has a master position not greater than the
    /// point before it (6782; the error register shows `section`).
    Table {
        /// Index of the offending point.
        section: u16,
    },
    /// Offset 38 holds a point count outside 2–512, or the table does not fit
    /// in D0–D8511 (6783).
    SectionCount {
        /// The count found at offset 38.
        count: i16,
    },
}

impl BlockError {
    /// The code for D8067.
    pub const fn code(&self) -> u16 {
        match self {
            Self::Parameter { .. } => CODE_PARAMETER,
            Self::Table { .. } => CODE_TABLE,
            Self::SectionCount { .. } => CODE_SECTION_COUNT,
        }
    }

    /// What the error register (offset 2) shows: the code for parameter and
    /// count errors, the section number for a table error.
    pub const fn register_value(&self) -> u16 {
        match self {
            Self::Table { section } => *section,
            _ => self.code(),
        }
    }

    /// Flag bits 3–5 for this error.
    pub const fn flag_bits(&self) -> u16 {
        match self {
            Self::Parameter { .. } => flags::ERROR | flags::PARAMETER_ERROR,
            Self::Table { .. } | Self::SectionCount { .. } => flags::ERROR | flags::TABLE_ERROR,
        }
    }

    /// The operation error the scan reports, naming the block's registers.
    pub fn to_operation_error(&self, block: u16) -> OperationError {
        OperationError::new(
            self.code(),
            format!("DECAM block D{block}: {}", Located(self, block)),
        )
    }
}

struct Located<'a>(&'a BlockError, u16);

impl fmt::Display for Located<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let block = u32::from(self.1);
        match self.0 {
            BlockError::Parameter { offset, reason } => {
                write!(
                    f,
                    "D{} (offset {offset}) {reason}",
                    block + u32::from(*offset)
                )
            }
            BlockError::Table { section } => write!(
                f,
                "table point {section} (D{}) has a master position not greater than point {}",
                block + offsets::block_words(*section),
                section.saturating_sub(1)
            ),
            BlockError::SectionCount { count } => write!(
                f,
                "D{} holds {count} table points; allowed 2-512, and the table must fit below D8512",
                block + u32::from(offsets::SECTIONS)
            ),
        }
    }
}

impl fmt::Display for BlockError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Parameter { offset, reason } => write!(f, "offset {offset} {reason}"),
            Self::Table { section } => write!(f, "table point {section}: master not increasing"),
            Self::SectionCount { count } => write!(f, "{count} table points; allowed 2-512"),
        }
    }
}

impl std::error::Error for BlockError {}

impl From<&BlockError> for OperationError {
    fn from(e: &BlockError) -> Self {
        OperationError::new(e.code(), e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_register_shows_code_or_section() {
        assert_eq!(
            BlockError::Parameter {
                offset: 29,
                reason: "x"
            }
            .register_value(),
            6781
        );
        assert_eq!(BlockError::Table { section: 7 }.register_value(), 7);
        assert_eq!(BlockError::SectionCount { count: 0 }.register_value(), 6783);
        let e = BlockError::Table { section: 3 }.to_operation_error(2000);
        assert_eq!(e.code, 6782);
        assert!(e.message.contains("D2052"), "{}", e.message);
    }
}
