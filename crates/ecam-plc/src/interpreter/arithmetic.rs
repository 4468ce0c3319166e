//! Arithmetic and logic on words: ADD/SUB, MUL, DIV, WAND/WOR/WXOR,
//! NEG and INC/DEC, each in its 16- and 32-bit form.

use super::operands::{
    dest_value, device_error, read_source, resolve_dest, set_flag, write_group, write_word,
};
use crate::device::{Device, DeviceError};
use crate::devices::Devices;
use crate::il::{ArithOp, Dest, LogicOp, Source, Width};
use crate::operation_error::{CODE_OPERAND, OperationError};
use crate::special::{M_BORROW, M_CARRY, M_ZERO};

/// `ADD`/`SUB` S1 S2 D: the result wraps; M8022 carry above, M8021 borrow
/// below, M8020 zero (FX).
pub(super) fn add_sub(
    devices: &mut Devices,
    (op, width): (ArithOp, Width),
    (s1, s2): (Source, Source),
    dst: Dest,
) -> Result<(), OperationError> {
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
    let wrapped = match width {
        Width::Word => i32::from(exact as i16),
        Width::Double => exact as i32,
    };
    set_flag(devices, M_CARRY, exact > max)?;
    set_flag(devices, M_BORROW, exact < min)?;
    set_flag(devices, M_ZERO, wrapped == 0)?;
    write_word(devices, dst, width, wrapped)
}

/// `MUL`/`DMUL` S1 S2 D: the product, twice as wide as the operands.
pub(super) fn multiply(
    devices: &mut Devices,
    width: Width,
    (s1, s2): (Source, Source),
    dst: Dest,
) -> Result<(), OperationError> {
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

/// `DIV`/`DDIV` S1 S2 D: quotient and remainder.
pub(super) fn divide(
    devices: &mut Devices,
    width: Width,
    (s1, s2): (Source, Source),
    dst: Dest,
) -> Result<(), OperationError> {
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
            format!("{a} / {b} is past the signed range (the result registers are unchanged)"),
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

/// `WAND`/`WOR`/`WXOR` (`DAND`/`DOR`/`DXOR`) S1 S2 D.
pub(super) fn logic(
    devices: &mut Devices,
    (op, width): (LogicOp, Width),
    (s1, s2): (Source, Source),
    dst: Dest,
) -> Result<(), OperationError> {
    let a = read_source(devices, s1, width)?;
    let b = read_source(devices, s2, width)?;
    let value = match op {
        LogicOp::And => a & b,
        LogicOp::Or => a | b,
        LogicOp::Xor => a ^ b,
    };
    write_word(devices, dst, width, value)
}

/// `NEG`/`DNEG` D: two's complement in place, wrapping.
pub(super) fn negate(devices: &mut Devices, width: Width, dst: Dest) -> Result<(), OperationError> {
    let words = if width == Width::Double { 2 } else { 1 };
    let dst = resolve_dest(devices, dst, width, words)?;
    let value = dest_value(devices, dst, width)?;
    let negated = match width {
        Width::Word => i32::from((value as i16).wrapping_neg()),
        Width::Double => value.wrapping_neg(),
    };
    write_word(devices, dst, width, negated)
}

/// `INC` (`up`) / `DEC` D: ±1, wrapping, no flags (FX).
pub(super) fn step(
    devices: &mut Devices,
    (up, width): (bool, Width),
    dst: Dest,
) -> Result<(), OperationError> {
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

/// Writes a 64-bit value into D n…n+3, lowest word first (DMUL).
fn write_quad(devices: &mut Devices, n: u16, value: i64) -> Result<(), OperationError> {
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
