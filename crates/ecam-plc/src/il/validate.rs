//! Static check of the logic-block and MPS stacks, so that a program whose
//! ANB/ORB/MRD/MPP has nothing to work on is refused at load time with its
//! line, instead of misbehaving at run time.

use super::error::StackError;
use super::instruction::{Instruction, Join, Statement};
use super::limits::MPS_DEPTH;

/// True for instructions that consume the power flow (coils and applied
/// instructions): the next LD after one starts a new rung.
pub(crate) fn is_output(instruction: &Instruction) -> bool {
    !matches!(
        instruction,
        Instruction::Load(..)
            | Instruction::And(..)
            | Instruction::Or(..)
            | Instruction::CompareContact { .. }
            | Instruction::AndBlock
            | Instruction::OrBlock
            | Instruction::Push
            | Instruction::Read
            | Instruction::Pop
            | Instruction::Nop
    )
}

/// Returns the line and message of the first misuse.
pub(crate) fn check(statements: &[Statement]) -> Result<(), (usize, StackError)> {
    let mut blocks = 0usize;
    let mut pushed = 0usize;
    // Lines of the MPS still open, to name the one never closed.
    let mut open_mps: Vec<usize> = Vec::new();
    let mut after_output = true;
    for statement in statements {
        let line = statement.line;
        let instruction = &statement.instruction;
        let need_flow = |blocks: usize, what: &'static str| {
            if blocks == 0 {
                Err((line, StackError::NoPowerFlow { what }))
            } else {
                Ok(())
            }
        };
        match instruction {
            Instruction::Load(..)
            | Instruction::CompareContact {
                join: Join::Load, ..
            } => {
                if after_output && pushed == 0 {
                    blocks = 0;
                }
                blocks += 1;
            }
            Instruction::And(..) | Instruction::Or(..) | Instruction::CompareContact { .. } => {
                need_flow(blocks, "AND/OR contact")?
            }
            Instruction::AndBlock | Instruction::OrBlock => {
                if blocks < 2 {
                    return Err((line, StackError::TwoBlocks));
                }
                blocks -= 1;
            }
            Instruction::Push => {
                need_flow(blocks, "MPS")?;
                if pushed >= MPS_DEPTH {
                    return Err((line, StackError::MpsDepth));
                }
                pushed += 1;
                open_mps.push(line);
            }
            Instruction::Read => {
                if pushed == 0 {
                    return Err((line, StackError::ReadWithoutPush));
                }
            }
            Instruction::Pop => {
                if pushed == 0 {
                    return Err((line, StackError::PopWithoutPush));
                }
                pushed -= 1;
                open_mps.pop();
            }
            Instruction::Nop => {}
            // A label starts a new rung; SRET and FEND take no power flow.
            Instruction::Label(_) | Instruction::SubReturn | Instruction::MainEnd => {
                blocks = 0;
            }
            _ => {
                need_flow(blocks, "this instruction")?;
                if blocks > 1 {
                    return Err((line, StackError::BlocksOpen(blocks)));
                }
            }
        }
        if !matches!(instruction, Instruction::Nop) {
            after_output = is_output(instruction);
        }
    }
    // An MPS whose branch point is never popped leaves the rung unfinished:
    // the FX programming tools refuse such a circuit, so do we.
    if let Some(&line) = open_mps.last() {
        return Err((line, StackError::PushNotClosed));
    }
    Ok(())
}
