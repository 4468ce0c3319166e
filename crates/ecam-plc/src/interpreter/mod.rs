//! Executes a [`Program`] once per scan, the FX way: contacts combine into a
//! power flow on a stack of logic blocks (ANB/ORB), MPS/MRD/MPP keep branch
//! points, coils follow the power flow, and applied instructions run while
//! their power flow is on (the `P` forms only in the scan it turns on).

mod applied;
mod operands;

use crate::decam::Decam;
use crate::devices::Devices;
use crate::hardware::Hardware;
use crate::il::{BitRef, Contact, Exec, Instruction, Join, Program};
use crate::operation_error::OperationError;

/// What one instruction remembers between scans (edges, PLSY latch).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Memory {
    /// The previous input of an edge contact, or previous power flow of a
    /// pulse instruction (PLS/PLF, P forms, counter coil).
    pub previous: bool,
    /// PLSY: the pulse train was started and has not been re-armed yet.
    pub latched: bool,
}

/// Everything an instruction may touch.
pub struct Machine<'a> {
    /// Device memory.
    pub devices: &'a mut Devices,
    /// Pulse outputs, counters, wires.
    pub hardware: &'a mut Hardware,
    /// One E-cam instance per DECAM instruction, in program order.
    pub decams: &'a mut [Decam],
    /// Simulated time of this scan.
    pub now_us: u64,
}

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
    blocks: Vec<bool>,
    pushed: Vec<bool>,
    /// Statement index of each pointer label (P63: the end of the main program).
    labels: Vec<Option<usize>>,
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

/// A CALL being executed: where to continue and the stacks to restore.
struct Frame {
    return_to: usize,
    blocks: Vec<bool>,
    pushed: Vec<bool>,
}

impl Interpreter {
    /// Fresh state for `program`.
    pub fn new(program: &Program) -> Self {
        let mut labels = vec![None; crate::il::POINTER_COUNT];
        let mut decam_of = Vec::with_capacity(program.statements.len());
        let mut decams = 0usize;
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
            if matches!(statement.instruction, Instruction::Decam { .. }) {
                decam_of.push(Some(decams));
                decams += 1;
            } else {
                decam_of.push(None);
            }
        }
        if let Some(slot) = labels.get_mut(usize::from(crate::il::END_POINTER)) {
            *slot = Some(main_end.unwrap_or(program.statements.len()));
        }
        Self {
            memory: vec![Memory::default(); program.statements.len()],
            blocks: Vec::new(),
            pushed: Vec::new(),
            labels,
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
        self.blocks.clear();
        self.pushed.clear();
        let mut after_output = true;
        let mut calls: Vec<Frame> = Vec::new();
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
            let result = match instruction {
                Instruction::Load(contact, device) => {
                    let (value, read) = contact_value(*contact, *device, memory, machine);
                    if after_output && self.pushed.is_empty() {
                        self.blocks.clear();
                    }
                    self.blocks.push(value);
                    read
                }
                Instruction::And(contact, device) => {
                    let (value, read) = contact_value(*contact, *device, memory, machine);
                    if let Some(top) = self.blocks.last_mut() {
                        *top = *top && value;
                    }
                    read
                }
                Instruction::Or(contact, device) => {
                    let (value, read) = contact_value(*contact, *device, memory, machine);
                    if let Some(top) = self.blocks.last_mut() {
                        *top = *top || value;
                    }
                    read
                }
                Instruction::CompareContact {
                    join,
                    relation,
                    width,
                    s1,
                    s2,
                } => {
                    let compared =
                        operands::read_source(machine.devices, *s1, *width).and_then(|a| {
                            operands::read_source(machine.devices, *s2, *width)
                                .map(|b| relation.holds(a, b))
                        });
                    let value = *compared.as_ref().unwrap_or(&false);
                    match join {
                        Join::Load => {
                            if after_output && self.pushed.is_empty() {
                                self.blocks.clear();
                            }
                            self.blocks.push(value);
                        }
                        Join::And => {
                            if let Some(top) = self.blocks.last_mut() {
                                *top = *top && value;
                            }
                        }
                        Join::Or => {
                            if let Some(top) = self.blocks.last_mut() {
                                *top = *top || value;
                            }
                        }
                    }
                    compared.map(|_| ())
                }
                Instruction::AndBlock | Instruction::OrBlock => {
                    let last = self.blocks.pop().unwrap_or(false);
                    if let Some(top) = self.blocks.last_mut() {
                        *top = if matches!(instruction, Instruction::AndBlock) {
                            *top && last
                        } else {
                            *top || last
                        };
                    }
                    Ok(())
                }
                Instruction::Push => {
                    self.pushed.push(power_of(&self.blocks));
                    Ok(())
                }
                Instruction::Read | Instruction::Pop => {
                    let saved = if matches!(instruction, Instruction::Read) {
                        self.pushed.last().copied()
                    } else {
                        self.pushed.pop()
                    };
                    if let (Some(saved), Some(top)) = (saved, self.blocks.last_mut()) {
                        *top = saved;
                    }
                    Ok(())
                }
                Instruction::Nop | Instruction::Label(_) => Ok(()),
                Instruction::MainEnd => break,
                Instruction::SubReturn => match calls.pop() {
                    Some(frame) => {
                        next = frame.return_to;
                        self.blocks = frame.blocks;
                        self.pushed = frame.pushed;
                        Ok(())
                    }
                    None => break,
                },
                Instruction::Jump { exec, pointer } => {
                    let power = power_of(&self.blocks);
                    if runs(*exec, power, memory) {
                        if let Some(to) = self.labels.get(usize::from(*pointer)).copied().flatten()
                        {
                            next = to;
                            last_jump = Some(statement.line);
                            self.blocks.clear();
                            self.pushed.clear();
                        }
                    }
                    Ok(())
                }
                Instruction::Call { exec, pointer } => {
                    let power = power_of(&self.blocks);
                    if !runs(*exec, power, memory) {
                        Ok(())
                    } else if calls.len() >= crate::il::CALL_DEPTH {
                        Err(OperationError::new(
                            crate::operation_error::CODE_CALL_NESTING,
                            format!(
                                "CALL P{pointer}: subroutines nested deeper than {} levels",
                                crate::il::CALL_DEPTH
                            ),
                        ))
                    } else if let Some(to) =
                        self.labels.get(usize::from(*pointer)).copied().flatten()
                    {
                        calls.push(Frame {
                            return_to: next,
                            blocks: core::mem::take(&mut self.blocks),
                            pushed: core::mem::take(&mut self.pushed),
                        });
                        next = to;
                        Ok(())
                    } else {
                        Ok(())
                    }
                }
                Instruction::Decam { .. } => {
                    let power = power_of(&self.blocks);
                    match self
                        .decam_of
                        .get(index)
                        .copied()
                        .flatten()
                        .and_then(|d| machine.decams.get_mut(d))
                    {
                        Some(decam) => decam.execute(power, machine.devices, machine.now_us),
                        None => Ok(()),
                    }
                }
                other => {
                    let power = power_of(&self.blocks);
                    applied::execute(other, index, power, memory, machine)
                }
            };
            if let Err(error) = &result {
                report(machine, error);
            }
            if let Err(error) = result {
                errors.push(LineError {
                    line: statement.line,
                    error,
                });
            }
            if !matches!(instruction, Instruction::Nop) {
                after_output = crate::il::is_output(instruction);
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

/// The power flow: the top logic block (off when there is none).
fn power_of(blocks: &[bool]) -> bool {
    blocks.last().copied().unwrap_or(false)
}

/// Reads a contact, remembering the device state for the edge forms. An
/// index-modified contact out of range reads as off and returns the
/// operation error to report.
fn contact_value(
    contact: Contact,
    device: BitRef,
    memory: &mut Memory,
    machine: &Machine<'_>,
) -> (bool, Result<(), OperationError>) {
    let (state, read) = match operands::read_bit_ref(machine.devices, machine.hardware, device) {
        Ok(state) => (state, Ok(())),
        Err(error) => (false, Err(error)),
    };
    let previous = memory.previous;
    memory.previous = state;
    let value = match contact {
        Contact::Open => state,
        Contact::Closed => !state && read.is_ok(),
        Contact::Rising => state && !previous,
        Contact::Falling => !state && previous && read.is_ok(),
    };
    (value, read)
}

/// Whether an applied instruction runs this scan: continuous forms while the
/// power flow is on, `P` forms in the scan it turns on.
pub(crate) fn runs(exec: Exec, power: bool, memory: &mut Memory) -> bool {
    let rising = power && !memory.previous;
    memory.previous = power;
    match exec {
        Exec::Continuous => power,
        Exec::Pulse => rising,
    }
}
