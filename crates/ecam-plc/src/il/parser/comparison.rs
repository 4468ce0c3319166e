//! Comparisons into bits: CMP and ZCP (the comparison contacts are in
//! `contacts.rs`).

use super::form::Form;
use super::operands::{arity, source, three_bits};
use crate::il::error::StatementError;
use crate::il::instruction::Instruction;
use crate::il::operand::Operand;

/// CMP or ZCP (`form.base`).
pub(super) fn parse(form: Form<'_>, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let Form {
        mnemonic,
        width,
        base,
        exec,
    } = form;
    Ok(match base {
        "CMP" => {
            arity(mnemonic, ops, &["S1", "S2", "D"])?;
            Instruction::Compare {
                width,
                exec,
                s1: source(mnemonic, 0, &ops[0], width)?,
                s2: source(mnemonic, 1, &ops[1], width)?,
                dst: three_bits(mnemonic, 2, &ops[2])?,
            }
        }
        // ZCP: the last base `applied` in `mod.rs` sends here.
        _ => {
            arity(mnemonic, ops, &["S1 (low)", "S2 (high)", "S3", "D"])?;
            Instruction::ZoneCompare {
                width,
                exec,
                low: source(mnemonic, 0, &ops[0], width)?,
                high: source(mnemonic, 1, &ops[1], width)?,
                value: source(mnemonic, 2, &ops[2], width)?,
                dst: three_bits(mnemonic, 3, &ops[3])?,
            }
        }
    })
}
