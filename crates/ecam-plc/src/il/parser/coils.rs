//! Coils: OUT (bits, timers, counters), SET, RST, PLS/PLF, and ZRST.

use super::form::Form;
use super::operands::{arity, at, bit_dest, coil, is_set_value, source, wrong};
use crate::device::{C_32BIT_FIRST, Device};
use crate::il::error::{OperandError, StatementError};
use crate::il::instruction::{BitRef, Dest, Exec, Instruction, Source, Width, ZoneDevice};
use crate::il::operand::{Modified, Operand};

pub(super) fn out(ops: &[Operand]) -> Result<Instruction, StatementError> {
    match ops {
        [Operand::Timer(timer)] => Err(StatementError::TimerNeedsSetValue(*timer)),
        [Operand::Timer(timer), set] => {
            let preset = source("OUT", 1, set, Width::Word)?;
            match preset {
                preset if !is_set_value(preset) => Err(wrong(
                    "OUT",
                    1,
                    set,
                    "a K/H constant or a D register (optionally index-modified, D10Z0)",
                )),
                // FX timers take a set value of 0-32767.
                Source::Constant(v) if v < 0 => Err(at(
                    &format!("OUT T{timer}"),
                    1,
                    OperandError::TimerSetValue(v),
                )),
                preset => Ok(Instruction::OutTimer {
                    timer: *timer,
                    preset,
                }),
            }
        }
        [Operand::Device(Device::C(counter))] => {
            Err(StatementError::CounterNeedsSetValue(*counter))
        }
        [op] => Ok(Instruction::Out(coil("OUT", 0, op)?)),
        [Operand::Device(Device::C(counter)), set] => {
            let width = if *counter >= C_32BIT_FIRST {
                Width::Double
            } else {
                Width::Word
            };
            let set_value = source("OUT", 1, set, width)?;
            if !is_set_value(set_value) {
                return Err(wrong(
                    "OUT",
                    1,
                    set,
                    "a K/H constant or a D register (optionally index-modified, D10Z0)",
                ));
            }
            // FX 16-bit counters count up to a set value of 0-32767; a
            // negative one would make the contact on from the first scan.
            if let (Width::Word, Source::Constant(v)) = (width, set_value) {
                if v < 0 {
                    return Err(at(
                        &format!("OUT C{counter}"),
                        1,
                        OperandError::CounterSetValue(v),
                    ));
                }
            }
            Ok(Instruction::OutCounter {
                counter: *counter,
                set_value,
            })
        }
        [first, _] => Err(wrong(
            "OUT",
            0,
            first,
            "a counter C or a timer T (two operands are only for OUT Cn/Tn K<set value>)",
        )),
        _ => Err(StatementError::OutArity(ops.len())),
    }
}

/// `SET`: a Y, an M or `Dn.b`.
pub(super) fn set(mnemonic: &str, ops: &[Operand]) -> Result<Instruction, StatementError> {
    arity(mnemonic, ops, &["Y/M/Dn.b"])?;
    Ok(Instruction::Set(coil(mnemonic, 0, &ops[0])?))
}

/// `RST`: a bit, a register, a counter, a timer or an index register.
pub(super) fn reset(mnemonic: &str, ops: &[Operand]) -> Result<Instruction, StatementError> {
    arity(mnemonic, ops, &["Y/M/D/C/T/V/Z/Dn.b"])?;
    Ok(match ops[0] {
        Operand::Device(d @ (Device::Y(_) | Device::M(_) | Device::D(_) | Device::C(_))) => {
            Instruction::Reset(BitRef::Device(d))
        }
        Operand::WordBit(b) => Instruction::Reset(BitRef::WordBit(b)),
        Operand::Timer(n) => Instruction::Reset(BitRef::Timer(n)),
        Operand::Indexed(Modified::Device(d @ (Device::Y(_) | Device::M(_))), by) => {
            Instruction::Reset(BitRef::Indexed(d, by))
        }
        // RST Vn/Zn clears the register while the power flow is on:
        // exactly what a continuous `MOV K0 Zn` does.
        Operand::Index(register) => Instruction::Move {
            width: Width::Word,
            exec: Exec::Continuous,
            src: Source::Constant(0),
            dst: Dest::Index(register),
        },
        ref other => {
            return Err(wrong(
                mnemonic,
                0,
                other,
                "a Y, M, D, C, T, V or Z device or a bit Dn.b",
            ));
        }
    })
}

/// `PLS`/`PLF`: a Y or an M on for one scan at the edge.
pub(super) fn pulse(mnemonic: &str, ops: &[Operand]) -> Result<Instruction, StatementError> {
    arity(mnemonic, ops, &["Y/M"])?;
    Ok(Instruction::Pulse {
        rising: mnemonic == "PLS",
        dest: bit_dest(mnemonic, 0, &ops[0])?,
    })
}

/// `ZRST` D1 D2: RST over a range of one kind of device.
pub(super) fn zone_reset(form: Form<'_>, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let Form { mnemonic, exec, .. } = form;
    form.no_double()?;
    arity(mnemonic, ops, &["D1", "D2"])?;
    let (kind, first, last) = match (ops[0], ops[1]) {
        (Operand::Device(Device::M(a)), Operand::Device(Device::M(b))) => (ZoneDevice::M, a, b),
        (Operand::Device(Device::Y(a)), Operand::Device(Device::Y(b))) => (ZoneDevice::Y, a, b),
        (Operand::Device(Device::D(a)), Operand::Device(Device::D(b))) => (ZoneDevice::D, a, b),
        (Operand::Device(Device::C(a)), Operand::Device(Device::C(b))) => (ZoneDevice::C, a, b),
        _ => {
            return Err(StatementError::ZoneKinds {
                mnemonic: mnemonic.to_string(),
                first: ops[0].describe(),
                second: ops[1].describe(),
            });
        }
    };
    if first > last {
        return Err(StatementError::ZoneOrder {
            mnemonic: mnemonic.to_string(),
        });
    }
    Ok(Instruction::ZoneReset {
        exec,
        kind,
        first,
        last,
    })
}
