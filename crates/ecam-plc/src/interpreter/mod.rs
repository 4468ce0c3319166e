//! Executes a [`Program`] once per scan, the FX way: contacts combine into a
//! power flow on a stack of logic blocks (ANB/ORB), MPS/MRD/MPP keep branch
//! points, coils follow the power flow, and applied instructions run while
//! their power flow is on (the `P` forms only in the scan it turns on).
//!
//! This file holds the scan loop; program flow (CJ, CALL/SRET, FEND) is in
//! `flow.rs`, and `dispatch.rs` sends every other instruction to its family:
//! `contacts.rs` and `power_flow.rs` (LD/AND/OR, comparison contacts,
//! ANB/ORB, MPS/MRD/MPP), `coils.rs` (OUT, SET/RST, PLS/PLF, timer and
//! counter coils, ZRST), `moves.rs` (MOV, DEMOV, BMOV, FMOV),
//! `arithmetic.rs` (ADD/SUB, MUL, DIV, WAND/WOR/WXOR, NEG, INC/DEC),
//! `comparison.rs` (CMP, ZCP), `shift.rs` (SFTL/SFTR), `pulse_output.rs`
//! (PLSY/DPLSY) and `cam.rs` (DECAM, ECAMTBX).

mod arithmetic;
mod cam;
mod coils;
mod comparison;
mod contacts;
mod dispatch;
mod flow;
mod machine;
mod moves;
mod operands;
mod power_flow;
mod pulse_output;
mod shift;

use self::dispatch::{Statement, execute};
use self::flow::{Calls, Labels};
pub(crate) use self::machine::Machine;
use self::machine::Memory;
use self::power_flow::PowerFlow;
use crate::il::{Instruction, Program, is_output};
use crate::operation_error::OperationError;

/// An operation error and the source line of the instruction that raised it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineError {
    /// 1-based source line.
    pub line: usize,
    /// The error (its code goes to D8067).
    pub error: OperationError,
}

/// The run-time state of a program: per-instruction memories and the stacks.
#[derive(Clone, Debug, Default)]
pub struct Interpreter {
    memory: Vec<Memory>,
    power_flow: PowerFlow,
    /// Statement index of each pointer label (P63: the end of the main program).
    labels: Labels,
    /// For each statement, the number of the DECAM it is (program order).
    decam_of: Vec<Option<usize>>,
}

/// What one scan did: its operation errors, how many instructions it
/// executed, and whether the watchdog stopped it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ScanOutcome {
    /// Operation errors, with their lines.
    pub errors: Vec<LineError>,
    /// Instructions executed.
    pub steps: u64,
    /// The scan ran past the watchdog time: the line of the last jump
    /// taken (a loop that never ends), or of the instruction reached.
    pub overrun_at: Option<usize>,
}

/// Where the scan goes after an instruction.
enum Next {
    /// The next statement.
    Continue,
    /// Statement `to` (a jump taken, a CALL, an SRET).
    At(usize),
    /// The scan ends (FEND, or SRET outside a subroutine).
    End,
}

impl Interpreter {
    /// Fresh state for `program`.
    pub fn new(program: &Program) -> Self {
        let mut decam_of = Vec::with_capacity(program.statements.len());
        let mut decams = 0usize;
        for statement in &program.statements {
            if matches!(statement.instruction, Instruction::Decam { .. }) {
                decam_of.push(Some(decams));
                decams += 1;
            } else {
                decam_of.push(None);
            }
        }
        Self {
            memory: vec![Memory::default(); program.statements.len()],
            power_flow: PowerFlow::default(),
            labels: Labels::of(program),
            decam_of,
        }
    }

    /// Runs every statement once. An instruction that fails does not stop the
    /// scan (as on the PLC); its error is returned with its line. Every
    /// [`crate::watchdog::CHECK_EVERY`] instructions `over_time(steps)` is
    /// asked whether the scan has run past the watchdog time; when it has,
    /// the scan ends there (a backward CJ whose condition never changes
    /// would otherwise loop for ever).
    pub fn scan(
        &mut self,
        program: &Program,
        machine: &mut Machine<'_>,
        over_time: &mut dyn FnMut(u64) -> bool,
    ) -> ScanOutcome {
        let mut errors = Vec::new();
        let mut overrun_at = None;
        self.power_flow.clear();
        let mut after_output = true;
        let mut calls = Calls::default();
        let mut next = 0usize;
        let mut steps = 0u64;
        // The line of the last jump taken: the loop an over-long scan names.
        let mut last_jump: Option<usize> = None;
        while let Some(statement) = program.statements.get(next) {
            let index = next;
            next += 1;
            steps += 1;
            if steps.is_multiple_of(crate::watchdog::CHECK_EVERY) && over_time(steps) {
                overrun_at = Some(last_jump.unwrap_or(statement.line));
                break;
            }
            let Some(memory) = self.memory.get_mut(index) else {
                break;
            };
            let instruction = &statement.instruction;
            let power_flow = &mut self.power_flow;
            let (result, then) = match *instruction {
                Instruction::Jump { exec, pointer } => {
                    match flow::jump((exec, pointer), &self.labels, power_flow, memory) {
                        Some(to) => {
                            last_jump = Some(statement.line);
                            (Ok(()), Next::At(to))
                        }
                        None => (Ok(()), Next::Continue),
                    }
                }
                Instruction::Call { exec, pointer } => {
                    let call = (&mut calls, &mut *power_flow);
                    match flow::call((exec, pointer), next, &self.labels, call, memory) {
                        Ok(Some(to)) => (Ok(()), Next::At(to)),
                        Ok(None) => (Ok(()), Next::Continue),
                        Err(error) => (Err(error), Next::Continue),
                    }
                }
                Instruction::SubReturn => match flow::sub_return(&mut calls, power_flow) {
                    Some(to) => (Ok(()), Next::At(to)),
                    None => (Ok(()), Next::End),
                },
                Instruction::MainEnd => (Ok(()), Next::End),
                _ => {
                    let decam = self.decam_of.get(index).copied().flatten();
                    let at = Statement { index, decam };
                    let result =
                        execute(instruction, at, (power_flow, after_output), memory, machine);
                    (result, Next::Continue)
                }
            };
            match then {
                Next::Continue => {}
                Next::At(to) => next = to,
                Next::End => break,
            }
            if let Err(error) = result {
                report(machine, &error);
                errors.push(LineError {
                    line: statement.line,
                    error,
                });
            }
            if !matches!(instruction, Instruction::Nop) {
                after_output = is_output(instruction);
            }
        }
        ScanOutcome {
            errors,
            steps,
            overrun_at,
        }
    }
}

/// Writes an operation error the FX way, at once: an instruction later in
/// this scan can test M8067 (or reset it) and see it.
fn report(machine: &mut Machine<'_>, error: &OperationError) {
    let _ = machine
        .devices
        .set_word(crate::special::D_OPERATION_ERROR, error.code as i16);
    let _ = machine
        .devices
        .set_m(crate::special::M_OPERATION_ERROR, true);
}
