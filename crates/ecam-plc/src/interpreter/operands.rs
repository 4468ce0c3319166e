//! Reading and writing operands at run time.

use crate::device::{C_32BIT_FIRST, C_COUNT, D_COUNT, Device, DeviceError, M_COUNT, XY_COUNT};
use crate::devices::Devices;
use crate::hardware::Hardware;
use crate::il::{BitRef, Dest, GroupKind, IndexBase, Indexed, Source, Width, WordGroup};
use crate::index_register::IndexReg;
use crate::operation_error::{CODE_DEVICE_RANGE, OperationError};

/// A device error at run time (the parser checks ranges, so this is rare).
pub(crate) fn device_error(device: impl core::fmt::Display, err: DeviceError) -> OperationError {
    OperationError::new(CODE_DEVICE_RANGE, format!("{device}: {err}"))
}

/// Sets special relay `m` (a flag such as M8020 or M8029).
pub(crate) fn set_flag(devices: &mut Devices, m: u16, on: bool) -> Result<(), OperationError> {
    devices
        .set_m(m, on)
        .map_err(|e| device_error(Device::M(m), e))
}

/// State of a bit operand: X/Y/M, or a counter's contact.
pub(crate) fn read_bit(devices: &Devices, hardware: &Hardware, device: Device) -> bool {
    match device {
        Device::C(n) => hardware.counters().contact(devices, n),
        Device::D(_) => false,
        bit => devices.bit(bit).unwrap_or(false),
    }
}

/// State of a contact operand: a bit device, a counter contact or `Dn.b`.
///
/// # Errors
/// An index-modified bit whose effective number is out of range (6706).
pub(crate) fn read_bit_ref(
    devices: &Devices,
    hardware: &Hardware,
    bit: BitRef,
) -> Result<bool, OperationError> {
    Ok(match bit {
        BitRef::Device(device) => read_bit(devices, hardware, device),
        BitRef::WordBit(b) => devices.word_bit(b.register, b.bit).unwrap_or(false),
        BitRef::Timer(n) => devices.timers().contact(n).unwrap_or(false),
        BitRef::Indexed(device, by) => {
            let device = indexed_bit(devices, device, by)?;
            read_bit(devices, hardware, device)
        }
        BitRef::IndexedTimer(n, by) => {
            let n = indexed_timer(devices, n, by)?;
            devices.timers().contact(n).unwrap_or(false)
        }
    })
}

/// The offset an index register adds: Vn/Zn as a signed word in 16-bit
/// instructions and bit instructions, the pair Vn:Zn in 32-bit ones.
fn offset(devices: &Devices, by: IndexReg, width: Width) -> Result<i64, OperationError> {
    match (by, width) {
        (IndexReg::Z(n), Width::Double) => devices.index_pair(n).map(i64::from),
        _ => devices.index_register(by).map(i64::from),
    }
    .map_err(|e| device_error(by, e))
}

/// The run-time out-of-range error of an index-modified operand: FX3U
/// operation error 6706 ("device out of range", index modification
/// included); the instruction is not executed.
fn past_range(
    what: impl core::fmt::Display,
    by: IndexReg,
    offset: i64,
    range: &str,
) -> OperationError {
    OperationError::new(
        CODE_DEVICE_RANGE,
        format!(
            "{what}: {by} = {offset} moves it out of range ({range}); the instruction was not executed"
        ),
    )
}

/// `base + offset` when the result and the `span` devices from it stay below `count`.
fn shifted(base: u16, offset: i64, span: u16, count: u16) -> Option<u16> {
    let first = i64::from(base).checked_add(offset)?;
    let last = first.checked_add(i64::from(span.max(1)) - 1)?;
    (first >= 0 && last < i64::from(count))
        .then(|| u16::try_from(first).ok())
        .flatten()
}

/// The X/Y/M bit an index-modified bit operand names now (X/Y numbers
/// are octal names, so Z0 = 8 moves X0 to X10, as on the FX).
pub(crate) fn indexed_bit(
    devices: &Devices,
    device: Device,
    by: IndexReg,
) -> Result<Device, OperationError> {
    let offset = offset(devices, by, Width::Word)?;
    let (n, count, make, range): (u16, u16, fn(u16) -> Device, &str) = match device {
        Device::X(n) => (n, XY_COUNT, Device::X, "X0-X377 octal"),
        Device::Y(n) => (n, XY_COUNT, Device::Y, "Y0-Y377 octal"),
        Device::M(n) => (n, M_COUNT, Device::M, "M0-M8511"),
        // A counter's contact (`LD C0Z0`); the parser allows C only in contacts.
        Device::C(n) => (n, C_COUNT, Device::C, "C0-C255"),
        other => return Err(device_error(other, DeviceError::WrongKind)),
    };
    shifted(n, offset, 1, count)
        .map(make)
        .ok_or_else(|| past_range(format_args!("{device}{by}"), by, offset, range))
}

/// The timer an index-modified timer contact names now (`LD T0Z1`).
pub(crate) fn indexed_timer(
    devices: &Devices,
    n: u16,
    by: IndexReg,
) -> Result<u16, OperationError> {
    let offset = offset(devices, by, Width::Word)?;
    shifted(n, offset, 1, crate::timers::T_COUNT)
        .ok_or_else(|| past_range(format_args!("T{n}{by}"), by, offset, "T0-T255"))
}

/// A word group moved by `offset` bits.
fn shifted_group(group: WordGroup, offset: i64) -> Option<WordGroup> {
    let count = match group.kind {
        GroupKind::X | GroupKind::Y => XY_COUNT,
        GroupKind::M => M_COUNT,
    };
    let first = shifted(group.first, offset, u16::from(group.digits) * 4, count)?;
    Some(WordGroup { first, ..group })
}

/// What an index-modified operand names at this moment, as a plain
/// source (constants get the offset added, wrapping at the width).
fn resolve(devices: &Devices, indexed: Indexed, width: Width) -> Result<Source, OperationError> {
    let by = indexed.by;
    let offset = offset(devices, by, width)?;
    let words: u16 = if width == Width::Double { 2 } else { 1 };
    let out = |range: &str| past_range(indexed, by, offset, range);
    match indexed.base {
        IndexBase::Constant(v) => {
            let sum = i64::from(v).wrapping_add(offset);
            Ok(Source::Constant(match width {
                Width::Word => i32::from(sum as i16),
                Width::Double => sum as i32,
            }))
        }
        IndexBase::Register(n) => shifted(n, offset, words, D_COUNT)
            .map(Source::Register)
            .ok_or_else(|| out("D0-D8511")),
        IndexBase::Counter(n) => shifted(n, offset, 1, C_COUNT)
            .map(Source::Counter)
            .ok_or_else(|| out("C0-C255")),
        IndexBase::Timer(n) => shifted(n, offset, 1, crate::timers::T_COUNT)
            .map(Source::Timer)
            .ok_or_else(|| out("T0-T255")),
        IndexBase::Group(g) => shifted_group(g, offset)
            .map(Source::Group)
            .ok_or_else(|| out("the group must stay inside X/Y 0-377 octal or M0-M8511")),
    }
}

/// A destination with its index modification applied (never
/// [`Dest::Indexed`]); `words` registers from a D must exist (MUL/DIV
/// results take 2 or 4).
pub(crate) fn resolve_dest(
    devices: &Devices,
    dest: Dest,
    width: Width,
    words: u16,
) -> Result<Dest, OperationError> {
    let Dest::Indexed(indexed) = dest else {
        return Ok(dest);
    };
    let by = indexed.by;
    let offset = offset(devices, by, width)?;
    let out = |range: &str| past_range(indexed, by, offset, range);
    match indexed.base {
        IndexBase::Register(n) => shifted(n, offset, words, D_COUNT)
            .map(Dest::Register)
            .ok_or_else(|| out("D0-D8511")),
        IndexBase::Counter(n) => shifted(n, offset, 1, C_COUNT)
            .map(Dest::Counter)
            .ok_or_else(|| out("C0-C255")),
        IndexBase::Group(g) => shifted_group(g, offset)
            .map(Dest::Group)
            .ok_or_else(|| out("the group must stay inside Y0-Y377 octal or M0-M8511")),
        // The parser builds no other indexed destination.
        IndexBase::Constant(_) | IndexBase::Timer(_) => {
            Err(device_error(indexed, DeviceError::WrongKind))
        }
    }
}

/// A destination read back as a source (NEG, INC, DEC read what they write).
pub(crate) fn dest_value(
    devices: &Devices,
    dest: Dest,
    width: Width,
) -> Result<i32, OperationError> {
    let source = match dest {
        Dest::Register(n) => Source::Register(n),
        Dest::Counter(n) => Source::Counter(n),
        Dest::Index(r) => Source::Index(r),
        Dest::Group(g) => Source::Group(g),
        Dest::Indexed(i) => Source::Indexed(i),
    };
    read_source(devices, source, width)
}

/// Drives a coil operand: Y, M or `Dn.b` (read-modify-write of the word).
pub(crate) fn write_bit_ref(
    devices: &mut Devices,
    bit: BitRef,
    on: bool,
) -> Result<(), OperationError> {
    match bit {
        BitRef::Device(device) => devices
            .set_bit(device, on)
            .map_err(|e| device_error(device, e)),
        BitRef::WordBit(b) => devices
            .set_word_bit(b.register, b.bit, on)
            .map_err(|e| device_error(b, e)),
        // The parser lets no OUT/SET name a timer without its set value.
        BitRef::Timer(n) | BitRef::IndexedTimer(n, _) => {
            Err(device_error(format!("T{n}"), DeviceError::WrongKind))
        }
        BitRef::Indexed(device, by) => {
            let device = indexed_bit(devices, device, by)?;
            devices
                .set_bit(device, on)
                .map_err(|e| device_error(device, e))
        }
    }
}

/// Value of a source operand at the instruction's width (16-bit reads are sign-extended).
pub(crate) fn read_source(
    devices: &Devices,
    source: Source,
    width: Width,
) -> Result<i32, OperationError> {
    let value = match source {
        Source::Constant(v) => return Ok(v),
        Source::Register(n) => match width {
            Width::Word => devices.word(n).map(i32::from),
            Width::Double => devices.dword(n),
        }
        .map_err(|e| device_error(Device::D(n), e))?,
        Source::Counter(n) => devices
            .counter(n)
            .map_err(|e| device_error(Device::C(n), e))?,
        Source::Timer(n) => devices
            .timers()
            .value(n)
            .map(i32::from)
            .map_err(|e| device_error(format!("T{n}"), e))?,
        Source::Group(group) => return read_group(devices, group, width),
        Source::Index(register) => {
            return match (register, width) {
                (IndexReg::Z(n), Width::Double) => devices.index_pair(n),
                _ => devices.index_register(register).map(i32::from),
            }
            .map_err(|e| device_error(register, e));
        }
        Source::Indexed(indexed) => {
            return match resolve(devices, indexed, width)? {
                // `resolve` never returns an indexed source.
                Source::Indexed(_) => Err(device_error(indexed, DeviceError::WrongKind)),
                plain => read_source(devices, plain, width),
            };
        }
    };
    Ok(match width {
        Width::Word => i32::from(value as i16),
        Width::Double => value,
    })
}

/// The number a word group holds: its n × 4 bits, lowest first. A group as
/// wide as the instruction (K4 at 16 bit, K8 at 32 bit) is signed, a
/// shorter one is positive (the FX fills the upper bits with 0).
fn read_group(
    devices: &Devices,
    group: crate::il::WordGroup,
    width: Width,
) -> Result<i32, OperationError> {
    let mut value: u32 = 0;
    for i in 0..u16::from(group.digits) * 4 {
        let device = group
            .bit(i)
            .ok_or_else(|| device_error(group, DeviceError::OutOfRange))?;
        if devices.bit(device).map_err(|e| device_error(device, e))? {
            value |= 1 << i;
        }
    }
    Ok(if group.digits == 4 && width == Width::Word {
        i32::from(value as u16 as i16)
    } else {
        value as i32
    })
}

/// Writes a word destination at the instruction's width: D (D, D+1),
/// C, V/Z (the pair Vn:Zn for Zn at 32 bit), or a word group, which takes
/// only its own n × 4 bits (K2Y0 gets the low 8 bits). Nothing is written
/// when any part is out of range.
pub(crate) fn write_word(
    devices: &mut Devices,
    dst: Dest,
    width: Width,
    value: i32,
) -> Result<(), OperationError> {
    let words = if width == Width::Double { 2 } else { 1 };
    let dst = resolve_dest(devices, dst, width, words)?;
    match (dst, width) {
        (Dest::Register(n), Width::Word) => devices.set_word(n, value as i16),
        (Dest::Register(n), Width::Double) => devices.set_dword(n, value),
        (Dest::Counter(n), Width::Word) if n < C_32BIT_FIRST => devices.set_counter(n, value),
        (Dest::Counter(n), Width::Word) => devices.set_counter(n, i32::from(value as i16)),
        (Dest::Counter(n), Width::Double) => devices.set_counter(n, value),
        (Dest::Index(IndexReg::Z(n)), Width::Double) => devices.set_index_pair(n, value),
        (Dest::Index(register), _) => devices.set_index_register(register, value as i16),
        (Dest::Group(group), _) => return write_group(devices, group, value),
        (Dest::Indexed(_), _) => Err(DeviceError::WrongKind),
    }
    .map_err(|e| device_error(dst, e))
}

/// Writes the low n × 4 bits of `value` into a word group, lowest bit first.
pub(crate) fn write_group(
    devices: &mut Devices,
    group: WordGroup,
    value: i32,
) -> Result<(), OperationError> {
    let bits = u16::from(group.digits) * 4;
    // Check every bit first: a group half written is worse than none.
    for i in 0..bits {
        let device = group
            .bit(i)
            .ok_or_else(|| device_error(group, DeviceError::OutOfRange))?;
        device.check().map_err(|e| device_error(group, e))?;
    }
    for i in 0..bits {
        let device = group
            .bit(i)
            .ok_or_else(|| device_error(group, DeviceError::OutOfRange))?;
        let on = (value as u32) >> i & 1 == 1;
        devices
            .set_bit(device, on)
            .map_err(|e| device_error(device, e))?;
    }
    Ok(())
}
