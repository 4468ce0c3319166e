//! Program flow: CJ jumps to a pointer label, CALL runs a subroutine up to
//! its SRET, FEND ends the main program (the load-time checks are in
//! `il/flow.rs`).

use super::machine::{Memory, runs};
use super::power_flow::PowerFlow;
use crate::il::{CALL_DEPTH, END_POINTER, Exec, Instruction, POINTER_COUNT, Program};
use crate::operation_error::{CODE_CALL_NESTING, OperationError};

/// The statement index of each pointer label; P63 stands for the end of
/// the main program (its FEND, or the end of the program).
#[derive(Clone, Debug, Default)]
pub(super) struct Labels(Vec<Option<usize>>);

impl Labels {
    /// The labels of `program`.
    pub(super) fn of(program: &Program) -> Self {
        let mut labels = vec![None; POINTER_COUNT];
        let mut main_end = None;
        for (index, statement) in program.statements.iter().enumerate() {
            match statement.instruction {
                Instruction::Label(n) => {
                    if let Some(slot) = labels.get_mut(usize::from(n)) {
                        *slot = Some(index);
                    }
                }
                Instruction::MainEnd if main_end.is_none() => main_end = Some(index),
                _ => {}
            }
        }
        if let Some(slot) = labels.get_mut(usize::from(END_POINTER)) {
            *slot = Some(main_end.unwrap_or(program.statements.len()));
        }
        Self(labels)
    }

    /// Where pointer `Pn` continues.
    fn target(&self, pointer: u8) -> Option<usize> {
        self.0.get(usize::from(pointer)).copied().flatten()
    }
}

/// A CALL being executed: where to continue and the power flow to restore.
struct Frame {
    return_to: usize,
    power_flow: PowerFlow,
}

/// The subroutines running in this scan, innermost last.
#[derive(Default)]
pub(super) struct Calls(Vec<Frame>);

/// `CJ`/`CJP Pn`: the statement to continue at when the jump is taken
/// (the power flow starts afresh there).
pub(super) fn jump(
    (exec, pointer): (Exec, u8),
    labels: &Labels,
    power_flow: &mut PowerFlow,
    memory: &mut Memory,
) -> Option<usize> {
    if !runs(exec, power_flow.power(), memory) {
        return None;
    }
    let to = labels.target(pointer)?;
    power_flow.clear();
    Some(to)
}

/// `CALL`/`CALLP Pn` before statement `return_to`: the statement to
/// continue at when the call is made; the caller's power flow is kept for
/// its SRET.
///
/// # Errors
/// 6702 when the call would nest deeper than the FX3U's five levels.
pub(super) fn call(
    (exec, pointer): (Exec, u8),
    return_to: usize,
    labels: &Labels,
    (calls, power_flow): (&mut Calls, &mut PowerFlow),
    memory: &mut Memory,
) -> Result<Option<usize>, OperationError> {
    if !runs(exec, power_flow.power(), memory) {
        return Ok(None);
    }
    if calls.0.len() >= CALL_DEPTH {
        return Err(OperationError::new(
            CODE_CALL_NESTING,
            format!("CALL P{pointer}: subroutines nested deeper than {CALL_DEPTH} levels"),
        ));
    }
    let Some(to) = labels.target(pointer) else {
        return Ok(None);
    };
    calls.0.push(Frame {
        return_to,
        power_flow: core::mem::take(power_flow),
    });
    Ok(Some(to))
}

/// `SRET`: the statement after the innermost CALL, whose power flow comes
/// back; `None` outside a subroutine (the scan ends).
pub(super) fn sub_return(calls: &mut Calls, power_flow: &mut PowerFlow) -> Option<usize> {
    let frame = calls.0.pop()?;
    *power_flow = frame.power_flow;
    Some(frame.return_to)
}
