//! What can be wrong with a cam table or a generator's parameters.
//!
//! The PLC manual (document 003) defines three operation error codes for its
//! E-cam instructions ([`CamErrorCode`]); every variant maps onto one of them
//! through [`TableError::kind`], so the PLC face can report them the
//! FX-family way.

use core::fmt;

/// The operation errors document 003 gives its E-cam instructions (`DECAM`,
/// `ECAMTBX`), by the codes the PLC shows (D8067, a DECAM block's error
/// register, ECAMTBX's negated result).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CamErrorCode {
    /// 6781: a parameter is out of range.
    Parameter,
    /// 6782: the table ("form") is out of range: a point is bad.
    Table,
    /// 6783: the number of points ("cams", sections) is out of range.
    SectionCount,
}

impl CamErrorCode {
    /// The number the PLC shows: 6781, 6782 or 6783.
    pub const fn number(self) -> u16 {
        match self {
            Self::Parameter => 6781,
            Self::Table => 6782,
            Self::SectionCount => 6783,
        }
    }
}

impl fmt::Display for CamErrorCode {
    /// `parameter error (6781)`, `table error (6782)`, `section count error (6783)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self {
            Self::Parameter => "parameter error",
            Self::Table => "table error",
            Self::SectionCount => "section count error",
        };
        write!(f, "{what} ({})", self.number())
    }
}

/// PLC code 6781: parameter error ([`CamErrorCode::Parameter`]).
pub const CODE_PARAMETER: u16 = CamErrorCode::Parameter.number();
/// PLC code 6782: the table is out of range ([`CamErrorCode::Table`]).
pub const CODE_TABLE: u16 = CamErrorCode::Table.number();
/// PLC code 6783: the number of sections is out of range
/// ([`CamErrorCode::SectionCount`]).
pub const CODE_SECTION_COUNT: u16 = CamErrorCode::SectionCount.number();

/// An invalid cam table or generator input.
#[derive(Clone, Debug, PartialEq)]
pub enum TableError {
    /// A parameter is out of its allowed range (code 6781).
    Parameter {
        /// Which parameter, as a user would name it.
        name: &'static str,
        /// Why it was refused, e.g. "must be between 10 and 512".
        reason: &'static str,
    },
    /// The master position of `section` is not greater than the one before it
    /// (code 6782; the section number goes to the error register).
    MasterNotIncreasing {
        /// Index of the offending section (point).
        section: usize,
    },
    /// A value of `section` is not a finite number or does not fit the target
    /// representation (code 6782).
    ValueOutOfRange {
        /// Index of the offending section (point).
        section: usize,
    },
    /// The table has too few or too many sections (code 6783).
    SectionCount {
        /// How many sections were given.
        count: usize,
        /// Fewest allowed.
        min: usize,
        /// Most allowed.
        max: usize,
    },
    /// The requested motion cannot be made within the given limits, e.g. a
    /// rotary cut whose velocity ratio would exceed the maximum (code 6781).
    Infeasible {
        /// What could not be met.
        reason: &'static str,
    },
}

impl TableError {
    /// The document 003 operation error this is.
    pub const fn kind(&self) -> CamErrorCode {
        match self {
            Self::Parameter { .. } | Self::Infeasible { .. } => CamErrorCode::Parameter,
            Self::MasterNotIncreasing { .. } | Self::ValueOutOfRange { .. } => CamErrorCode::Table,
            Self::SectionCount { .. } => CamErrorCode::SectionCount,
        }
    }

    /// The document 003 error code for this error ([`Self::kind`]'s number).
    pub const fn code(&self) -> u16 {
        self.kind().number()
    }

    /// The section number the PLC's error register shows, where there is one.
    pub const fn section(&self) -> Option<usize> {
        match self {
            Self::MasterNotIncreasing { section } | Self::ValueOutOfRange { section } => {
                Some(*section)
            }
            _ => None,
        }
    }
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = self.kind();
        match self {
            Self::Parameter { name, reason } => write!(f, "{kind}: {name} {reason}"),
            Self::MasterNotIncreasing { section } => write!(
                f,
                "{kind} at section {section}: master position must be greater than the previous section's"
            ),
            Self::ValueOutOfRange { section } => write!(
                f,
                "{kind} at section {section}: value is not finite or out of range"
            ),
            // The Rust API has no upper limit (`max == usize::MAX`); printing
            // that number would read as noise rather than as "no limit".
            Self::SectionCount { count, min, max } if *max == usize::MAX => {
                write!(f, "{kind}: {count} sections, at least {min} needed")
            }
            Self::SectionCount { count, min, max } => {
                write!(f, "{kind}: {count} sections, allowed {min} to {max}")
            }
            Self::Infeasible { reason } => write!(f, "{kind}: cannot generate: {reason}"),
        }
    }
}

impl core::error::Error for TableError {}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    #[test]
    fn an_unbounded_section_count_says_what_is_needed() {
        let e = TableError::SectionCount {
            count: 1,
            min: 2,
            max: usize::MAX,
        };
        let text = e.to_string();
        assert!(text.contains("at least 2"), "{text}");
        assert!(!text.contains(&usize::MAX.to_string()), "{text}");
        let bounded = TableError::SectionCount {
            count: 600,
            min: 2,
            max: 512,
        };
        assert!(bounded.to_string().contains("allowed 2 to 512"));
    }

    #[test]
    fn the_codes_are_the_manuals_and_say_what_they_are() {
        assert_eq!(
            [CODE_PARAMETER, CODE_TABLE, CODE_SECTION_COUNT],
            [6781, 6782, 6783]
        );
        assert_eq!(
            CamErrorCode::Parameter.to_string(),
            "parameter error (6781)"
        );
        assert_eq!(CamErrorCode::Table.to_string(), "table error (6782)");
        assert_eq!(
            CamErrorCode::SectionCount.to_string(),
            "section count error (6783)"
        );
        let e = TableError::MasterNotIncreasing { section: 4 };
        assert_eq!((e.kind(), e.code()), (CamErrorCode::Table, 6782));
        assert!(
            e.to_string()
                .starts_with("table error (6782) at section 4:")
        );
    }
}
