//! Zoom (document 003 registers 23/24 and 29/30): exact ratios, never floats.
//!
//! A zoom scales the master before it enters the table, or the table value
//! before it reaches the output. Both are kept as numerator/denominator so
//! that a cam running for a year drifts by nothing.
//!
//! The document's registers hold positive ratios only ([`Zoom::new`]).
//! PLCopen's `MasterScaling` and `SlaveScaling` are signed
//! ([`Zoom::signed`]): a negative slave zoom mirrors the cam (slave =
//! −table × |zoom|), a negative master zoom runs the profile backwards
//! (table input = −|zoom| × master: the master moving forwards walks the
//! table from its end towards its start).

use core::num::NonZeroU16;

use crate::EngineError;

/// An exact ratio `±num / den`, each of `num` and `den` between 1 and
/// 65535.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Zoom {
    num: NonZeroU16,
    den: NonZeroU16,
    negative: bool,
}

impl Zoom {
    /// No scaling: 1/1.
    pub const ONE: Zoom = Zoom {
        num: NonZeroU16::MIN,
        den: NonZeroU16::MIN,
        negative: false,
    };

    /// The ratio `num / den`.
    ///
    /// # Errors
    /// [`EngineError::BadZoom`] when either is zero (document 003 allows 1–65535).
    pub const fn new(num: u16, den: u16) -> Result<Zoom, EngineError> {
        match (NonZeroU16::new(num), NonZeroU16::new(den)) {
            (Some(num), Some(den)) => Ok(Zoom {
                num,
                den,
                negative: false,
            }),
            _ => Err(EngineError::BadZoom),
        }
    }

    /// The signed ratio `num / den` (PLCopen scalings): `|num|` and `den`
    /// between 1 and 65535. See the module documentation for what a
    /// negative master or slave zoom does.
    ///
    /// # Errors
    /// [`EngineError::BadZoom`] when `num` is 0 or beyond ±65535, or `den`
    /// is 0.
    pub const fn signed(num: i32, den: u16) -> Result<Zoom, EngineError> {
        let magnitude = num.unsigned_abs();
        if magnitude > u16::MAX as u32 {
            return Err(EngineError::BadZoom);
        }
        match Zoom::new(magnitude as u16, den) {
            Ok(zoom) => Ok(Zoom {
                negative: num < 0,
                ..zoom
            }),
            Err(e) => Err(e),
        }
    }

    /// The numerator's magnitude (see [`Zoom::signed_num`] for its sign).
    pub const fn num(self) -> u16 {
        self.num.get()
    }

    /// The numerator with its sign.
    pub const fn signed_num(self) -> i32 {
        if self.negative {
            -(self.num.get() as i32)
        } else {
            self.num.get() as i32
        }
    }

    /// The ratio is negative.
    pub const fn is_negative(self) -> bool {
        self.negative
    }

    /// The reciprocal `den / num`, sign kept.
    pub const fn reciprocal(self) -> Zoom {
        Zoom {
            num: self.den,
            den: self.num,
            negative: self.negative,
        }
    }

    /// The denominator.
    pub const fn den(self) -> u16 {
        self.den.get()
    }

    /// The ratio as a float (for velocity ratios only, never for positions).
    pub fn ratio(self) -> f64 {
        f64::from(self.signed_num()) / f64::from(self.den())
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

    #[test]
    fn signed_zooms() {
        let z = Zoom::signed(-3, 2).unwrap_or(Zoom::ONE);
        assert_eq!((z.num(), z.signed_num(), z.den()), (3, -3, 2));
        assert!(z.is_negative());
        assert_eq!(z.ratio(), -1.5);
        assert_eq!(z.reciprocal().ratio(), -2.0 / 3.0);
        assert_eq!(Zoom::signed(0, 1), Err(EngineError::BadZoom));
        assert_eq!(Zoom::signed(-65_536, 1), Err(EngineError::BadZoom));
        assert_eq!(Zoom::signed(65_535, 1), Zoom::new(65_535, 1));
    }
}
