//! Transfers: MOV/DMOV, DEMOV, BMOV and FMOV/DFMOV.

use super::operands::{device_error, read_source, resolve_dest, write_word};
use crate::device::{D_COUNT, Device};
use crate::devices::Devices;
use crate::il::{BLOCK_MAX, Dest, FloatSource, Source, Width};
use crate::operation_error::{CODE_DEVICE_RANGE, CODE_OPERAND, OperationError};

/// `MOV`/`DMOV` S D.
pub(super) fn mov(
    devices: &mut Devices,
    width: Width,
    src: Source,
    dst: Dest,
) -> Result<(), OperationError> {
    let value = read_source(devices, src, width)?;
    write_word(devices, dst, width, value)
}

/// `DEMOV` S D: a float into the register pair D, D+1.
pub(super) fn float_move(
    devices: &mut Devices,
    src: FloatSource,
    dst: u16,
) -> Result<(), OperationError> {
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

/// `BMOV` S D n: n registers from S to D.
pub(super) fn block_move(
    devices: &mut Devices,
    src: Dest,
    dst: Dest,
    count: Source,
) -> Result<(), OperationError> {
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

/// `FMOV`/`DFMOV` S D n: S into n registers (register pairs) from D.
pub(super) fn fill(
    devices: &mut Devices,
    width: Width,
    (src, dst): (Source, Dest),
    count: Source,
) -> Result<(), OperationError> {
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

/// n of BMOV/FMOV: 1–512, else operation error 6705.
fn block_len(devices: &Devices, count: Source) -> Result<u16, OperationError> {
    let n = read_source(devices, count, Width::Word)?;
    u16::try_from(n)
        .ok()
        .filter(|n| (1..=BLOCK_MAX).contains(&i32::from(*n)))
        .ok_or_else(|| {
            OperationError::new(
                CODE_OPERAND,
                format!(
                    "block length n = {n} is out of range (1 to {BLOCK_MAX}); nothing was moved"
                ),
            )
        })
}

/// The first register of a BMOV/FMOV block of `words` registers, index
/// modification applied; 6706 when the block runs past D8511.
fn block_start(devices: &Devices, start: Dest, words: u16) -> Result<u16, OperationError> {
    match resolve_dest(devices, start, Width::Word, words)? {
        Dest::Register(n) if n.checked_add(words).is_some_and(|end| end <= D_COUNT) => Ok(n),
        other => Err(OperationError::new(
            CODE_DEVICE_RANGE,
            format!("a block of {words} registers from {other} runs past D8511; nothing was moved"),
        )),
    }
}
