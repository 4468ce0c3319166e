//! Modbus requests answered against the shared PLC's device memory,
//! through the address map (`docs/modbus.md` has the whole map and the
//! exceptions).

use crate::bus::BusFace;
use crate::map;
use crate::pdu::{Exception, Request, Response};
use crate::state::WriteError;
use crate::state::{Event, Shared};
use crate::write::WriteBatch;

/// Makes `batch` durable and applies it, or answers the exception: 03
/// when the running cams refuse it, 04 when the journal failed (reported).
fn commit(shared: &Shared, batch: &WriteBatch) -> Result<(), Exception> {
    shared.write(batch).map_err(|err| {
        let exception = err.exception();
        if let WriteError::Journal(err) = err {
            shared.report(Event::WriteRefused(err));
        }
        exception
    })
}

/// Answers one decoded request against device memory; a write is made
/// durable (when there is a journal) before it is applied, and a write
/// that cannot be is reported as [`Event::WriteRefused`].
///
/// A write syncs the journal to disk: an async server runs it off its
/// workers (see [`Request::is_write`]).
///
/// # Errors
/// 02 for addresses outside the map or writes to Y, 03 for quantity 0 and
/// for a write that would leave a running cam's table invalid, 04 when a
/// write cannot be made durable.
pub fn answer_request(shared: &Shared, request: &Request) -> Result<Response, Exception> {
    if let Some(bus) = shared.bus.get() {
        if let Some(reply) = answer_bus(bus, request) {
            return reply;
        }
    }
    match *request {
        Request::ReadCoils { address, quantity }
        | Request::ReadDiscreteInputs { address, quantity } => {
            let range = map::coil_range(address, quantity)?;
            Ok(Response::Bits(shared.read(|devices| {
                range
                    .devices()
                    .map(|d| devices.bit(d).unwrap_or(false))
                    .collect()
            })))
        }
        Request::ReadHoldingRegisters { address, quantity }
        | Request::ReadInputRegisters { address, quantity } => {
            let range = map::register_range(address, quantity)?;
            Ok(Response::Registers(shared.read(|devices| {
                range
                    .registers()
                    .map(|n| devices.word(n).unwrap_or(0) as u16)
                    .collect()
            })))
        }
        Request::WriteSingleCoil { address, on } => {
            let range = map::writable_coil_range(address, 1)?;
            let mut batch = WriteBatch::new();
            for device in range.devices() {
                batch.bit(device, on);
            }
            commit(shared, &batch)?;
            Ok(Response::Echo {
                address,
                value: if on { 0xFF00 } else { 0x0000 },
            })
        }
        Request::WriteSingleRegister { address, value } => {
            let range = map::register_range(address, 1)?;
            commit(shared, WriteBatch::new().word(range.first, value))?;
            Ok(Response::Echo { address, value })
        }
        Request::WriteMultipleCoils { address, ref coils } => {
            let quantity = u16::try_from(coils.len()).map_err(|_| Exception::IllegalDataValue)?;
            let range = map::writable_coil_range(address, quantity)?;
            let mut batch = WriteBatch::new();
            for (device, &on) in range.devices().zip(coils) {
                batch.bit(device, on);
            }
            commit(shared, &batch)?;
            Ok(Response::Written { address, quantity })
        }
        Request::WriteMultipleRegisters {
            address,
            ref values,
        } => {
            let quantity = u16::try_from(values.len()).map_err(|_| Exception::IllegalDataValue)?;
            let range = map::register_range(address, quantity)?;
            let mut batch = WriteBatch::new();
            for (n, &value) in range.registers().zip(values) {
                batch.word(n, value);
            }
            commit(shared, &batch)?;
            Ok(Response::Written { address, quantity })
        }
    }
}

/// Answers a request for the fieldbus areas (coils 14000–14001, input
/// registers from 20000); `None` for every other address.
fn answer_bus(bus: &BusFace, request: &Request) -> Option<Result<Response, Exception>> {
    Some(match *request {
        Request::ReadCoils { address, quantity }
        | Request::ReadDiscreteInputs { address, quantity }
            if BusFace::owns_coils(address) =>
        {
            bus.read_coils(address, quantity).map(Response::Bits)
        }
        Request::ReadInputRegisters { address, quantity } if BusFace::owns_registers(address) => {
            bus.read_registers(address, quantity)
                .map(Response::Registers)
        }
        Request::WriteSingleCoil { address, on } if BusFace::owns_coils(address) => {
            bus.write_coils(address, &[on]).map(|()| Response::Echo {
                address,
                value: if on { 0xFF00 } else { 0x0000 },
            })
        }
        Request::WriteMultipleCoils { address, ref coils } if BusFace::owns_coils(address) => {
            bus.write_coils(address, coils).map(|()| Response::Written {
                address,
                quantity: u16::try_from(coils.len()).unwrap_or(u16::MAX),
            })
        }
        _ => return None,
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use crate::state::ServeInfo;
    use ecam_plc::Device;
    use ecam_plc::Plc;

    fn shared() -> Shared {
        let program = ecam_plc::Program::parse("", "empty.il").unwrap();
        let addr = "127.0.0.1:0".parse().unwrap();
        Shared::new(
            Plc::new(program).unwrap(),
            None,
            ServeInfo {
                program: None,
                timing: ecam_plc::sim::Timing::default(),
                modbus: addr,
                http: addr,
                state_dir: None,
                limits: Default::default(),
            },
            |_| {},
        )
    }

    #[test]
    fn registers_and_coils_reach_device_memory() {
        let s = shared();
        assert_eq!(
            answer_request(
                &s,
                &Request::WriteMultipleRegisters {
                    address: 8510,
                    values: vec![1, 0xFFFF]
                }
            ),
            Ok(Response::Written {
                address: 8510,
                quantity: 2
            })
        );
        assert_eq!(s.read(|d| d.word(8511)), Ok(-1));
        answer_request(
            &s,
            &Request::WriteSingleCoil {
                address: 10015,
                on: true,
            },
        )
        .unwrap();
        assert_eq!(s.read(|d| d.bit(Device::X(15))), Ok(true));
        assert_eq!(
            answer_request(
                &s,
                &Request::ReadCoils {
                    address: 10014,
                    quantity: 3
                }
            ),
            Ok(Response::Bits(vec![false, true, false]))
        );
        assert_eq!(
            answer_request(
                &s,
                &Request::ReadInputRegisters {
                    address: 8511,
                    quantity: 1
                }
            ),
            Ok(Response::Registers(vec![0xFFFF]))
        );
    }

    #[test]
    fn outputs_refuse_writes_and_leave_memory_alone() {
        let s = shared();
        assert_eq!(
            answer_request(
                &s,
                &Request::WriteMultipleCoils {
                    address: 12000,
                    coils: vec![true; 8]
                }
            ),
            Err(Exception::IllegalDataAddress)
        );
        assert_eq!(s.read(|d| d.bit(Device::Y(0))), Ok(false));
        assert_eq!(
            answer_request(
                &s,
                &Request::WriteSingleRegister {
                    address: 8512,
                    value: 1
                }
            ),
            Err(Exception::IllegalDataAddress)
        );
    }
}
