//! PLSY/DPLSY: a pulse train on Y0–Y3.

use super::form::Form;
use super::operands::{arity, pulse_output, source};
use crate::il::error::StatementError;
use crate::il::instruction::Instruction;
use crate::il::operand::Operand;

/// PLSY or DPLSY.
pub(super) fn parse(form: Form<'_>, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let Form {
        mnemonic, width, ..
    } = form;
    form.no_pulse()?;
    arity(
        mnemonic,
        ops,
        &["S1 (frequency)", "S2 (pulses)", "D (Y0-Y3)"],
    )?;
    Ok(Instruction::PulseOutput {
        width,
        frequency: source(mnemonic, 0, &ops[0], width)?,
        count: source(mnemonic, 1, &ops[1], width)?,
        output: pulse_output(mnemonic, 2, &ops[2])?,
    })
}
