//! Program flow and its pointers: labels `Pn`, CJ/CJP, CALL/CALLP, SRET,
//! FEND (the checks across the whole program are in `il/flow.rs`).

use super::operands::at;
use crate::il::error::{StatementError, TokenError};
use crate::il::instruction::{Exec, Instruction};
use crate::il::limits::{END_POINTER, POINTER_COUNT};

/// `Some` when `mnemonic` is a pointer label `Pn` (P and digits only):
/// its number, or why it is not a usable label.
pub(super) fn label(mnemonic: &str) -> Option<Result<u8, StatementError>> {
    let digits = mnemonic.strip_prefix('P')?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(match pointer_number(mnemonic) {
        Ok(n) if n == END_POINTER => Err(StatementError::EndPointerLabel),
        Ok(n) => Ok(n),
        Err(e) => Err(StatementError::BadLabel(e)),
    })
}

/// The n of a pointer `Pn`, n = 0–127.
fn pointer_number(token: &str) -> Result<u8, TokenError> {
    let upper = token.to_ascii_uppercase();
    let number = upper
        .strip_prefix('P')
        .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
        .ok_or_else(|| TokenError::PointerSyntax(token.to_string()))?;
    match number.parse::<u8>() {
        Ok(n) if usize::from(n) < POINTER_COUNT => Ok(n),
        _ => Err(TokenError::PointerRange(upper)),
    }
}

/// CJ/CJP/CALL/CALLP/SRET/FEND, whose operand is a pointer rather than a
/// device: `None` for other mnemonics.
pub(super) fn flow_instruction(
    mnemonic: &str,
    tokens: &[&str],
) -> Option<Result<Instruction, StatementError>> {
    let pointer = |exec: Exec, call: bool| -> Result<Instruction, StatementError> {
        match tokens {
            [token] => {
                let pointer = pointer_number(token).map_err(|e| at(mnemonic, 0, e))?;
                if call && pointer == END_POINTER {
                    return Err(StatementError::CallEndPointer {
                        mnemonic: mnemonic.to_string(),
                    });
                }
                Ok(if call {
                    Instruction::Call { exec, pointer }
                } else {
                    Instruction::Jump { exec, pointer }
                })
            }
            _ => Err(StatementError::FlowArity {
                mnemonic: mnemonic.to_string(),
                found: tokens.len(),
            }),
        }
    };
    let bare = |instruction: Instruction| -> Result<Instruction, StatementError> {
        if tokens.is_empty() {
            Ok(instruction)
        } else {
            Err(StatementError::NoOperands {
                mnemonic: mnemonic.to_string(),
            })
        }
    };
    Some(match mnemonic {
        "CJ" => pointer(Exec::Continuous, false),
        "CJP" => pointer(Exec::Pulse, false),
        "CALL" => pointer(Exec::Continuous, true),
        "CALLP" => pointer(Exec::Pulse, true),
        "SRET" => bare(Instruction::SubReturn),
        "FEND" => bare(Instruction::MainEnd),
        _ => return None,
    })
}
