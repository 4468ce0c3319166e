//! Which family executes which instruction: every instruction but program
//! flow (CJ, CALL, SRET, FEND: the scan loop's own) goes to the function of
//! its family with its operands; applied instructions run only when their
//! execution condition holds (`P` forms once per rising power flow).

use super::machine::{Machine, Memory, runs};
use super::power_flow::PowerFlow;
use super::{arithmetic, cam, coils, comparison, contacts, moves, pulse_output, shift};
use crate::hardware::OutputOwner;
use crate::il::{Exec, Instruction, Join};
use crate::operation_error::OperationError;

/// Where an instruction stands in the program.
#[derive(Clone, Copy)]
pub(super) struct Statement {
    /// Its index among the statements (a PLSY's identity as output owner).
    pub(super) index: usize,
    /// For a DECAM, its number in program order.
    pub(super) decam: Option<usize>,
}

/// Executes one instruction other than program flow, by family.
pub(super) fn execute(
    instruction: &Instruction,
    at: Statement,
    (power_flow, after_output): (&mut PowerFlow, bool),
    memory: &mut Memory,
    machine: &mut Machine<'_>,
) -> Result<(), OperationError> {
    let power = power_flow.power();
    // The `P` forms run in the scan their power flow turns on.
    let mut runs = |exec: Exec| runs(exec, power, memory);
    let devices = &mut *machine.devices;
    match *instruction {
        // Contacts and the power-flow stack.
        Instruction::Load(contact, device)
        | Instruction::And(contact, device)
        | Instruction::Or(contact, device) => {
            let (value, read) = contacts::bit_contact(contact, device, memory, machine);
            power_flow.join(join_of(instruction), value, after_output);
            read
        }
        Instruction::CompareContact {
            join,
            relation,
            width,
            s1,
            s2,
        } => {
            let (value, read) = contacts::compare_contact(relation, width, (s1, s2), machine);
            power_flow.join(join, value, after_output);
            read
        }
        Instruction::AndBlock => {
            power_flow.join_blocks(true);
            Ok(())
        }
        Instruction::OrBlock => {
            power_flow.join_blocks(false);
            Ok(())
        }
        Instruction::Push => {
            power_flow.push();
            Ok(())
        }
        Instruction::Read => {
            power_flow.restore(true);
            Ok(())
        }
        Instruction::Pop => {
            power_flow.restore(false);
            Ok(())
        }
        // Coils.
        Instruction::Out(dest) => coils::out(machine, dest, power),
        Instruction::Set(dest) => coils::set(machine, dest, power),
        Instruction::Reset(dest) => coils::reset(machine, dest, power),
        Instruction::Pulse { rising, dest } => coils::pulse(machine, (rising, dest), power, memory),
        Instruction::OutTimer { timer, preset } => coils::timer(machine, (timer, preset), power),
        Instruction::OutCounter { counter, set_value } => {
            coils::counter(machine, (counter, set_value), power)
        }
        Instruction::ZoneReset {
            exec,
            kind,
            first,
            last,
        } => gated(runs(exec), || {
            coils::zone_reset(machine, kind, (first, last))
        }),
        // Transfers.
        Instruction::Move {
            width,
            exec,
            src,
            dst,
        } => gated(runs(exec), || moves::mov(devices, width, src, dst)),
        Instruction::FloatMove { exec, src, dst } => {
            gated(runs(exec), || moves::float_move(devices, src, dst))
        }
        Instruction::BlockMove {
            exec,
            src,
            dst,
            count,
        } => gated(runs(exec), || moves::block_move(devices, src, dst, count)),
        Instruction::Fill {
            width,
            exec,
            src,
            dst,
            count,
        } => gated(runs(exec), || {
            moves::fill(devices, width, (src, dst), count)
        }),
        // Arithmetic and logic.
        Instruction::Arith {
            op,
            width,
            exec,
            s1,
            s2,
            dst,
        } => gated(runs(exec), || {
            arithmetic::add_sub(devices, (op, width), (s1, s2), dst)
        }),
        Instruction::Multiply {
            width,
            exec,
            s1,
            s2,
            dst,
        } => gated(runs(exec), || {
            arithmetic::multiply(devices, width, (s1, s2), dst)
        }),
        Instruction::Divide {
            width,
            exec,
            s1,
            s2,
            dst,
        } => gated(runs(exec), || {
            arithmetic::divide(devices, width, (s1, s2), dst)
        }),
        Instruction::Logic {
            op,
            width,
            exec,
            s1,
            s2,
            dst,
        } => gated(runs(exec), || {
            arithmetic::logic(devices, (op, width), (s1, s2), dst)
        }),
        Instruction::Negate { width, exec, dst } => {
            gated(runs(exec), || arithmetic::negate(devices, width, dst))
        }
        Instruction::Step {
            up,
            width,
            exec,
            dst,
        } => gated(runs(exec), || arithmetic::step(devices, (up, width), dst)),
        // Comparisons into bits.
        Instruction::Compare {
            width,
            exec,
            s1,
            s2,
            dst,
        } => gated(runs(exec), || {
            comparison::compare(devices, width, (s1, s2), dst)
        }),
        Instruction::ZoneCompare {
            width,
            exec,
            low,
            high,
            value,
            dst,
        } => gated(runs(exec), || {
            comparison::zone_compare(devices, width, (low, high, value), dst)
        }),
        // Shifts.
        Instruction::BitShift {
            left,
            exec,
            src,
            dst,
            length,
            places,
        } => gated(runs(exec), || {
            shift::bit_shift(devices, left, (src, dst), (length, places))
        }),
        // Pulse output and the E-cam instructions.
        Instruction::PulseOutput {
            width,
            frequency,
            count,
            output,
        } => pulse_output::plsy(
            machine,
            memory,
            (OutputOwner::PulseTrain(at.index), power),
            width,
            (frequency, count),
            output,
        ),
        Instruction::Decam { .. } => cam::decam(machine, at.decam, power),
        Instruction::Ecamtbx {
            params,
            kind,
            table,
            result,
        } => cam::ecamtbx(machine, power, (params, kind), (table, result)),
        // Program flow is handled by the scan loop; labels and NOP do nothing.
        Instruction::Jump { .. }
        | Instruction::Call { .. }
        | Instruction::SubReturn
        | Instruction::MainEnd
        | Instruction::Label(_)
        | Instruction::Nop => Ok(()),
    }
}

/// How a bit contact joins the power flow.
fn join_of(instruction: &Instruction) -> Join {
    match instruction {
        Instruction::And(..) => Join::And,
        Instruction::Or(..) => Join::Or,
        _ => Join::Load,
    }
}

/// Runs `instruction` when its execution condition holds this scan.
fn gated(
    run: bool,
    instruction: impl FnOnce() -> Result<(), OperationError>,
) -> Result<(), OperationError> {
    if run { instruction() } else { Ok(()) }
}
