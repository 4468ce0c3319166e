//! Contacts: LD/AND/OR and their inverse and edge forms on a bit, and the
//! comparison contacts (`LD=`, `AND<>`, `ORD>=` …).

use super::machine::{Machine, Memory};
use super::operands::{read_bit_ref, read_source};
use crate::il::{BitRef, Contact, Relation, Source, Width};
use crate::operation_error::OperationError;

/// Reads a contact, remembering the device state for the edge forms. An
/// index-modified contact out of range reads as off and returns the
/// operation error to report.
pub(super) fn bit_contact(
    contact: Contact,
    device: BitRef,
    memory: &mut Memory,
    machine: &Machine<'_>,
) -> (bool, Result<(), OperationError>) {
    let (state, read) = match read_bit_ref(machine.devices, machine.hardware, device) {
        Ok(state) => (state, Ok(())),
        Err(error) => (false, Err(error)),
    };
    let previous = memory.previous;
    memory.previous = state;
    let value = match contact {
        Contact::Open => state,
        Contact::Closed => !state && read.is_ok(),
        Contact::Rising => state && !previous,
        Contact::Falling => !state && previous && read.is_ok(),
    };
    (value, read)
}

/// A comparison contact: on while `s1 relation s2` holds; an operand that
/// cannot be read makes it off and returns the operation error to report.
pub(super) fn compare_contact(
    relation: Relation,
    width: Width,
    (s1, s2): (Source, Source),
    machine: &Machine<'_>,
) -> (bool, Result<(), OperationError>) {
    let compared = read_source(machine.devices, s1, width)
        .and_then(|a| read_source(machine.devices, s2, width).map(|b| relation.holds(a, b)));
    let value = *compared.as_ref().unwrap_or(&false);
    (value, compared.map(|_| ()))
}
