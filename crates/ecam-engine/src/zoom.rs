//! Zoom (document 003 registers 23/24 and 29/30): exact ratios, never floats.
//!
//! A zoom scales the master before it enters the table, or the table value
//! before it reaches the output. Both are kept as numerator/denominator so
//! that a cam running for a year drifts by nothing.

use core::num::NonZeroU16;

use crate::EngineError;

/// An exact ratio `num / den`, each between 1 and 65535.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Zoom {
    num: NonZeroU16,
    den: NonZeroU16,
}

impl Zoom {
    /// No scaling: 1/1.
    pub const ONE: Zoom = Zoom {
        num: NonZeroU16::MIN,
        den: NonZeroU16::MIN,
    };

    /// The ratio `num / den`.
    ///
    /// # Errors
    /// [`EngineError::BadZoom`] when either is zero (document 003 allows 1–65535).
    pub const fn new(num: u16, den: u16) -> Result<Zoom, EngineError> {
        match (NonZeroU16::new(num), NonZeroU16::new(den)) {
            (Some(num), Some(den)) => Ok(Zoom { num, den }),
            _ => Err(EngineError::BadZoom),
        }
    }

    /// The numerator.
    pub const fn num(self) -> u16 {
        self.num.get()
    }

    /// The denominator.
    pub const fn den(self) -> u16 {
        self.den.get()
    }

    /// The ratio as a float (for velocity ratios only, never for positions).
    pub fn ratio(self) -> f64 {
        f64::from(self.num()) / f64::from(self.den())
    }
}

impl Default for Zoom {
    fn default() -> Self {
        Self::ONE
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_is_refused() {
        assert_eq!(Zoom::new(0, 3), Err(EngineError::BadZoom));
        assert_eq!(Zoom::new(3, 0), Err(EngineError::BadZoom));
        let z = Zoom::new(7, 3).unwrap_or(Zoom::ONE);
        assert_eq!((z.num(), z.den()), (7, 3));
        assert_eq!(Zoom::ONE.ratio(), 1.0);
    }
}
