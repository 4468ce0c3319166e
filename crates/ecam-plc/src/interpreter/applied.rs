//! Coils and applied instructions (everything after the contacts).

use super::operands::{
    dest_value, device_error, read_source, resolve_dest, write_bit_ref, write_group, write_word,
};
use super::{Machine, Memory, runs};
use crate::device::Device;
use crate::device::DeviceError;
use crate::hardware::{OutputOwner, PulseTrain};
use crate::il::{ArithOp, BitRef, Dest, FloatSource, Instruction, LogicOp, Width, ZoneDevice};
use crate::operation_error::{CODE_OPERAND, OperationError};
use crate::special::{M_BORROW, M_CARRY, M_EXECUTION_COMPLETE, M_ZERO};

/// Highest PLSY frequency (16-bit operand).
const PLSY_MAX_HZ: i32 = 32_767;
/// Highest DPLSY frequency: the LX3V's 200 kHz pulse outputs (document 003,
/// "Maximum frequency of E-cam ... 200K").
const DPLSY_MAX_HZ: i32 = 200_000;

/// Executes a coil or applied instruction (statement `statement` of the
/// program) with power flow `power`.
pub(super) fn execute(
    instruction: &Instruction,
    statement: usize,
    power: bool,
    memory: &mut Memory,
    machine: &mut Machine<'_>,
) -> Result<(), OperationError> {
    let devices = &mut *machine.devices;
    match *instruction {
        Instruction::Out(dest) => write_bit_ref(devices, dest, power),
        Instruction::Set(dest) if power => write_bit_ref(devices, dest, true),
        Instruction::Reset(BitRef::Device(device)) if power => reset(machine, device),
        Instruction::Reset(BitRef::Timer(n)) if power => devices
            .timers_mut()
            .reset(n)
            .map_err(|e| device_error(format!("T{n}"), e)),
        Instruction::Reset(bit @ (BitRef::WordBit(_) | BitRef::Indexed(..))) if power => {
            write_bit_ref(devices, bit, false)
        }
        Instruction::Set(_) | Instruction::Reset(_) => Ok(()),
        Instruction::Pulse { rising, dest } => {
            let edge = if rising {
                power && !memory.previous
            } else {
                !power && memory.previous
            };
            memory.previous = power;
            devices
                .set_bit(dest.0, edge)
                .map_err(|e| device_error(dest.0, e))
        }
        Instruction::OutTimer { timer, preset } => {
            let preset = read_source(devices, preset, Width::Word)?;
            // A register set value reads as -32768..=32767; FX timers count
            // only up to 0..=32767, so a negative one is an operand error.
            let preset = i16::try_from(preset)
                .ok()
                .filter(|p| *p >= 0)
                .ok_or_else(|| {
                    OperationError::new(
                        CODE_OPERAND,
                        format!("T{timer} set value {preset} is negative (K0 to K32767)"),
                    )
                })?;
            devices
                .timers_mut()
                .drive(timer, power, preset, machine.now_us)
                .map_err(|e| device_error(format!("T{timer}"), e))
        }
        Instruction::OutCounter { counter, set_value } => {
            let width = if counter >= crate::device::C_32BIT_FIRST {
                Width::Double
            } else {
                Width::Word
            };
            let set_value = read_source(devices, set_value, width)?;
            machine
                .hardware
                .counters_mut()
                .drive_coil(devices, counter, power, set_value);
            Ok(())
        }
        Instruction::Move {
            width,
            exec,
            src,
            dst,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let value = read_source(devices, src, width)?;
            write_word(devices, dst, width, value)
        }
        Instruction::FloatMove { exec, src, dst } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let value = match src {
                FloatSource::Constant(v) => v,
                FloatSource::Register(n) => devices
                    .float(n)
                    .map_err(|e| device_error(Device::D(n), e))?,
            };
            devices
                .set_float(dst, value)
                .map_err(|e| device_error(Device::D(dst), e))
        }
        Instruction::ZoneReset {
            exec,
            kind,
            first,
            last,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            for n in first..=last {
                let device = match kind {
                    ZoneDevice::M => Device::M(n),
                    ZoneDevice::Y => Device::Y(n),
                    ZoneDevice::D => Device::D(n),
                    ZoneDevice::C => Device::C(n),
                };
                reset(machine, device)?;
            }
            Ok(())
        }
        Instruction::Arith {
            op,
            width,
            exec,
            s1,
            s2,
            dst,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let a = i64::from(read_source(devices, s1, width)?);
            let b = i64::from(read_source(devices, s2, width)?);
            // An index-modified destination out of range fails before the
            // flags move: the instruction is not executed at all.
            let words = if width == Width::Double { 2 } else { 1 };
            let dst = resolve_dest(devices, dst, width, words)?;
            let exact = match op {
                ArithOp::Add => a + b,
                ArithOp::Sub => a - b,
            };
            let (min, max) = match width {
                Width::Word => (i64::from(i16::MIN), i64::from(i16::MAX)),
                Width::Double => (i64::from(i32::MIN), i64::from(i32::MAX)),
            };
            // FX: the result wraps; M8022 carry above, M8021 borrow below, M8020 zero.
            let wrapped = match width {
                Width::Word => i32::from(exact as i16),
                Width::Double => exact as i32,
            };
            set_flag(devices, M_CARRY, exact > max)?;
            set_flag(devices, M_BORROW, exact < min)?;
            set_flag(devices, M_ZERO, wrapped == 0)?;
            write_word(devices, dst, width, wrapped)
        }
        Instruction::Multiply {
            width,
            exec,
            s1,
            s2,
            dst,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let a = i64::from(read_source(devices, s1, width)?);
            let b = i64::from(read_source(devices, s2, width)?);
            // |a·b| ≤ 2^62 for 32-bit operands: exact in i64, never wraps.
            let product = a.saturating_mul(b);
            let words = if width == Width::Double { 4 } else { 2 };
            match (resolve_dest(devices, dst, width, words)?, width) {
                (Dest::Register(n), Width::Word) => devices
                    .set_dword(n, product as i32)
                    .map_err(|e| device_error(Device::D(n), e)),
                (Dest::Register(n), Width::Double) => write_quad(devices, n, product),
                // A group takes the product's low n × 4 bits (K8 at most:
                // the low 32 bits of a DMUL product, as on the FX).
                (Dest::Group(g), _) => write_group(devices, g, product as i32),
                (other, _) => Err(device_error(other, DeviceError::WrongKind)),
            }
        }
        Instruction::Divide {
            width,
            exec,
            s1,
            s2,
            dst,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let a = read_source(devices, s1, width)?;
            let b = read_source(devices, s2, width)?;
            // FX3U manual (DIV, "Error"): divisor 0 is an operation error and
            // the instruction is not executed; it names no code, we use the
            // operand-value one.
            if b == 0 {
                return Err(OperationError::new(
                    CODE_OPERAND,
                    format!("division of {a} by zero (the result registers are unchanged)"),
                ));
            }
            // FX3U manual (DIV, "Error"): a quotient over 32767 (16 bit) or
            // 2147483647 (32 bit) is an operation error too.
            let too_big = match width {
                Width::Word => a == i32::from(i16::MIN) && b == -1,
                Width::Double => a == i32::MIN && b == -1,
            };
            if too_big {
                return Err(OperationError::new(
                    CODE_OPERAND,
                    format!(
                        "{a} / {b} is past the signed range (the result registers are unchanged)"
                    ),
                ));
            }
            let words = if width == Width::Double { 4 } else { 2 };
            // `resolve_dest` checked that all `words` registers exist.
            match (resolve_dest(devices, dst, width, words)?, width) {
                (Dest::Register(n), Width::Word) => {
                    let (a, b) = (a as i16, b as i16);
                    devices
                        .set_word(n, a.wrapping_div(b))
                        .and_then(|()| devices.set_word(n.saturating_add(1), a.wrapping_rem(b)))
                        .map_err(|e| device_error(Device::D(n), e))
                }
                (Dest::Register(n), Width::Double) => devices
                    .set_dword(n, a.wrapping_div(b))
                    .and_then(|()| devices.set_dword(n.saturating_add(2), a.wrapping_rem(b)))
                    .map_err(|e| device_error(Device::D(n), e)),
                // FX: a bit-device destination gets the quotient, no remainder.
                (Dest::Group(g), _) => write_group(devices, g, a.wrapping_div(b)),
                (other, _) => Err(device_error(other, DeviceError::WrongKind)),
            }
        }
        Instruction::Logic {
            op,
            width,
            exec,
            s1,
            s2,
            dst,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let a = read_source(devices, s1, width)?;
            let b = read_source(devices, s2, width)?;
            let value = match op {
                LogicOp::And => a & b,
                LogicOp::Or => a | b,
                LogicOp::Xor => a ^ b,
            };
            write_word(devices, dst, width, value)
        }
        Instruction::Negate { width, exec, dst } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let words = if width == Width::Double { 2 } else { 1 };
            let dst = resolve_dest(devices, dst, width, words)?;
            let value = dest_value(devices, dst, width)?;
            let negated = match width {
                Width::Word => i32::from((value as i16).wrapping_neg()),
                Width::Double => value.wrapping_neg(),
            };
            write_word(devices, dst, width, negated)
        }
        Instruction::Step {
            up,
            width,
            exec,
            dst,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let words = if width == Width::Double { 2 } else { 1 };
            let dst = resolve_dest(devices, dst, width, words)?;
            let value = dest_value(devices, dst, width)?;
            let next = if up {
                value.wrapping_add(1)
            } else {
                value.wrapping_sub(1)
            };
            let next = match width {
                Width::Word => i32::from(next as i16),
                Width::Double => next,
            };
            write_word(devices, dst, width, next)
        }
        Instruction::Compare {
            width,
            exec,
            s1,
            s2,
            dst,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let a = read_source(devices, s1, width)?;
            let b = read_source(devices, s2, width)?;
            set_three(devices, dst, [a > b, a == b, a < b])
        }
        Instruction::ZoneCompare {
            width,
            exec,
            low,
            high,
            value,
            dst,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let low = read_source(devices, low, width)?;
            // FX3U: a lower limit above the upper one counts as both.
            let high = read_source(devices, high, width)?.max(low);
            let value = read_source(devices, value, width)?;
            set_three(
                devices,
                dst,
                [value < low, (low..=high).contains(&value), value > high],
            )
        }
        Instruction::BlockMove {
            exec,
            src,
            dst,
            count,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let n = block_len(devices, count)?;
            let from = block_start(devices, src, n)?;
            let to = block_start(devices, dst, n)?;
            // Through a buffer: overlapping blocks copy as the FX3U does.
            let words: Vec<i16> = (0..n)
                .map(|i| devices.word(from + i))
                .collect::<Result<_, _>>()
                .map_err(|e| device_error(Device::D(from), e))?;
            for (i, word) in (0..n).zip(words) {
                devices
                    .set_word(to + i, word)
                    .map_err(|e| device_error(Device::D(to + i), e))?;
            }
            Ok(())
        }
        Instruction::Fill {
            width,
            exec,
            src,
            dst,
            count,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            let value = read_source(devices, src, width)?;
            let n = block_len(devices, count)?;
            let stride = if width == Width::Double { 2 } else { 1 };
            let to = block_start(devices, dst, n * stride)?;
            for i in 0..n {
                let at = to + i * stride;
                match width {
                    Width::Word => devices.set_word(at, value as i16),
                    Width::Double => devices.set_dword(at, value),
                }
                .map_err(|e| device_error(Device::D(at), e))?;
            }
            Ok(())
        }
        Instruction::BitShift {
            left,
            exec,
            src,
            dst,
            length,
            places,
        } => {
            if !runs(exec, power, memory) {
                return Ok(());
            }
            // Read everything first: S may overlap D.
            let incoming = read_bits(devices, src, places)?;
            let block = read_bits(devices, dst, length)?;
            let kept = usize::from(length - places);
            let shifted: Vec<bool> = if left {
                incoming.iter().chain(&block[..kept]).copied().collect()
            } else {
                block[usize::from(places)..]
                    .iter()
                    .chain(&incoming)
                    .copied()
                    .collect()
            };
            for (i, on) in (0u16..).zip(shifted) {
                let device = nth_bit(dst, i)?;
                devices
                    .set_bit(device, on)
                    .map_err(|e| device_error(device, e))?;
            }
            Ok(())
        }
        Instruction::PulseOutput {
            width,
            frequency,
            count,
            output,
        } => pulse_output(
            machine,
            memory,
            (OutputOwner::PulseTrain(statement), power),
            width,
            (frequency, count),
            output,
        ),
        Instruction::Ecamtbx {
            params,
            kind,
            table,
            result,
        } => {
            if !power {
                return Ok(());
            }
            let kind = read_source(devices, kind, Width::Double)?;
            crate::ecamtbx::execute(devices, params, kind, table, result)
        }
        // Contacts, stack instructions and DECAM are handled by the scan loop.
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
        | Instruction::Label(_)
        | Instruction::Jump { .. }
        | Instruction::Call { .. }
        | Instruction::SubReturn
        | Instruction::MainEnd
        | Instruction::Decam { .. } => Ok(()),
    }
}

/// Writes a 64-bit value into D n…n+3, lowest word first (DMUL).
fn write_quad(
    devices: &mut crate::devices::Devices,
    n: u16,
    value: i64,
) -> Result<(), OperationError> {
    let high = n
        .checked_add(2)
        .ok_or_else(|| device_error(Device::D(n), DeviceError::OutOfRange))?;
    // The parser checked that D n+3 exists; check again before writing anything.
    devices
        .word(high.saturating_add(1))
        .map_err(|e| device_error(Device::D(n), e))?;
    devices
        .set_dword(n, value as i32)
        .and_then(|()| devices.set_dword(high, (value >> 32) as i32))
        .map_err(|e| device_error(Device::D(n), e))
}

/// Writes the three result bits of CMP/ZCP from `dst` on (the parser
/// checked that all three exist).
fn set_three(
    devices: &mut crate::devices::Devices,
    dst: Device,
    bits: [bool; 3],
) -> Result<(), OperationError> {
    for (offset, on) in (0u16..).zip(bits) {
        let device = match dst {
            Device::M(n) => Device::M(n.saturating_add(offset)),
            Device::Y(n) => Device::Y(n.saturating_add(offset)),
            other => other,
        };
        devices
            .set_bit(device, on)
            .map_err(|e| device_error(device, e))?;
    }
    Ok(())
}

/// The bit `i` places after `first` (X, Y or M).
fn nth_bit(first: Device, i: u16) -> Result<Device, OperationError> {
    let next = |n: u16| {
        n.checked_add(i)
            .ok_or_else(|| device_error(first, DeviceError::OutOfRange))
    };
    match first {
        Device::X(n) => next(n).map(Device::X),
        Device::Y(n) => next(n).map(Device::Y),
        Device::M(n) => next(n).map(Device::M),
        other => Err(device_error(other, DeviceError::WrongKind)),
    }
}

/// `count` consecutive bits from `first`, lowest first.
fn read_bits(
    devices: &crate::devices::Devices,
    first: Device,
    count: u16,
) -> Result<Vec<bool>, OperationError> {
    (0..count)
        .map(|i| {
            let device = nth_bit(first, i)?;
            devices.bit(device).map_err(|e| device_error(device, e))
        })
        .collect()
}

/// n of BMOV/FMOV: 1–512, else operation error 6705.
fn block_len(
    devices: &crate::devices::Devices,
    count: crate::il::Source,
) -> Result<u16, OperationError> {
    let n = read_source(devices, count, Width::Word)?;
    u16::try_from(n)
        .ok()
        .filter(|n| (1..=crate::il::BLOCK_MAX).contains(&i32::from(*n)))
        .ok_or_else(|| {
            OperationError::new(
                CODE_OPERAND,
                format!(
                    "block length n = {n} is out of range (1 to {}); nothing was moved",
                    crate::il::BLOCK_MAX
                ),
            )
        })
}

/// The first register of a BMOV/FMOV block of `words` registers, index
/// modification applied; 6706 when the block runs past D8511.
fn block_start(
    devices: &crate::devices::Devices,
    start: Dest,
    words: u16,
) -> Result<u16, OperationError> {
    match resolve_dest(devices, start, Width::Word, words)? {
        Dest::Register(n)
            if n.checked_add(words)
                .is_some_and(|end| end <= crate::device::D_COUNT) =>
        {
            Ok(n)
        }
        other => Err(OperationError::new(
            crate::operation_error::CODE_DEVICE_RANGE,
            format!("a block of {words} registers from {other} runs past D8511; nothing was moved"),
        )),
    }
}

fn set_flag(devices: &mut crate::devices::Devices, m: u16, on: bool) -> Result<(), OperationError> {
    devices
        .set_m(m, on)
        .map_err(|e| device_error(Device::M(m), e))
}

/// RST of one device: bits off, words and counters to 0.
fn reset(machine: &mut Machine<'_>, device: Device) -> Result<(), OperationError> {
    let devices = &mut *machine.devices;
    match device {
        Device::D(n) => devices.set_word(n, 0),
        Device::C(n) => {
            // The latched contact goes off with the value.
            Device::C(n).check().map_err(|e| device_error(device, e))?;
            machine.hardware.counters_mut().reset(devices, n);
            Ok(())
        }
        bit => devices.set_bit(bit, false),
    }
    .map_err(|e| device_error(device, e))
}

/// PLSY/DPLSY: starts a pulse train when the power flow turns on, follows
/// frequency changes while it runs, stops it when the power flow goes off;
/// a finished train turns M8029 on and is not restarted until the power flow
/// has been off.
///
/// One instruction drives an output at a time (the FX rule): while another
/// PLSY/DPLSY or a DECAM holds the output, the train does not start; it
/// starts in the first scan that finds the output free with the power flow
/// still on. Nothing is flagged meanwhile (as on the FX).
fn pulse_output(
    machine: &mut Machine<'_>,
    memory: &mut Memory,
    (owner, power): (OutputOwner, bool),
    width: Width,
    (frequency, count): (crate::il::Source, crate::il::Source),
    output: u8,
) -> Result<(), OperationError> {
    let devices = &mut *machine.devices;
    let hardware = &mut *machine.hardware;
    if !power {
        if memory.latched {
            hardware.stop_pulse_train(output, owner);
            memory.latched = false;
            set_flag(devices, M_EXECUTION_COMPLETE, false)?;
        }
        return Ok(());
    }
    let max_hz = if width == Width::Double {
        DPLSY_MAX_HZ
    } else {
        PLSY_MAX_HZ
    };
    let hz = read_source(devices, frequency, width)?;
    let pulses = read_source(devices, count, width)?;
    let name = if width == Width::Double {
        "DPLSY"
    } else {
        "PLSY"
    };
    let invalid = if !(0..=max_hz).contains(&hz) {
        Some(format!(
            "{name} frequency {hz} Hz is out of range (0-{max_hz})"
        ))
    } else if pulses < 0 {
        Some(format!(
            "{name} pulse count {pulses} is negative (0 = endless)"
        ))
    } else {
        None
    };
    if let Some(message) = invalid {
        hardware.stop_pulse_train(output, owner);
        return Err(OperationError::new(CODE_OPERAND, message));
    }
    let hz = hz.unsigned_abs();
    if !memory.latched {
        let train = PulseTrain::new(hz, u64::from(pulses.unsigned_abs()));
        if hardware.start_pulse_train(output, owner, train) {
            memory.latched = true;
            set_flag(devices, M_EXECUTION_COMPLETE, false)?;
        }
    } else if hardware.owner(output) == Some(owner) {
        hardware.set_train_frequency(output, owner, hz);
    } else {
        set_flag(devices, M_EXECUTION_COMPLETE, true)?;
    }
    Ok(())
}
