//! The E-cam instructions: DECAM hands its power flow to its own E-cam
//! instance (`crate::decam`), ECAMTBX generates a table (`crate::ecamtbx`).

use super::machine::Machine;
use super::operands::read_source;
use crate::il::{Source, Width};
use crate::operation_error::OperationError;

/// `DECAM`: the instance `decam` (its number in program order) runs its
/// scan half with power flow `power`.
pub(super) fn decam(
    machine: &mut Machine<'_>,
    decam: Option<usize>,
    power: bool,
) -> Result<(), OperationError> {
    match decam.and_then(|d| machine.decams.get_mut(d)) {
        Some(decam) => decam.execute(power, machine.devices, machine.now_us),
        None => Ok(()),
    }
}

/// `ECAMTBX S0 S1 D1 D2`: while the power flow is on, generates the table
/// of kind S1 (a 32-bit value) from the parameters at S0 into D1.
pub(super) fn ecamtbx(
    machine: &mut Machine<'_>,
    power: bool,
    (params, kind): (u16, Source),
    (table, result): (u16, u16),
) -> Result<(), OperationError> {
    if !power {
        return Ok(());
    }
    let kind = read_source(machine.devices, kind, Width::Double)?;
    crate::ecamtbx::execute(machine.devices, params, kind, table, result)
}
