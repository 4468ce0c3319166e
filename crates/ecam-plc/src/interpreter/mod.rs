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
}

impl Interpreter {
    /// Fresh state for `program`.
    pub fn new(program: &Program) -> Self {
        Self {
            memory: vec![Memory::default(); program.statements.len()],
            blocks: Vec::new(),
            pushed: Vec::new(),
        }
    }

    /// Runs every statement once. An instruction that fails does not stop the
    /// scan (as on the PLC); its error is returned with its line.
    pub fn scan(&mut self, program: &Program, machine: &mut Machine<'_>) -> Vec<LineError> {
        let mut errors = Vec::new();
        self.blocks.clear();
        self.pushed.clear();
        let mut after_output = true;
        let mut decam_index = 0usize;
        for (index, statement) in program.statements.iter().enumerate() {
            let Some(memory) = self.memory.get_mut(index) else {
                break;
            };
            let instruction = &statement.instruction;
            let result = match instruction {
                Instruction::Load(contact, device) => {
                    let value = contact_value(*contact, *device, memory, machine);
                    if after_output && self.pushed.is_empty() {
                        self.blocks.clear();
                    }
                    self.blocks.push(value);
                    Ok(())
                }
                Instruction::And(contact, device) => {
                    let value = contact_value(*contact, *device, memory, machine);
                    if let Some(top) = self.blocks.last_mut() {
                        *top = *top && value;
                    }
                    Ok(())
                }
                Instruction::Or(contact, device) => {
                    let value = contact_value(*contact, *device, memory, machine);
                    if let Some(top) = self.blocks.last_mut() {
                        *top = *top || value;
                    }
                    Ok(())
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
                Instruction::Nop => Ok(()),
                Instruction::Decam { .. } => {
                    let power = power_of(&self.blocks);
                    let result = match machine.decams.get_mut(decam_index) {
                        Some(decam) => decam.execute(power, machine.devices, machine.now_us),
                        None => Ok(()),
                    };
                    decam_index += 1;
                    result
                }
                other => {
                    let power = power_of(&self.blocks);
                    applied::execute(other, index, power, memory, machine)
                }
            };
            if let Err(error) = &result {
                // The FX way, at once: an instruction later in this scan can
                // test M8067 (or reset it) and see this error.
                let _ = machine
                    .devices
                    .set_word(crate::special::D_OPERATION_ERROR, error.code as i16);
                let _ = machine
                    .devices
                    .set_m(crate::special::M_OPERATION_ERROR, true);
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
        errors
    }
}

/// The power flow: the top logic block (off when there is none).
fn power_of(blocks: &[bool]) -> bool {
    blocks.last().copied().unwrap_or(false)
}

/// Reads a contact, remembering the device state for the edge forms.
fn contact_value(
    contact: Contact,
    device: BitRef,
    memory: &mut Memory,
    machine: &Machine<'_>,
) -> bool {
    let state = operands::read_bit_ref(machine.devices, machine.hardware, device);
    let previous = memory.previous;
    memory.previous = state;
    match contact {
        Contact::Open => state,
        Contact::Closed => !state,
        Contact::Rising => state && !previous,
        Contact::Falling => !state && previous,
    }
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
