//! Transfers: MOV/DMOV, DEMOV, BMOV, FMOV/DFMOV.

use super::form::Form;
use super::operands::{arity, block, block_count, register, source, word_dest, wrong};
use crate::device::Device;
use crate::il::error::{StatementError, UnknownHint};
use crate::il::instruction::{FloatSource, Instruction, Width};
use crate::il::operand::Operand;

/// MOV, DEMOV, BMOV or FMOV (`form.base`).
pub(super) fn parse(form: Form<'_>, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let Form {
        mnemonic,
        width,
        base,
        exec,
    } = form;
    Ok(match base {
        "MOV" => {
            arity(mnemonic, ops, &["S", "D"])?;
            Instruction::Move {
                width,
                exec,
                src: source(mnemonic, 0, &ops[0], width)?,
                dst: word_dest(mnemonic, 1, &ops[1], width)?,
            }
        }
        "EMOV" => {
            if width != Width::Double {
                return Err(form.unknown(UnknownHint::FloatMove));
            }
            arity(mnemonic, ops, &["S", "D"])?;
            let src = match ops[0] {
                Operand::Float(v) => FloatSource::Constant(v),
                Operand::Decimal(v) => FloatSource::Constant(v as f32),
                Operand::Device(Device::D(n)) => {
                    FloatSource::Register(register(mnemonic, 0, n, Width::Double)?)
                }
                ref other => {
                    return Err(wrong(
                        mnemonic,
                        0,
                        other,
                        "an E constant (E1.6667) or a D register",
                    ));
                }
            };
            let dst = match ops[1] {
                Operand::Device(Device::D(n)) => register(mnemonic, 1, n, Width::Double)?,
                ref other => return Err(wrong(mnemonic, 1, other, "a D register")),
            };
            Instruction::FloatMove { exec, src, dst }
        }
        "BMOV" => {
            form.no_double()?;
            arity(mnemonic, ops, &["S", "D", "n"])?;
            Instruction::BlockMove {
                exec,
                src: block(mnemonic, 0, &ops[0])?,
                dst: block(mnemonic, 1, &ops[1])?,
                count: block_count(mnemonic, 2, &ops[2])?,
            }
        }
        // FMOV: the last base `applied` in `mod.rs` sends here.
        _ => {
            arity(mnemonic, ops, &["S", "D", "n"])?;
            Instruction::Fill {
                width,
                exec,
                src: source(mnemonic, 0, &ops[0], width)?,
                dst: block(mnemonic, 1, &ops[1])?,
                count: block_count(mnemonic, 2, &ops[2])?,
            }
        }
    })
}
