//! The E-cam instructions: DECAM and ECAMTBX.

use super::form::Form;
use super::operands::{arity, pulse_output, register, source, wrong};
use crate::device::Device;
use crate::il::error::{StatementError, UnknownHint};
use crate::il::instruction::{Instruction, MasterSpec, Width};
use crate::il::operand::Operand;

/// DECAM or ECAMTBX (`form.base`).
pub(super) fn parse(form: Form<'_>, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let Form {
        mnemonic,
        width,
        base,
        ..
    } = form;
    Ok(match base {
        "ECAM" => {
            form.no_pulse()?;
            if width != Width::Double {
                return Err(form.unknown(UnknownHint::Ecam));
            }
            arity(
                mnemonic,
                ops,
                &[
                    "S1 (master)",
                    "S2 (block)",
                    "S3 (start)",
                    "D1 (Y0-Y3)",
                    "D2 (direction Y)",
                ],
            )?;
            let master = match ops[0] {
                Operand::Device(Device::C(n)) => MasterSpec::Counter(n),
                Operand::Device(Device::D(n)) => {
                    MasterSpec::Register(register(mnemonic, 0, n, Width::Double)?)
                }
                Operand::Decimal(k) if (1..=i64::from(u32::MAX)).contains(&k) => {
                    MasterSpec::TimeBase(k as u32)
                }
                ref other => {
                    return Err(wrong(
                        mnemonic,
                        0,
                        other,
                        "a counter C, a D register or a time base K1 or more",
                    ));
                }
            };
            let block = match ops[1] {
                Operand::Device(Device::D(n)) => n,
                ref other => return Err(wrong(mnemonic, 1, other, "a D register")),
            };
            let start = match ops[2] {
                Operand::Device(d @ (Device::X(_) | Device::M(_))) => d,
                ref other => return Err(wrong(mnemonic, 2, other, "an X or M device")),
            };
            let direction = match ops[4] {
                Operand::Device(d @ Device::Y(_)) => d,
                ref other => return Err(wrong(mnemonic, 4, other, "a Y output")),
            };
            Instruction::Decam {
                master,
                block,
                start,
                pulse_output: pulse_output(mnemonic, 3, &ops[3])?,
                direction,
            }
        }
        _ => {
            // ECAMTBX: the last base `applied` in `mod.rs` sends here.
            form.no_double()?;
            form.no_pulse()?;
            arity(mnemonic, ops, &["S0", "S1", "D1", "D2"])?;
            let d = |i: usize| match ops[i] {
                Operand::Device(Device::D(n)) => Ok(n),
                ref other => Err(wrong(mnemonic, i, other, "a D register")),
            };
            Instruction::Ecamtbx {
                params: d(0)?,
                kind: source(mnemonic, 1, &ops[1], Width::Double)?,
                table: d(2)?,
                result: d(3)?,
            }
        }
    })
}
