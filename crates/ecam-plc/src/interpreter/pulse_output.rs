//! PLSY/DPLSY: a pulse train of S2 pulses at S1 Hz on Y0–Y3.

use super::machine::{Machine, Memory};
use super::operands::{read_source, set_flag};
use crate::hardware::{OutputOwner, PulseTrain};
use crate::il::{Source, Width};
use crate::operation_error::{CODE_OPERAND, OperationError};
use crate::special::M_EXECUTION_COMPLETE;

/// Highest PLSY frequency (16-bit operand).
const PLSY_MAX_HZ: i32 = 32_767;
/// Highest DPLSY frequency: the LX3V's 200 kHz pulse outputs (document 003,
/// "Maximum frequency of E-cam ... 200K").
const DPLSY_MAX_HZ: i32 = 200_000;

/// PLSY/DPLSY: starts a pulse train when the power flow turns on, follows
/// frequency changes while it runs, stops it when the power flow goes off;
/// a finished train turns M8029 on and is not restarted until the power flow
/// has been off.
///
/// One instruction drives an output at a time (the FX rule): while another
/// PLSY/DPLSY or a DECAM holds the output, the train does not start; it
/// starts in the first scan that finds the output free with the power flow
/// still on. Nothing is flagged meanwhile (as on the FX).
pub(super) fn plsy(
    machine: &mut Machine<'_>,
    memory: &mut Memory,
    (owner, power): (OutputOwner, bool),
    width: Width,
    (frequency, count): (Source, Source),
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
