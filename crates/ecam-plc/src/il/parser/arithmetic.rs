//! Arithmetic and logic on words: ADD/SUB, MUL, DIV, WAND/WOR/WXOR,
//! NEG, INC/DEC.

use super::form::Form;
use super::operands::{arity, at, result_dest, source, word_dest, wrong};
use crate::device::D_COUNT;
use crate::il::error::{OperandError, StatementError};
use crate::il::instruction::{ArithOp, Dest, IndexBase, Indexed, Instruction, LogicOp, Width};
use crate::il::operand::Operand;

/// ADD, SUB, MUL, DIV, WAND, WOR, WXOR, NEG, INC or DEC (`form.base`).
pub(super) fn parse(form: Form<'_>, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let Form {
        mnemonic,
        width,
        base,
        exec,
    } = form;
    Ok(match base {
        "ADD" | "SUB" => {
            arity(mnemonic, ops, &["S1", "S2", "D"])?;
            Instruction::Arith {
                op: if base == "ADD" {
                    ArithOp::Add
                } else {
                    ArithOp::Sub
                },
                width,
                exec,
                s1: source(mnemonic, 0, &ops[0], width)?,
                s2: source(mnemonic, 1, &ops[1], width)?,
                dst: word_dest(mnemonic, 2, &ops[2], width)?,
            }
        }
        "MUL" | "DIV" => {
            arity(mnemonic, ops, &["S1", "S2", "D"])?;
            let s1 = source(mnemonic, 0, &ops[0], width)?;
            let s2 = source(mnemonic, 1, &ops[1], width)?;
            let words: u16 = if width == Width::Double { 4 } else { 2 };
            // A 16-bit MUL's product is 32 bits wide: K1–K8 groups take it.
            let digits = if base == "MUL" || width == Width::Double {
                8
            } else {
                4
            };
            let dst = match result_dest(mnemonic, 2, &ops[2], width, digits)? {
                Dest::Register(n) if n.checked_add(words - 1).is_some_and(|l| l < D_COUNT) => {
                    Dest::Register(n)
                }
                Dest::Register(n) => {
                    return Err(at(
                        mnemonic,
                        2,
                        OperandError::ResultPastEnd { words, register: n },
                    ));
                }
                dst @ (Dest::Group(_)
                | Dest::Indexed(Indexed {
                    base: IndexBase::Register(_) | IndexBase::Group(_),
                    ..
                })) => dst,
                // 16-bit MUL into Zn is allowed by the FX3U (low word only);
                // we keep the result where the user can see all of it.
                _ => {
                    return Err(wrong(
                        mnemonic,
                        2,
                        &ops[2],
                        "a D register or a word group KnM/KnY (optionally index-modified)",
                    ));
                }
            };
            if base == "MUL" {
                Instruction::Multiply {
                    width,
                    exec,
                    s1,
                    s2,
                    dst,
                }
            } else {
                Instruction::Divide {
                    width,
                    exec,
                    s1,
                    s2,
                    dst,
                }
            }
        }
        "WAND" | "WOR" | "WXOR" => {
            arity(mnemonic, ops, &["S1", "S2", "D"])?;
            Instruction::Logic {
                op: match base {
                    "WAND" => LogicOp::And,
                    "WOR" => LogicOp::Or,
                    _ => LogicOp::Xor,
                },
                width,
                exec,
                s1: source(mnemonic, 0, &ops[0], width)?,
                s2: source(mnemonic, 1, &ops[1], width)?,
                dst: word_dest(mnemonic, 2, &ops[2], width)?,
            }
        }
        "NEG" => {
            arity(mnemonic, ops, &["D"])?;
            Instruction::Negate {
                width,
                exec,
                dst: word_dest(mnemonic, 0, &ops[0], width)?,
            }
        }
        // INC or DEC: the last bases `applied` in `mod.rs` sends here.
        _ => {
            arity(mnemonic, ops, &["D"])?;
            Instruction::Step {
                up: base == "INC",
                width,
                exec,
                dst: word_dest(mnemonic, 0, &ops[0], width)?,
            }
        }
    })
}
