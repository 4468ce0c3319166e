//! The Modbus TCP server: MBAP framing, one task per client, and the
//! requests mapped onto device memory through [`super::map`].
//!
//! Framing (Modbus Messaging on TCP/IP Implementation Guide V1.0b): a
//! 7-byte MBAP header (transaction id, protocol id 0, length = unit id + PDU,
//! unit id) and the PDU. Any unit id is answered (a gateway's unit ids are
//! not ours to check) and echoed. A header with another protocol id or a
//! length outside 2..=254 is not Modbus: the connection is closed, the
//! server goes on. A well-framed PDU always gets a response or an exception.

use std::io;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use tokio::io::{AsyncReadExt as _, AsyncWriteExt as _};
use tokio::net::{TcpListener, TcpStream};

use super::map;
use super::pdu::{self, Exception, Request, Response};
use super::state::Shared;
use super::write::WriteBatch;

/// MBAP header length.
const HEADER_LEN: usize = 7;
/// Largest MBAP length field: unit id + a 253-byte PDU.
const MAX_LENGTH: u16 = 254;

/// Accepts clients on `listener` for ever.
pub async fn serve(listener: TcpListener, shared: Arc<Shared>) {
    loop {
        match listener.accept().await {
            Ok((stream, _)) => {
                shared
                    .stats
                    .modbus_connections
                    .fetch_add(1, Ordering::Relaxed);
                tokio::spawn(connection(stream, Arc::clone(&shared)));
            }
            Err(err) => {
                // Out of file descriptors and the like: wait, do not spin.
                eprintln!("ecam serve: modbus accept: {err}");
                tokio::time::sleep(std::time::Duration::from_millis(100)).await;
            }
        }
    }
}

/// Serves one client until it disconnects or sends something that is not Modbus.
async fn connection(mut stream: TcpStream, shared: Arc<Shared>) {
    let _ = stream.set_nodelay(true);
    // Errors only mean the client went away.
    let _ = requests(&mut stream, &shared).await;
}

async fn requests(stream: &mut TcpStream, shared: &Arc<Shared>) -> io::Result<()> {
    let mut header = [0u8; HEADER_LEN];
    loop {
        stream.read_exact(&mut header).await?;
        let [t_hi, t_lo, p_hi, p_lo, l_hi, l_lo, unit] = header;
        let length = u16::from_be_bytes([l_hi, l_lo]);
        if u16::from_be_bytes([p_hi, p_lo]) != 0 || !(2..=MAX_LENGTH).contains(&length) {
            shared.stats.modbus_garbage.fetch_add(1, Ordering::Relaxed);
            return Ok(());
        }
        let mut request_pdu = vec![0u8; usize::from(length) - 1];
        stream.read_exact(&mut request_pdu).await?;
        let function = request_pdu.first().copied().unwrap_or(0);
        let reply = match pdu::parse(&request_pdu) {
            Ok(request) if is_write(&request) => {
                // The journal syncs to disk: keep that off the async workers.
                let shared = Arc::clone(shared);
                tokio::task::spawn_blocking(move || handle(&shared, &request))
                    .await
                    .unwrap_or(Err(Exception::ServerDeviceFailure))
            }
            Ok(request) => handle(shared, &request),
            Err(exception) => Err(exception),
        };
        shared.stats.modbus_requests.fetch_add(1, Ordering::Relaxed);
        if reply.is_err() {
            shared
                .stats
                .modbus_exceptions
                .fetch_add(1, Ordering::Relaxed);
        }
        let body = pdu::encode(function, &reply);
        // Responses are at most 252 bytes: the length fits.
        let [len_hi, len_lo] = ((body.len() + 1) as u16).to_be_bytes();
        let mut frame = Vec::with_capacity(HEADER_LEN + body.len());
        frame.extend_from_slice(&[t_hi, t_lo, 0, 0, len_hi, len_lo, unit]);
        frame.extend_from_slice(&body);
        stream.write_all(&frame).await?;
    }
}

fn is_write(request: &Request) -> bool {
    matches!(
        request,
        Request::WriteSingleCoil { .. }
            | Request::WriteSingleRegister { .. }
            | Request::WriteMultipleCoils { .. }
            | Request::WriteMultipleRegisters { .. }
    )
}

/// Makes `batch` durable and applies it, or reports exception 04.
fn commit(shared: &Shared, batch: &WriteBatch) -> Result<(), Exception> {
    shared.write(batch).map_err(|err| {
        eprintln!("ecam serve: write refused: {err}");
        Exception::ServerDeviceFailure
    })
}

/// Answers one decoded request against device memory.
///
/// # Errors
/// 02 for addresses outside the map or writes to Y, 03 for quantity 0,
/// 04 when a write cannot be made durable.
pub fn handle(shared: &Shared, request: &Request) -> Result<Response, Exception> {
    match *request {
        Request::ReadCoils { address, quantity }
        | Request::ReadDiscreteInputs { address, quantity } => {
            let range = map::coils(address, quantity)?;
            Ok(Response::Bits(shared.read(|devices| {
                range
                    .devices()
                    .map(|d| devices.bit(d).unwrap_or(false))
                    .collect()
            })))
        }
        Request::ReadHoldingRegisters { address, quantity }
        | Request::ReadInputRegisters { address, quantity } => {
            let range = map::registers(address, quantity)?;
            Ok(Response::Registers(shared.read(|devices| {
                range
                    .registers()
                    .map(|n| devices.word(n).unwrap_or(0) as u16)
                    .collect()
            })))
        }
        Request::WriteSingleCoil { address, on } => {
            let range = map::writable_coils(address, 1)?;
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
            let range = map::registers(address, 1)?;
            commit(shared, WriteBatch::new().word(range.first, value))?;
            Ok(Response::Echo { address, value })
        }
        Request::WriteMultipleCoils { address, ref coils } => {
            let quantity = u16::try_from(coils.len()).map_err(|_| Exception::IllegalDataValue)?;
            let range = map::writable_coils(address, quantity)?;
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
            let range = map::registers(address, quantity)?;
            let mut batch = WriteBatch::new();
            for (n, &value) in range.registers().zip(values) {
                batch.word(n, value);
            }
            commit(shared, &batch)?;
            Ok(Response::Written { address, quantity })
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use crate::serve::state::ServeInfo;
    use ecam_plc::devices::Device;
    use ecam_plc::scan::Plc;

    fn shared() -> Shared {
        let program = ecam_plc::il::parse("", "empty.il").unwrap();
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
            },
        )
    }

    #[test]
    fn registers_and_coils_reach_device_memory() {
        let s = shared();
        assert_eq!(
            handle(
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
        handle(
            &s,
            &Request::WriteSingleCoil {
                address: 10015,
                on: true,
            },
        )
        .unwrap();
        assert_eq!(s.read(|d| d.bit(Device::X(15))), Ok(true));
        assert_eq!(
            handle(
                &s,
                &Request::ReadCoils {
                    address: 10014,
                    quantity: 3
                }
            ),
            Ok(Response::Bits(vec![false, true, false]))
        );
        assert_eq!(
            handle(
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
            handle(
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
            handle(
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
