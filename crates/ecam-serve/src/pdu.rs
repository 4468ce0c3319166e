//! Modbus application PDUs (function code + data), as the Modbus
//! Application Protocol Specification V1.1b3 defines them.
//!
//! We decode requests ourselves rather than through `tokio-modbus`'s server
//! codec: its 0x0F decoder indexes past the data when the quantity claims
//! more coils than the byte count carries (a panic per malformed frame), and
//! it drops the connection where the specification asks for exception 03
//! (a quantity over the protocol maximum). Here every request either decodes
//! or yields the exception the specification names, checked in its order:
//! function code (01), then quantity and length (03), then address (02).

use core::fmt;

/// Most coils one read (0x01/0x02) may ask for.
pub const MAX_READ_BITS: u16 = 2000;
/// Most registers one read (0x03/0x04) may ask for.
pub const MAX_READ_REGISTERS: u16 = 125;
/// Most coils one write (0x0F) may carry.
pub const MAX_WRITE_BITS: u16 = 1968;
/// Most registers one write (0x10) may carry.
pub const MAX_WRITE_REGISTERS: u16 = 123;

/// A Modbus exception code sent back instead of a response.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exception {
    /// 01: the function code is not supported.
    IllegalFunction,
    /// 02: the address range is not (or not wholly) in one device area,
    /// or the area is read only.
    IllegalDataAddress,
    /// 03: quantity 0 or over the maximum, a byte count that does not match,
    /// a coil value other than 0xFF00/0x0000, a PDU of the wrong length.
    IllegalDataValue,
    /// 04: the write could not be made durable (the state directory failed).
    ServerDeviceFailure,
    /// 06: the fieldbus cycle has not taken the commands queued before
    /// (`--ethercat` only).
    ServerDeviceBusy,
}

impl Exception {
    /// The code on the wire.
    pub const fn code(self) -> u8 {
        match self {
            Self::IllegalFunction => 0x01,
            Self::IllegalDataAddress => 0x02,
            Self::IllegalDataValue => 0x03,
            Self::ServerDeviceFailure => 0x04,
            Self::ServerDeviceBusy => 0x06,
        }
    }
}

impl std::error::Error for Exception {}

impl fmt::Display for Exception {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::IllegalFunction => "illegal function (01)",
            Self::IllegalDataAddress => "illegal data address (02)",
            Self::IllegalDataValue => "illegal data value (03)",
            Self::ServerDeviceFailure => "server device failure (04)",
            Self::ServerDeviceBusy => "server device busy (06)",
        })
    }
}

/// A decoded request.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Request {
    /// 0x01 Read Coils.
    ReadCoils {
        /// First coil.
        address: u16,
        /// Number of coils, 1..=2000.
        quantity: u16,
    },
    /// 0x02 Read Discrete Inputs (served from the coil map, read only).
    ReadDiscreteInputs {
        /// First input.
        address: u16,
        /// Number of inputs, 1..=2000.
        quantity: u16,
    },
    /// 0x03 Read Holding Registers.
    ReadHoldingRegisters {
        /// First register.
        address: u16,
        /// Number of registers, 1..=125.
        quantity: u16,
    },
    /// 0x04 Read Input Registers (served from the holding-register map).
    ReadInputRegisters {
        /// First register.
        address: u16,
        /// Number of registers, 1..=125.
        quantity: u16,
    },
    /// 0x05 Write Single Coil.
    WriteSingleCoil {
        /// The coil.
        address: u16,
        /// On (0xFF00) or off (0x0000).
        on: bool,
    },
    /// 0x06 Write Single Register.
    WriteSingleRegister {
        /// The register.
        address: u16,
        /// Its new value.
        value: u16,
    },
    /// 0x0F Write Multiple Coils.
    WriteMultipleCoils {
        /// First coil.
        address: u16,
        /// New states, 1..=1968 of them.
        coils: Vec<bool>,
    },
    /// 0x10 Write Multiple Registers.
    WriteMultipleRegisters {
        /// First register.
        address: u16,
        /// New values, 1..=123 of them.
        values: Vec<u16>,
    },
}

impl Request {
    /// Whether the request writes (0x05, 0x06, 0x0F, 0x10): answering it
    /// may wait for the journal's sync to disk.
    pub const fn is_write(&self) -> bool {
        matches!(
            self,
            Self::WriteSingleCoil { .. }
                | Self::WriteSingleRegister { .. }
                | Self::WriteMultipleCoils { .. }
                | Self::WriteMultipleRegisters { .. }
        )
    }
}

/// Values one log line lists before it says how many more there are.
const VALUES_SHOWN: usize = 16;

/// `v1 v2 … (and N more)`.
fn list<T: fmt::Display>(
    f: &mut fmt::Formatter<'_>,
    values: impl ExactSizeIterator<Item = T>,
) -> fmt::Result {
    let total = values.len();
    for (i, v) in values.take(VALUES_SHOWN).enumerate() {
        if i > 0 {
            f.write_str(" ")?;
        }
        write!(f, "{v}")?;
    }
    if total > VALUES_SHOWN {
        write!(f, " (and {} more)", total - VALUES_SHOWN)?;
    }
    Ok(())
}

/// A traffic log's words for a request, function code first, e.g.
/// `06 write register 100 = 3183` (addresses are Modbus addresses, values
/// as on the wire: coils 1/0, registers unsigned).
impl fmt::Display for Request {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::ReadCoils { address, quantity } => {
                write!(f, "01 read coils {address}, {quantity} of them")
            }
            Self::ReadDiscreteInputs { address, quantity } => {
                write!(f, "02 read discrete inputs {address}, {quantity} of them")
            }
            Self::ReadHoldingRegisters { address, quantity } => {
                write!(f, "03 read holding registers {address}, {quantity} of them")
            }
            Self::ReadInputRegisters { address, quantity } => {
                write!(f, "04 read input registers {address}, {quantity} of them")
            }
            Self::WriteSingleCoil { address, on } => {
                write!(f, "05 write coil {address} = {}", u8::from(*on))
            }
            Self::WriteSingleRegister { address, value } => {
                write!(f, "06 write register {address} = {value}")
            }
            Self::WriteMultipleCoils { address, coils } => {
                write!(f, "0F write coils from {address}: ")?;
                list(f, coils.iter().map(|&c| u8::from(c)))
            }
            Self::WriteMultipleRegisters { address, values } => {
                write!(f, "10 write registers from {address}: ")?;
                list(f, values.iter())
            }
        }
    }
}

/// A traffic log's words for a response, e.g. `registers 3183 0`.
impl fmt::Display for Response {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Bits(bits) => {
                f.write_str("bits ")?;
                list(f, bits.iter().map(|&b| u8::from(b)))
            }
            Self::Registers(values) => {
                f.write_str("registers ")?;
                list(f, values.iter())
            }
            Self::Echo { address, value } => write!(f, "done: {address} = {value}"),
            Self::Written { address, quantity } => {
                write!(f, "done: {quantity} from {address}")
            }
        }
    }
}

/// A successful response.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Response {
    /// To 0x01/0x02: the coil states.
    Bits(Vec<bool>),
    /// To 0x03/0x04: the register values.
    Registers(Vec<u16>),
    /// To 0x05/0x06: the request's address and value, echoed.
    Echo {
        /// Address written.
        address: u16,
        /// Value field of the request (0xFF00/0x0000 for a coil).
        value: u16,
    },
    /// To 0x0F/0x10: address and quantity written.
    Written {
        /// First address written.
        address: u16,
        /// Number of coils or registers written.
        quantity: u16,
    },
}

fn u16_at(pdu: &[u8], at: usize) -> Option<u16> {
    let hi = *pdu.get(at)?;
    let lo = *pdu.get(at.checked_add(1)?)?;
    Some(u16::from_be_bytes([hi, lo]))
}

/// Address and quantity of a read, exactly 5 bytes long.
fn read_range(pdu: &[u8], max: u16) -> Result<(u16, u16), Exception> {
    if pdu.len() != 5 {
        return Err(Exception::IllegalDataValue);
    }
    let address = u16_at(pdu, 1).ok_or(Exception::IllegalDataValue)?;
    let quantity = u16_at(pdu, 3).ok_or(Exception::IllegalDataValue)?;
    if quantity == 0 || quantity > max {
        return Err(Exception::IllegalDataValue);
    }
    Ok((address, quantity))
}

/// Address, quantity and the data bytes of a 0x0F/0x10 write, after
/// checking the byte count against the quantity and the PDU length.
fn write_block(
    pdu: &[u8],
    max: u16,
    bytes_for: fn(u16) -> usize,
) -> Result<(u16, u16, &[u8]), Exception> {
    let address = u16_at(pdu, 1).ok_or(Exception::IllegalDataValue)?;
    let quantity = u16_at(pdu, 3).ok_or(Exception::IllegalDataValue)?;
    let byte_count = usize::from(*pdu.get(5).ok_or(Exception::IllegalDataValue)?);
    if quantity == 0 || quantity > max || byte_count != bytes_for(quantity) {
        return Err(Exception::IllegalDataValue);
    }
    let data = pdu.get(6..).ok_or(Exception::IllegalDataValue)?;
    if data.len() != byte_count {
        return Err(Exception::IllegalDataValue);
    }
    Ok((address, quantity, data))
}

/// Decodes a request PDU (function code first).
///
/// # Errors
/// The exception to send back: 01 for a function we do not serve, 03 for a
/// malformed body. Addresses are checked later, against the map.
pub fn parse_request(pdu: &[u8]) -> Result<Request, Exception> {
    let function = *pdu.first().ok_or(Exception::IllegalFunction)?;
    Ok(match function {
        0x01 => {
            let (address, quantity) = read_range(pdu, MAX_READ_BITS)?;
            Request::ReadCoils { address, quantity }
        }
        0x02 => {
            let (address, quantity) = read_range(pdu, MAX_READ_BITS)?;
            Request::ReadDiscreteInputs { address, quantity }
        }
        0x03 => {
            let (address, quantity) = read_range(pdu, MAX_READ_REGISTERS)?;
            Request::ReadHoldingRegisters { address, quantity }
        }
        0x04 => {
            let (address, quantity) = read_range(pdu, MAX_READ_REGISTERS)?;
            Request::ReadInputRegisters { address, quantity }
        }
        0x05 => {
            if pdu.len() != 5 {
                return Err(Exception::IllegalDataValue);
            }
            let address = u16_at(pdu, 1).ok_or(Exception::IllegalDataValue)?;
            let on = match u16_at(pdu, 3) {
                Some(0xFF00) => true,
                Some(0x0000) => false,
                _ => return Err(Exception::IllegalDataValue),
            };
            Request::WriteSingleCoil { address, on }
        }
        0x06 => {
            if pdu.len() != 5 {
                return Err(Exception::IllegalDataValue);
            }
            let address = u16_at(pdu, 1).ok_or(Exception::IllegalDataValue)?;
            let value = u16_at(pdu, 3).ok_or(Exception::IllegalDataValue)?;
            Request::WriteSingleRegister { address, value }
        }
        0x0F => {
            let (address, quantity, data) =
                write_block(pdu, MAX_WRITE_BITS, |q| usize::from(q).div_ceil(8))?;
            let coils = (0..usize::from(quantity))
                .map(|i| data.get(i / 8).is_some_and(|byte| byte >> (i % 8) & 1 == 1))
                .collect();
            Request::WriteMultipleCoils { address, coils }
        }
        0x10 => {
            let (address, _, data) = write_block(pdu, MAX_WRITE_REGISTERS, |q| usize::from(q) * 2)?;
            let values = data
                .chunks_exact(2)
                .filter_map(|pair| match pair {
                    [hi, lo] => Some(u16::from_be_bytes([*hi, *lo])),
                    _ => None,
                })
                .collect();
            Request::WriteMultipleRegisters { address, values }
        }
        _ => return Err(Exception::IllegalFunction),
    })
}

/// Encodes the response PDU to a request with function code `function`:
/// the response itself, or `function | 0x80` and the exception code.
pub fn encode_response(function: u8, reply: &Result<Response, Exception>) -> Vec<u8> {
    let mut out = Vec::new();
    match reply {
        Err(exception) => {
            out.push(function | 0x80);
            out.push(exception.code());
        }
        Ok(Response::Bits(bits)) => {
            out.push(function);
            let mut packed = vec![0u8; bits.len().div_ceil(8)];
            for (i, _) in bits.iter().enumerate().filter(|(_, on)| **on) {
                if let Some(byte) = packed.get_mut(i / 8) {
                    *byte |= 1 << (i % 8);
                }
            }
            // At most 2000 bits = 250 bytes: the byte count fits.
            out.push(packed.len() as u8);
            out.extend_from_slice(&packed);
        }
        Ok(Response::Registers(values)) => {
            // At most 125 registers = 250 bytes.
            out.push(function);
            out.push((values.len() * 2) as u8);
            for v in values {
                out.extend_from_slice(&v.to_be_bytes());
            }
        }
        Ok(Response::Echo { address, value }) => {
            out.push(function);
            out.extend_from_slice(&address.to_be_bytes());
            out.extend_from_slice(&value.to_be_bytes());
        }
        Ok(Response::Written { address, quantity }) => {
            out.push(function);
            out.extend_from_slice(&address.to_be_bytes());
            out.extend_from_slice(&quantity.to_be_bytes());
        }
    }
    out
}

#[cfg(test)]
mod display_tests {
    use super::*;

    #[test]
    fn traffic_words_name_function_address_and_values() {
        let write = Request::WriteSingleRegister {
            address: 100,
            value: 3183,
        };
        assert_eq!(write.to_string(), "06 write register 100 = 3183");
        let many = Request::WriteMultipleRegisters {
            address: 7,
            values: (0..20).collect(),
        };
        assert!(many.to_string().ends_with("14 15 (and 4 more)"), "{many}");
        let coils = Request::WriteMultipleCoils {
            address: 10000,
            coils: vec![true, false],
        };
        assert_eq!(coils.to_string(), "0F write coils from 10000: 1 0");
        assert_eq!(Response::Registers(vec![1, 2]).to_string(), "registers 1 2");
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    #[test]
    fn reads_decode_and_check_quantity() {
        assert_eq!(
            parse_request(&[0x03, 0x07, 0xD0, 0x00, 0x02]),
            Ok(Request::ReadHoldingRegisters {
                address: 2000,
                quantity: 2
            })
        );
        assert_eq!(
            parse_request(&[0x03, 0, 0, 0, 0]),
            Err(Exception::IllegalDataValue)
        );
        assert_eq!(
            parse_request(&[0x03, 0, 0, 0, 126]),
            Err(Exception::IllegalDataValue)
        );
        assert_eq!(
            parse_request(&[0x01, 0, 0, 0x07, 0xD0]),
            Ok(Request::ReadCoils {
                address: 0,
                quantity: 2000
            })
        );
        assert_eq!(
            parse_request(&[0x01, 0, 0, 0x07, 0xD1]),
            Err(Exception::IllegalDataValue)
        );
        // Too short and too long bodies.
        assert_eq!(
            parse_request(&[0x03, 0, 0]),
            Err(Exception::IllegalDataValue)
        );
        assert_eq!(
            parse_request(&[0x03, 0, 0, 0, 1, 9]),
            Err(Exception::IllegalDataValue)
        );
    }

    #[test]
    fn unknown_functions_are_illegal() {
        for f in [0x00, 0x07, 0x08, 0x11, 0x16, 0x17, 0x2B, 0x41, 0x83, 0xFF] {
            assert_eq!(
                parse_request(&[f, 0, 0, 0, 1]),
                Err(Exception::IllegalFunction)
            );
        }
        assert_eq!(parse_request(&[]), Err(Exception::IllegalFunction));
    }

    #[test]
    fn single_coil_takes_only_the_two_legal_values() {
        assert_eq!(
            parse_request(&[0x05, 0x27, 0x1F, 0xFF, 0x00]),
            Ok(Request::WriteSingleCoil {
                address: 10015,
                on: true
            })
        );
        assert_eq!(
            parse_request(&[0x05, 0, 1, 0, 0]),
            Ok(Request::WriteSingleCoil {
                address: 1,
                on: false
            })
        );
        assert_eq!(
            parse_request(&[0x05, 0, 1, 0, 1]),
            Err(Exception::IllegalDataValue)
        );
    }

    #[test]
    fn multiple_coils_need_a_matching_byte_count() {
        // 10 coils: 0b1100_1101, 0b01 → on at 0, 2, 3, 6, 7, 8.
        let pdu = [0x0F, 0, 20, 0, 10, 2, 0xCD, 0x01];
        let Ok(Request::WriteMultipleCoils { address, coils }) = parse_request(&pdu) else {
            panic!("should decode");
        };
        assert_eq!(address, 20);
        let on: Vec<usize> = (0..10).filter(|&i| coils[i]).collect();
        assert_eq!(on, vec![0, 2, 3, 6, 7, 8]);
        // Quantity claims more coils than the bytes hold: 03, no panic.
        assert_eq!(
            parse_request(&[0x0F, 0, 0, 0, 100, 1, 0xFF]),
            Err(Exception::IllegalDataValue)
        );
        // Byte count says 2, only 1 byte follows.
        assert_eq!(
            parse_request(&[0x0F, 0, 0, 0, 10, 2, 0xFF]),
            Err(Exception::IllegalDataValue)
        );
        assert_eq!(
            parse_request(&[0x0F, 0, 0, 0, 0, 0]),
            Err(Exception::IllegalDataValue)
        );
    }

    #[test]
    fn multiple_registers_need_a_matching_byte_count() {
        assert_eq!(
            parse_request(&[0x10, 0, 100, 0, 2, 4, 0x12, 0x34, 0xFF, 0xFE]),
            Ok(Request::WriteMultipleRegisters {
                address: 100,
                values: vec![0x1234, 0xFFFE]
            })
        );
        // Quantity 0x8000 would overflow a naive `quantity * 2`.
        assert_eq!(
            parse_request(&[0x10, 0, 0, 0x80, 0, 0]),
            Err(Exception::IllegalDataValue)
        );
        assert_eq!(
            parse_request(&[0x10, 0, 0, 0, 124, 248]),
            Err(Exception::IllegalDataValue)
        );
        assert_eq!(
            parse_request(&[0x10, 0, 0, 0, 1, 2, 0x12]),
            Err(Exception::IllegalDataValue)
        );
    }

    #[test]
    fn responses_encode_per_the_specification() {
        assert_eq!(
            encode_response(
                0x01,
                &Ok(Response::Bits(vec![
                    true, false, true, true, false, false, true, true, true
                ]))
            ),
            vec![0x01, 2, 0xCD, 0x01]
        );
        assert_eq!(
            encode_response(0x03, &Ok(Response::Registers(vec![0x1234, 1]))),
            vec![0x03, 4, 0x12, 0x34, 0, 1]
        );
        assert_eq!(
            encode_response(
                0x06,
                &Ok(Response::Echo {
                    address: 7,
                    value: 9
                })
            ),
            vec![0x06, 0, 7, 0, 9]
        );
        assert_eq!(
            encode_response(
                0x10,
                &Ok(Response::Written {
                    address: 7,
                    quantity: 3
                })
            ),
            vec![0x10, 0, 7, 0, 3]
        );
        assert_eq!(
            encode_response(0x05, &Err(Exception::IllegalDataAddress)),
            vec![0x85, 0x02]
        );
    }
}
