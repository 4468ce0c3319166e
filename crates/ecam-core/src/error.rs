//! What can be wrong with a cam table or a generator's parameters.
//!
//! The PLC manual (document 003) defines three operation error codes for its
//! E-cam instructions; every variant maps onto one of them through
//! [`TableError::code`], so the PLC face can report them the FX-family way.

use core::fmt;

/// PLC code 6781: parameter error.
pub const CODE_PARAMETER: u16 = 6781;
/// PLC code 6782: the table is out of range (a section is bad).
pub const CODE_TABLE: u16 = 6782;
/// PLC code 6783: the number of sections is out of range.
pub const CODE_SECTION_COUNT: u16 = 6783;

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
    /// The document 003 error code for this error.
    pub const fn code(&self) -> u16 {
        match self {
            Self::Parameter { .. } | Self::Infeasible { .. } => CODE_PARAMETER,
            Self::MasterNotIncreasing { .. } | Self::ValueOutOfRange { .. } => CODE_TABLE,
            Self::SectionCount { .. } => CODE_SECTION_COUNT,
        }
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
        match self {
            Self::Parameter { name, reason } => {
                write!(f, "parameter error ({CODE_PARAMETER}): {name} {reason}")
            }
            Self::MasterNotIncreasing { section } => write!(
                f,
                "table error ({CODE_TABLE}) at section {section}: master position must be greater than the previous section's"
            ),
            Self::ValueOutOfRange { section } => write!(
                f,
                "table error ({CODE_TABLE}) at section {section}: value is not finite or out of range"
            ),
            // The Rust API has no upper limit (`max == usize::MAX`); printing
            // that number would read as noise rather than as "no limit".
            Self::SectionCount { count, min, max } if *max == usize::MAX => write!(
                f,
                "section count error ({CODE_SECTION_COUNT}): {count} sections, at least {min} needed"
            ),
            Self::SectionCount { count, min, max } => write!(
                f,
                "section count error ({CODE_SECTION_COUNT}): {count} sections, allowed {min} to {max}"
            ),
            Self::Infeasible { reason } => {
                write!(
                    f,
                    "parameter error ({CODE_PARAMETER}): cannot generate: {reason}"
                )
            }
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
}
