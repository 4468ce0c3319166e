//! The index registers V0–V7 and Z0–Z7 of the FX3U (which the LX3V
//! follows): 16 bits each, and in a 32-bit instruction `Zn` names the pair
//! Vn (high word) : Zn (low word).

/// An index register V0–V7 or Z0–Z7 (16 bits each; Vn:Zn pair as 32 bits).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IndexReg {
    /// Vn, n = 0–7.
    V(u8),
    /// Zn, n = 0–7.
    Z(u8),
}

/// Number of V (and of Z) registers: V0–V7, Z0–Z7.
pub const INDEX_COUNT: u8 = 8;

impl IndexReg {
    /// The register number n of Vn/Zn.
    pub fn number(self) -> u8 {
        match self {
            Self::V(n) | Self::Z(n) => n,
        }
    }
}

impl core::fmt::Display for IndexReg {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::V(n) => write!(f, "V{n}"),
            Self::Z(n) => write!(f, "Z{n}"),
        }
    }
}
