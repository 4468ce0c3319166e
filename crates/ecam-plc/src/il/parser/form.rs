//! An applied instruction's mnemonic split into its forms: `DMOVP` is the
//! 32-bit (`D`), pulse (`P`) form of `MOV`.

use crate::il::error::{StatementError, UnknownHint};
use crate::il::instruction::{Exec, Width};

/// A mnemonic with its 32-bit and pulse forms taken apart.
#[derive(Clone, Copy, Debug)]
pub(super) struct Form<'a> {
    /// The mnemonic as written (upper case).
    pub(super) mnemonic: &'a str,
    /// 16 or 32 bit (`D` prefix).
    pub(super) width: Width,
    /// The instruction without its prefix and suffix (`MOV`).
    pub(super) base: &'a str,
    /// Continuous or pulse (`P` suffix).
    pub(super) exec: Exec,
}

impl Form<'_> {
    /// The mnemonic is not an instruction the LX3V has.
    pub(super) fn unknown(&self, hint: UnknownHint) -> StatementError {
        StatementError::Unknown {
            mnemonic: self.mnemonic.to_string(),
            hint,
        }
    }

    /// Refuses a `D` form of an instruction that has none.
    pub(super) fn no_double(&self) -> Result<(), StatementError> {
        if self.width == Width::Double {
            Err(self.unknown(UnknownHint::NoDoubleForm(self.base.to_string())))
        } else {
            Ok(())
        }
    }

    /// Refuses a `P` form of an instruction that has none.
    pub(super) fn no_pulse(&self) -> Result<(), StatementError> {
        if self.exec == Exec::Pulse {
            Err(self.unknown(UnknownHint::NoPulseForm(self.base.to_string())))
        } else {
            Ok(())
        }
    }
}

/// Splits `DMOVP` into (Double, "MOV", Pulse) for the applied instructions
/// that have 32-bit and pulse forms.
pub(super) fn split(mnemonic: &str) -> Option<Form<'_>> {
    const BASES: [&str; 22] = [
        "MOV", "EMOV", "ADD", "SUB", "MUL", "DIV", "INC", "DEC", "NEG", "WAND", "WOR", "WXOR",
        "CMP", "ZCP", "BMOV", "FMOV", "SFTL", "SFTR", "ZRST", "PLSY", "ECAM", "ECAMTBX",
    ];
    let form = |width, base, exec| Form {
        mnemonic,
        width,
        base,
        exec,
    };
    // The 32-bit word logic is DAND/DOR/DXOR, not DWAND.
    for (double, word) in [("DAND", "WAND"), ("DOR", "WOR"), ("DXOR", "WXOR")] {
        match mnemonic.strip_prefix(double) {
            Some("") => return Some(form(Width::Double, word, Exec::Continuous)),
            Some("P") => return Some(form(Width::Double, word, Exec::Pulse)),
            _ => {}
        }
    }
    if mnemonic.starts_with("DW") {
        return None;
    }
    let (width, rest) = match mnemonic.strip_prefix('D') {
        Some(rest)
            if BASES.contains(&rest)
                || rest.strip_suffix('P').is_some_and(|r| BASES.contains(&r)) =>
        {
            (Width::Double, rest)
        }
        _ => (Width::Word, mnemonic),
    };
    let (base, exec) = match rest.strip_suffix('P') {
        Some(base) if BASES.contains(&base) => (base, Exec::Pulse),
        _ => (rest, Exec::Continuous),
    };
    BASES.contains(&base).then_some(form(width, base, exec))
}
