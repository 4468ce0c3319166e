//! CAN application protocol over EtherCAT (CoE, ETG1000.6 section 5.6):
//! the mailbox and CoE headers both sides of ecam use, the SDO abort
//! codes and the emergency message. The master's SDO transfers go
//! through ethercrab; the emulated drive answers them
//! ([`crate::emulation`]); the cycle reads emergencies itself
//! ([`crate::segment::AcyclicStep::ReadMailbox`]).

mod abort;
mod emergency;

pub use abort::{SdoAbort, abort_text};
pub use emergency::{EMERGENCY_BYTES, Emergency, error_register_text};

/// Bytes of the mailbox header (length, address, channel and priority,
/// type and counter).
pub const MAILBOX_HEADER: usize = 6;
/// Mailbox type of CoE (ETG1000.4 table 29).
pub const MAILBOX_COE: u8 = 3;
/// Mailbox type of a mailbox error reply.
pub const MAILBOX_ERROR: u8 = 0;

/// The CoE service, the top four bits of the CoE header.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CoeService {
    /// Emergency (drive to master).
    Emergency = 1,
    /// SDO request (master to drive).
    SdoRequest = 2,
    /// SDO response.
    SdoResponse = 3,
    /// SDO information service.
    SdoInformation = 8,
}

impl CoeService {
    /// The service of a CoE header word.
    pub fn from_header(header: u16) -> Option<Self> {
        Some(match header >> 12 {
            1 => Self::Emergency,
            2 => Self::SdoRequest,
            3 => Self::SdoResponse,
            8 => Self::SdoInformation,
            _ => return None,
        })
    }

    /// The CoE header word of this service (number 0).
    pub const fn header(self) -> u16 {
        (self as u16) << 12
    }
}

/// A mailbox message's header, as it sits in the first six bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MailboxHeader {
    /// Bytes after the header.
    pub length: u16,
    /// Mailbox type (3: CoE).
    pub kind: u8,
    /// The sender's counter (1–7; 0 for messages outside a session).
    pub counter: u8,
}

impl MailboxHeader {
    /// Reads the header at the start of a mailbox; `None` when it is too
    /// short.
    pub fn parse(mailbox: &[u8]) -> Option<Self> {
        let bytes = mailbox.get(..MAILBOX_HEADER)?;
        Some(Self {
            length: u16::from_le_bytes([bytes[0], bytes[1]]),
            kind: bytes[5] & 0x0F,
            counter: (bytes[5] >> 4) & 0x07,
        })
    }

    /// Writes the header into the first six bytes of `out` (address,
    /// channel and priority 0).
    pub fn write(&self, out: &mut [u8]) {
        if let Some(bytes) = out.get_mut(..MAILBOX_HEADER) {
            bytes[0..2].copy_from_slice(&self.length.to_le_bytes());
            bytes[2..5].fill(0);
            bytes[5] = (self.kind & 0x0F) | ((self.counter & 0x07) << 4);
        }
    }
}
