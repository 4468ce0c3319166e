//! Operation errors of instructions, reported the FX-family way.

use core::fmt;

/// An instruction that could not execute. The scan cycle writes `code` to
/// D8067 and sets M8067, as the FX family does; the E-cam instructions use
/// document 003's codes 6781 (parameter), 6782 (table out of range) and 6783
/// (number of sections out of range).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OperationError {
    /// The error code for D8067.
    pub code: u16,
    /// What went wrong, for people.
    pub message: String,
}

/// FX code for an operand whose value is out of range (e.g. a PLSY frequency).
pub const CODE_OPERAND: u16 = 6705;
/// FX code for a device number out of range at run time, including an
/// index-modified operand (`D10Z0`) whose V/Z value moves it out of range
/// (the FX3U uses this code for both).
pub const CODE_DEVICE_RANGE: u16 = 6706;

/// FX code for CALL nested deeper than the FX3U's five levels.
pub const CODE_CALL_NESTING: u16 = 6702;

impl OperationError {
    /// An error with `code` and a message.
    pub fn new(code: u16, message: impl Into<String>) -> Self {
        Self {
            code,
            message: message.into(),
        }
    }
}

impl fmt::Display for OperationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "operation error {}: {}", self.code, self.message)
    }
}

impl std::error::Error for OperationError {}
