//! Load-time checks of program flow: pointer labels, CJ, CALL/SRET and FEND,
//! so that a jump to nowhere or a subroutine that never returns is refused
//! with its line instead of misbehaving at run time.

use super::error::FlowError;
use super::instruction::{Instruction, Statement};
use super::limits::{CALL_DEPTH, END_POINTER, POINTER_COUNT};

/// Returns the line and message of the first flow error.
pub(crate) fn check(statements: &[Statement]) -> Result<(), (usize, FlowError)> {
    let mut labels: [Option<usize>; POINTER_COUNT] = [None; POINTER_COUNT];
    for (index, statement) in statements.iter().enumerate() {
        if let Instruction::Label(n) = statement.instruction {
            let slot = labels
                .get_mut(usize::from(n))
                .ok_or((statement.line, FlowError::PointerRange(n)))?;
            if let Some(first) = *slot {
                let first_line = statements.get(first).map_or(0, |s| s.line);
                return Err((
                    statement.line,
                    FlowError::DuplicateLabel {
                        pointer: n,
                        first_line,
                    },
                ));
            }
            *slot = Some(index);
        }
    }
    let fend = statements
        .iter()
        .position(|s| matches!(s.instruction, Instruction::MainEnd));
    let in_main = |index: usize| fend.is_none_or(|f| index < f);
    let target = |line: usize, mnemonic: &'static str, n: u8| {
        labels.get(usize::from(n)).copied().flatten().ok_or((
            line,
            FlowError::NoLabel {
                mnemonic,
                pointer: n,
            },
        ))
    };
    for (index, statement) in statements.iter().enumerate() {
        let line = statement.line;
        match statement.instruction {
            Instruction::Jump { pointer, .. } if pointer != END_POINTER => {
                let to = target(line, "CJ", pointer)?;
                if in_main(index) != in_main(to) {
                    return Err((line, FlowError::JumpAcrossEnd(pointer)));
                }
            }
            Instruction::Call { pointer, .. } => {
                let to = target(line, "CALL", pointer)?;
                if in_main(to) {
                    return Err((
                        line,
                        FlowError::CallIntoMain {
                            pointer,
                            label_line: statements.get(to).map_or(0, |s| s.line),
                        },
                    ));
                }
                subroutine_end(statements, to)?;
            }
            Instruction::SubReturn if in_main(index) => {
                return Err((line, FlowError::ReturnInMain));
            }
            _ => {}
        }
    }
    // CALL nesting: each subroutine body runs from its label to its SRET.
    let mut depths: [Option<usize>; POINTER_COUNT] = [None; POINTER_COUNT];
    let mut running = [false; POINTER_COUNT];
    for (index, statement) in statements.iter().enumerate() {
        if in_main(index) {
            if let Instruction::Call { pointer, .. } = statement.instruction {
                let levels = depth(statements, &labels, pointer, &mut depths, &mut running)?;
                if levels > CALL_DEPTH {
                    return Err((statement.line, FlowError::TooDeep { pointer, levels }));
                }
            }
        }
    }
    Ok(())
}

/// The index of the SRET closing the subroutine that starts at `label`.
fn subroutine_end(statements: &[Statement], label: usize) -> Result<usize, (usize, FlowError)> {
    let label_line = statements.get(label).map_or(0, |s| s.line);
    for (offset, statement) in statements.iter().enumerate().skip(label) {
        match statement.instruction {
            Instruction::SubReturn => return Ok(offset),
            Instruction::MainEnd => break,
            _ => {}
        }
    }
    Err((label_line, FlowError::NeverReturns))
}

/// How many CALL levels running subroutine `pointer` takes (1 when it
/// calls nothing), each subroutine computed once; a recursive CALL is an
/// error at its line.
fn depth(
    statements: &[Statement],
    labels: &[Option<usize>; POINTER_COUNT],
    pointer: u8,
    depths: &mut [Option<usize>; POINTER_COUNT],
    running: &mut [bool; POINTER_COUNT],
) -> Result<usize, (usize, FlowError)> {
    let slot = usize::from(pointer);
    if let Some(Some(known)) = depths.get(slot) {
        return Ok(*known);
    }
    let Some(start) = labels.get(slot).copied().flatten() else {
        return Ok(1);
    };
    let end = subroutine_end(statements, start)?;
    if let Some(flag) = running.get_mut(slot) {
        *flag = true;
    }
    let mut deepest = 0usize;
    for statement in statements.get(start..end).unwrap_or(&[]) {
        if let Instruction::Call { pointer: inner, .. } = statement.instruction {
            if running.get(usize::from(inner)).copied().unwrap_or(false) {
                return Err((statement.line, FlowError::Recursive(inner)));
            }
            deepest = deepest.max(depth(statements, labels, inner, depths, running)?);
        }
    }
    if let Some(flag) = running.get_mut(slot) {
        *flag = false;
    }
    let levels = deepest.saturating_add(1);
    if let Some(known) = depths.get_mut(slot) {
        *known = Some(levels);
    }
    Ok(levels)
}
