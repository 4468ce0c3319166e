//! Contacts: LD/AND/OR and their inverse and edge forms, ANB/ORB,
//! MPS/MRD/MPP, NOP, and the comparison contacts (`LD=` … `ORD>=`).

use super::operands::{arity, at, bit_source, source};
use crate::device::C_32BIT_FIRST;
use crate::il::error::{OperandError, StatementError, UnknownHint};
use crate::il::instruction::{Contact, Instruction, Join, Relation, Source, Width};
use crate::il::operand::Operand;

/// A bit contact or a stack instruction; `None` for any other mnemonic.
pub(super) fn parse(
    mnemonic: &str,
    ops: &[Operand],
) -> Option<Result<Instruction, StatementError>> {
    let contact = |join: fn(Contact, crate::il::instruction::BitRef) -> Instruction, contact| {
        arity(mnemonic, ops, &["device"])?;
        Ok(join(contact, bit_source(mnemonic, 0, &ops[0])?))
    };
    let stack = |instruction| {
        arity(mnemonic, ops, &[])?;
        Ok(instruction)
    };
    Some(match mnemonic {
        "LD" => contact(Instruction::Load, Contact::Open),
        "LDI" => contact(Instruction::Load, Contact::Closed),
        "LDP" => contact(Instruction::Load, Contact::Rising),
        "LDF" => contact(Instruction::Load, Contact::Falling),
        "AND" => contact(Instruction::And, Contact::Open),
        "ANI" => contact(Instruction::And, Contact::Closed),
        "ANDP" => contact(Instruction::And, Contact::Rising),
        "ANDF" => contact(Instruction::And, Contact::Falling),
        "OR" => contact(Instruction::Or, Contact::Open),
        "ORI" => contact(Instruction::Or, Contact::Closed),
        "ORP" => contact(Instruction::Or, Contact::Rising),
        "ORF" => contact(Instruction::Or, Contact::Falling),
        "ANB" => stack(Instruction::AndBlock),
        "ORB" => stack(Instruction::OrBlock),
        "MPS" => stack(Instruction::Push),
        "MRD" => stack(Instruction::Read),
        "MPP" => stack(Instruction::Pop),
        "NOP" => stack(Instruction::Nop),
        _ if comparison(mnemonic).is_some() => compare_contact(mnemonic, ops),
        _ => return None,
    })
}

/// Splits `ANDD<>` into (And, Double, NotEqual).
fn comparison(mnemonic: &str) -> Option<(Join, Width, Relation)> {
    let (join, rest) = [("LD", Join::Load), ("AND", Join::And), ("OR", Join::Or)]
        .into_iter()
        .find_map(|(prefix, join)| mnemonic.strip_prefix(prefix).map(|rest| (join, rest)))?;
    let (width, rest) = match rest.strip_prefix('D') {
        Some(rest) => (Width::Double, rest),
        None => (Width::Word, rest),
    };
    let relation = match rest {
        "=" => Relation::Equal,
        "<>" => Relation::NotEqual,
        ">" => Relation::Greater,
        "<" => Relation::Less,
        ">=" => Relation::GreaterOrEqual,
        "<=" => Relation::LessOrEqual,
        _ => return None,
    };
    Some((join, width, relation))
}

fn compare_contact(mnemonic: &str, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let Some((join, width, relation)) = comparison(mnemonic) else {
        return Err(StatementError::Unknown {
            mnemonic: mnemonic.to_string(),
            hint: UnknownHint::Comparison,
        });
    };
    arity(mnemonic, ops, &["S1", "S2"])?;
    let operand = |index: usize| -> Result<Source, StatementError> {
        let source = source(mnemonic, index, &ops[index], width)?;
        // The FX manual: a 32-bit counter in a 16-bit comparison is an
        // error; say so at load instead of comparing its low word.
        match source {
            Source::Counter(n) if width == Width::Word && n >= C_32BIT_FIRST => {
                let prefix = match join {
                    Join::Load => "LD",
                    Join::And => "AND",
                    Join::Or => "OR",
                };
                let relation = mnemonic.get(prefix.len()..).unwrap_or("");
                Err(at(
                    mnemonic,
                    index,
                    OperandError::Counter32 {
                        counter: n,
                        instead: format!("{prefix}D{relation}"),
                    },
                ))
            }
            other => Ok(other),
        }
    };
    Ok(Instruction::CompareContact {
        join,
        relation,
        width,
        s1: operand(0)?,
        s2: operand(1)?,
    })
}
