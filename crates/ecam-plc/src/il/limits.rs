//! The limits of the LX3V's instruction list (those of the FX3U, which it
//! follows), checked when a program is loaded and again where an
//! instruction runs.

/// Pointers P0–P127.
pub(crate) const POINTER_COUNT: usize = 128;
/// `CJ P63` jumps to the end of the main program; P63 labels no line.
pub(crate) const END_POINTER: u8 = 63;
/// CALL nesting of the FX3U: five levels (a CALL in the main program and
/// four more inside subroutines).
pub(crate) const CALL_DEPTH: usize = 5;
/// MPS depth of the FX family.
pub(crate) const MPS_DEPTH: usize = 11;
/// Most words BMOV/FMOV move at once (FX3U: n ≤ 512).
pub(crate) const BLOCK_MAX: i32 = 512;
/// Longest SFTL/SFTR block (FX3U: n1 ≤ 1024).
pub(crate) const SHIFT_MAX: u16 = 1024;
/// What n1 and n2 of SFTL/SFTR take, in a message (1 to [`SHIFT_MAX`]).
pub(crate) const SHIFT_COUNT: &str = "a K constant 1 to 1024";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shift_message_names_the_shift_limit() {
        assert!(SHIFT_COUNT.ends_with(&format!(" {SHIFT_MAX}")));
    }
}
