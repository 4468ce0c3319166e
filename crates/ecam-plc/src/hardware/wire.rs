//! `--wire Yn:Xm`: a pulse output wired to a counter input.

use core::fmt;

use super::counter::counters_on_input;
use crate::device::Device;

/// A wire from pulse output Yn (0..=3) to input Xm that feeds a high-speed counter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Wire {
    output: u8,
    input: u16,
}

/// Why a wire cannot be made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WireError(String);

impl fmt::Display for WireError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for WireError {}

impl Wire {
    /// A wire from Y`output` to X`input`.
    ///
    /// # Errors
    /// When `output` is not 0..=3 or no supported high-speed counter counts X`input`.
    pub fn new(output: u8, input: u16) -> Result<Self, WireError> {
        if output > 3 {
            return Err(WireError(format!(
                "Y{output:o} is not a pulse output (expected Y0-Y3)"
            )));
        }
        if counters_on_input(input).next().is_none() {
            return Err(WireError(format!(
                "no high-speed counter counts X{input:o} (expected X0-X5: C231/C235 on X0, C236-C240 on X1-X5)"
            )));
        }
        Ok(Self { output, input })
    }

    /// Parses `Y1:X0`.
    ///
    /// # Errors
    /// A malformed text, or what [`Wire::new`] refuses.
    ///
    /// ```
    /// let wire = ecam_plc::Wire::parse("Y1:X0").unwrap();
    /// assert_eq!((wire.output(), wire.input()), (1, 0));
    /// assert!(ecam_plc::Wire::parse("Y1-X0").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Self, WireError> {
        let malformed = || {
            WireError(format!(
                "`{text}` is not a wire (expected Yn:Xm, e.g. Y1:X0)"
            ))
        };
        let (from, to) = text.split_once(':').ok_or_else(malformed)?;
        match (Device::parse(from), Device::parse(to)) {
            (Ok(Device::Y(y)), Ok(Device::X(x))) => {
                Self::new(u8::try_from(y).unwrap_or(u8::MAX), x)
            }
            _ => Err(malformed()),
        }
    }

    /// Pulse output number (0..=3).
    pub fn output(&self) -> u8 {
        self.output
    }

    /// Input number (decimal index of the octal X name).
    pub fn input(&self) -> u16 {
        self.input
    }
}
