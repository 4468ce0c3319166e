//! Bit shifts: SFTL and SFTR.

use super::form::Form;
use super::operands::{arity, at, bit_dest, bits_exist, wrong};
use crate::device::Device;
use crate::il::error::{OperandError, StatementError};
use crate::il::instruction::Instruction;
use crate::il::limits::{SHIFT_COUNT, SHIFT_MAX};
use crate::il::operand::Operand;

/// SFTL or SFTR (`form.base`).
pub(super) fn parse(form: Form<'_>, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let Form {
        mnemonic,
        base,
        exec,
        ..
    } = form;
    form.no_double()?;
    arity(mnemonic, ops, &["S", "D", "n1", "n2"])?;
    let count = |i: usize| match ops[i] {
        Operand::Decimal(n) if (1..=i64::from(SHIFT_MAX)).contains(&n) => Ok(n as u16),
        ref other => Err(wrong(mnemonic, i, other, SHIFT_COUNT)),
    };
    let (length, places) = (count(2)?, count(3)?);
    if places > length {
        return Err(StatementError::ShiftLonger {
            mnemonic: mnemonic.to_string(),
            places,
            length,
        });
    }
    let src = match ops[0] {
        Operand::Device(d @ (Device::X(_) | Device::Y(_) | Device::M(_))) => d,
        ref other => return Err(wrong(mnemonic, 0, other, "an X, Y or M bit")),
    };
    let dst = bit_dest(mnemonic, 1, &ops[1])?.0;
    for (index, first, bits) in [(0, src, places), (1, dst, length)] {
        if !bits_exist(first, bits) {
            return Err(at(
                mnemonic,
                index,
                OperandError::BitsPastEnd { bits, first },
            ));
        }
    }
    Ok(Instruction::BitShift {
        left: base == "SFTL",
        exec,
        src,
        dst,
        length,
        places,
    })
}
