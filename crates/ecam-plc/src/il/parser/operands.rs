//! Operands checked against the instruction that takes them: what each
//! place accepts (a bit, a coil, a source, a destination, a block, a pulse
//! output), constants at the instruction's width, index modifiers, and the
//! messages that say what was expected.

use crate::device::{D_COUNT, Device, M_COUNT, XY_COUNT};
use crate::il::error::{OperandError, StatementError};
use crate::il::instruction::{BitDest, BitRef, Dest, IndexBase, Indexed, Source, Width};
use crate::il::limits::BLOCK_MAX;
use crate::il::operand::{Modified, Operand};
use crate::index_register::IndexReg;

/// Checks the operand count; the message names the expected operands.
pub(super) fn arity(
    mnemonic: &str,
    operands: &[Operand],
    names: &'static [&'static str],
) -> Result<(), StatementError> {
    if operands.len() == names.len() {
        Ok(())
    } else {
        Err(StatementError::Arity {
            mnemonic: mnemonic.to_string(),
            names,
            found: operands.len(),
        })
    }
}

/// The problem of operand `index` (from 0) of `mnemonic`.
pub(super) fn at(mnemonic: &str, index: usize, problem: impl Into<OperandError>) -> StatementError {
    StatementError::Operand {
        mnemonic: mnemonic.to_string(),
        position: index + 1,
        problem: problem.into(),
    }
}

/// Operand `index` of `mnemonic` is of the wrong kind.
pub(super) fn wrong(
    mnemonic: &str,
    index: usize,
    operand: &Operand,
    expected: &'static str,
) -> StatementError {
    at(
        mnemonic,
        index,
        OperandError::Wrong {
            expected,
            found: operand.describe(),
            indexed: matches!(operand, Operand::Indexed(..)),
        },
    )
}

/// The set value of a timer or counter coil: a K/H constant or a D
/// register, which may be index-modified (FX3U).
pub(super) fn is_set_value(source: Source) -> bool {
    matches!(
        source,
        Source::Constant(_)
            | Source::Register(_)
            | Source::Indexed(Indexed {
                base: IndexBase::Register(_),
                ..
            })
    )
}

pub(super) fn bit_source(
    mnemonic: &str,
    index: usize,
    op: &Operand,
) -> Result<BitRef, StatementError> {
    match op {
        Operand::Device(d @ (Device::X(_) | Device::Y(_) | Device::M(_) | Device::C(_))) => {
            Ok(BitRef::Device(*d))
        }
        Operand::WordBit(b) => Ok(BitRef::WordBit(*b)),
        Operand::Timer(n) => Ok(BitRef::Timer(*n)),
        Operand::Indexed(
            Modified::Device(d @ (Device::X(_) | Device::Y(_) | Device::M(_) | Device::C(_))),
            by,
        ) => Ok(BitRef::Indexed(*d, *by)),
        Operand::Indexed(Modified::Timer(n), by) => Ok(BitRef::IndexedTimer(*n, *by)),
        other => Err(wrong(
            mnemonic,
            index,
            other,
            "a bit device X, Y, M, a counter contact C, a timer contact T (each optionally index-modified, C5Z0) or a bit of a register Dn.b",
        )),
    }
}

/// Operand of OUT and SET: Y, M or `Dn.b`.
pub(super) fn coil(mnemonic: &str, index: usize, op: &Operand) -> Result<BitRef, StatementError> {
    match op {
        Operand::Device(d @ (Device::Y(_) | Device::M(_))) => Ok(BitRef::Device(*d)),
        Operand::WordBit(b) => Ok(BitRef::WordBit(*b)),
        Operand::Indexed(Modified::Device(d @ (Device::Y(_) | Device::M(_))), by) => {
            Ok(BitRef::Indexed(*d, *by))
        }
        other => Err(wrong(
            mnemonic,
            index,
            other,
            "an output Y, a relay M (optionally index-modified, M0Z1) or a bit of a register Dn.b",
        )),
    }
}

pub(super) fn bit_dest(
    mnemonic: &str,
    index: usize,
    op: &Operand,
) -> Result<BitDest, StatementError> {
    match op {
        Operand::Device(d @ (Device::Y(_) | Device::M(_))) => Ok(BitDest(*d)),
        other => Err(wrong(mnemonic, index, other, "an output Y or a relay M")),
    }
}

/// The result bits of CMP/ZCP: M or Y, with the two bits after it.
pub(super) fn three_bits(
    mnemonic: &str,
    index: usize,
    op: &Operand,
) -> Result<Device, StatementError> {
    let dst = bit_dest(mnemonic, index, op)?.0;
    let last_ok = match dst {
        Device::M(n) => n.checked_add(2).is_some_and(|l| l < M_COUNT),
        Device::Y(n) => n.checked_add(2).is_some_and(|l| l < XY_COUNT),
        _ => false,
    };
    if last_ok {
        Ok(dst)
    } else {
        Err(at(mnemonic, index, OperandError::ThreeBits(dst)))
    }
}

/// Whether `bits` consecutive bit devices from `first` exist.
pub(super) fn bits_exist(first: Device, bits: u16) -> bool {
    let (n, count) = match first {
        Device::X(n) | Device::Y(n) => (n, XY_COUNT),
        Device::M(n) => (n, M_COUNT),
        _ => return false,
    };
    u32::from(n) + u32::from(bits) <= u32::from(count)
}

/// A block of BMOV/FMOV: the first D register, optionally index-modified
/// (the length is checked when the instruction runs).
pub(super) fn block(mnemonic: &str, index: usize, op: &Operand) -> Result<Dest, StatementError> {
    match *op {
        Operand::Device(Device::D(n)) => Ok(Dest::Register(n)),
        Operand::Indexed(Modified::Device(Device::D(n)), by) => Ok(Dest::Indexed(Indexed {
            base: IndexBase::Register(n),
            by: modifier(mnemonic, index, op, by, Width::Word)?,
        })),
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a D register (optionally index-modified)",
        )),
    }
}

/// n of BMOV/FMOV: K1–K512, or a D register read at run time (the blocks
/// are checked against D8511 when the instruction runs, as their start
/// may be index-modified).
pub(super) fn block_count(
    mnemonic: &str,
    index: usize,
    op: &Operand,
) -> Result<Source, StatementError> {
    match *op {
        Operand::Decimal(n) if (1..=i64::from(BLOCK_MAX)).contains(&n) => {
            Ok(Source::Constant(n as i32))
        }
        Operand::Decimal(n) => Err(at(mnemonic, index, OperandError::BlockCount(n))),
        Operand::Device(Device::D(n)) => Ok(Source::Register(n)),
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a K constant 1-512 or a D register",
        )),
    }
}

pub(super) fn register(
    mnemonic: &str,
    index: usize,
    n: u16,
    width: Width,
) -> Result<u16, StatementError> {
    if width == Width::Double && n.checked_add(1).is_none_or(|hi| hi >= D_COUNT) {
        return Err(at(mnemonic, index, OperandError::NoHighWord(n)));
    }
    Ok(n)
}

pub(super) fn source(
    mnemonic: &str,
    index: usize,
    op: &Operand,
    width: Width,
) -> Result<Source, StatementError> {
    let out_of_range = |range: &'static str| {
        at(
            mnemonic,
            index,
            OperandError::OutOfRange {
                operand: op.describe(),
                range,
            },
        )
    };
    match (*op, width) {
        (Operand::Decimal(v), _) => constant(v, None, width)
            .map(Source::Constant)
            .map_err(out_of_range),
        (Operand::Hex(v), _) => constant(i64::try_from(v).unwrap_or(i64::MAX), Some(v), width)
            .map(Source::Constant)
            .map_err(out_of_range),
        (Operand::Device(Device::D(n)), _) => {
            Ok(Source::Register(register(mnemonic, index, n, width)?))
        }
        (Operand::Device(Device::C(n)), _) => Ok(Source::Counter(n)),
        (Operand::Timer(n), Width::Word) => Ok(Source::Timer(n)),
        (Operand::Group(g), Width::Word) if g.digits > 4 => Err(at(
            mnemonic,
            index,
            OperandError::GroupTooWide16 {
                group: g.to_string(),
                digits: g.digits,
            },
        )),
        (Operand::Group(g), _) => Ok(Source::Group(g)),
        (Operand::Index(reg), _) => Ok(Source::Index(index_register(mnemonic, index, reg, width)?)),
        (Operand::Indexed(base, by), _) => {
            let by = modifier(mnemonic, index, op, by, width)?;
            let base = match base {
                Modified::Decimal(v) => constant(v, None, width)
                    .map(IndexBase::Constant)
                    .map_err(out_of_range)?,
                Modified::Hex(v) => constant(i64::try_from(v).unwrap_or(i64::MAX), Some(v), width)
                    .map(IndexBase::Constant)
                    .map_err(out_of_range)?,
                Modified::Device(Device::D(n)) => {
                    IndexBase::Register(register(mnemonic, index, n, width)?)
                }
                Modified::Device(Device::C(n)) => IndexBase::Counter(n),
                Modified::Timer(n) if width == Width::Word => IndexBase::Timer(n),
                Modified::Group(g) if width == Width::Word && g.digits > 4 => {
                    return Err(at(
                        mnemonic,
                        index,
                        OperandError::GroupTooWide16 {
                            group: g.to_string(),
                            digits: g.digits,
                        },
                    ));
                }
                Modified::Group(g) => IndexBase::Group(g),
                _ => {
                    return Err(wrong(
                        mnemonic,
                        index,
                        op,
                        "a K/H constant, D, C, (16 bit) T or a word group, index-modified",
                    ));
                }
            };
            Ok(Source::Indexed(Indexed { base, by }))
        }
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a K/H constant, a D register, a counter C, a word group KnM/KnX/KnY, an index register V/Z or (16 bit) a timer T",
        )),
    }
}

/// A K (`hex` = None) or H constant at the instruction's width: its value,
/// or the allowed range for the message. H constants are bit patterns
/// (HFFFF is −1 at 16 bit).
pub(super) fn constant(value: i64, hex: Option<u64>, width: Width) -> Result<i32, &'static str> {
    match (hex, width) {
        (None, Width::Word) => i16::try_from(value)
            .map(i32::from)
            .map_err(|_| "K-32768 to K32767"),
        (None, Width::Double) => i32::try_from(value).map_err(|_| "K-2147483648 to K2147483647"),
        (Some(v), Width::Word) => u16::try_from(v)
            .map(|v| i32::from(v as i16))
            .map_err(|_| "H0 to HFFFF"),
        (Some(v), Width::Double) => u32::try_from(v)
            .map(|v| v as i32)
            .map_err(|_| "H0 to HFFFFFFFF"),
    }
}

/// An index register as a whole operand: at 32 bit only Zn, which names
/// the pair Vn:Zn (FX3U).
pub(super) fn index_register(
    mnemonic: &str,
    index: usize,
    reg: IndexReg,
    width: Width,
) -> Result<IndexReg, StatementError> {
    match (reg, width) {
        (IndexReg::V(n), Width::Double) => Err(at(mnemonic, index, OperandError::PairByV(n))),
        _ => Ok(reg),
    }
}

/// The modifier of an index-modified operand: at 32 bit only Zn (the
/// offset is then the 32-bit pair Vn:Zn, FX3U rule).
pub(super) fn modifier(
    mnemonic: &str,
    index: usize,
    op: &Operand,
    by: IndexReg,
    width: Width,
) -> Result<IndexReg, StatementError> {
    match (by, width) {
        (IndexReg::V(n), Width::Double) => Err(at(
            mnemonic,
            index,
            OperandError::ModifierV {
                operand: op.describe(),
                n,
            },
        )),
        _ => Ok(by),
    }
}

/// The destination of a word instruction: D, C, V/Z, a word group KnM/KnY
/// (not KnX: inputs are driven from outside), each optionally
/// index-modified.
pub(super) fn word_dest(
    mnemonic: &str,
    index: usize,
    op: &Operand,
    width: Width,
) -> Result<Dest, StatementError> {
    let digits = if width == Width::Double { 8 } else { 4 };
    result_dest(mnemonic, index, op, width, digits)
}

/// [`word_dest`] for a result up to `max_digits` × 4 bits wide (a 16-bit
/// MUL's product fills K8).
pub(super) fn result_dest(
    mnemonic: &str,
    index: usize,
    op: &Operand,
    width: Width,
    max_digits: u8,
) -> Result<Dest, StatementError> {
    let group = |g: crate::il::WordGroup| -> Result<crate::il::WordGroup, StatementError> {
        if g.kind == crate::il::GroupKind::X {
            return Err(at(mnemonic, index, OperandError::InputGroup(op.describe())));
        }
        if g.digits > max_digits {
            return Err(at(
                mnemonic,
                index,
                OperandError::GroupTooWide {
                    group: g.to_string(),
                    digits: g.digits,
                    max: max_digits,
                },
            ));
        }
        Ok(g)
    };
    match *op {
        Operand::Device(Device::D(n)) => Ok(Dest::Register(register(mnemonic, index, n, width)?)),
        Operand::Device(Device::C(n)) => Ok(Dest::Counter(n)),
        Operand::Group(g) => Ok(Dest::Group(group(g)?)),
        Operand::Index(reg) => Ok(Dest::Index(index_register(mnemonic, index, reg, width)?)),
        Operand::Indexed(base, by) => {
            let by = modifier(mnemonic, index, op, by, width)?;
            let base = match base {
                Modified::Device(Device::D(n)) => {
                    IndexBase::Register(register(mnemonic, index, n, width)?)
                }
                Modified::Device(Device::C(n)) => IndexBase::Counter(n),
                Modified::Group(g) => IndexBase::Group(group(g)?),
                _ => {
                    return Err(wrong(
                        mnemonic,
                        index,
                        op,
                        "D, C or a word group KnM/KnY, index-modified",
                    ));
                }
            };
            Ok(Dest::Indexed(Indexed { base, by }))
        }
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a D register, a counter C, an index register V/Z or a word group KnM/KnY",
        )),
    }
}

pub(super) fn pulse_output(
    mnemonic: &str,
    index: usize,
    op: &Operand,
) -> Result<u8, StatementError> {
    match *op {
        Operand::Device(Device::Y(n)) if n <= 3 => Ok(n as u8),
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a pulse output Y0, Y1, Y2 or Y3",
        )),
    }
}
