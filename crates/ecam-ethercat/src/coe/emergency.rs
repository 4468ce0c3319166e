//! The CoE emergency message (ETG1000.6 section 5.6.4, CiA 301's EMCY): a
//! drive sends it unasked through its mailbox when an error appears or
//! is reset. Eight bytes: the error code (the same codes as 0x603F), the
//! error register (0x1001) and five bytes the manufacturer defines.

use super::{CoeService, MAILBOX_COE, MAILBOX_HEADER, MailboxHeader};
use crate::cia402::error_code_text;

/// Bytes of an emergency message in the mailbox (header, CoE header,
/// eight data bytes).
pub const EMERGENCY_BYTES: usize = MAILBOX_HEADER + 2 + 8;

/// One emergency message.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Emergency {
    /// The error code (0x0000: the error was reset).
    pub code: u16,
    /// The error register (0x1001).
    pub register: u8,
    /// The manufacturer-specific bytes.
    pub data: [u8; 5],
}

impl Emergency {
    /// An emergency for `code` with the error register bits CiA 301 gives
    /// its class (generic, current, voltage, temperature, communication).
    pub fn for_code(code: u16) -> Self {
        let class = match code >> 12 {
            0x2 => 0x02,
            0x3 => 0x04,
            0x4 => 0x08,
            0x8 => 0x10,
            _ => 0,
        };
        Self {
            code,
            register: if code == 0 { 0 } else { 0x01 | class },
            data: [0; 5],
        }
    }

    /// The emergency in a mailbox message, if the message is one.
    pub fn from_mailbox(mailbox: &[u8]) -> Option<Self> {
        let header = MailboxHeader::parse(mailbox)?;
        if header.kind != MAILBOX_COE || usize::from(header.length) < 10 {
            return None;
        }
        let body = mailbox.get(MAILBOX_HEADER..EMERGENCY_BYTES)?;
        if CoeService::from_header(u16::from_le_bytes([body[0], body[1]]))
            != Some(CoeService::Emergency)
        {
            return None;
        }
        let mut data = [0; 5];
        data.copy_from_slice(&body[5..10]);
        Some(Self {
            code: u16::from_le_bytes([body[2], body[3]]),
            register: body[4],
            data,
        })
    }

    /// Writes the message into `out` (at least [`EMERGENCY_BYTES`]) and
    /// returns its length.
    pub fn write_mailbox(&self, out: &mut [u8]) -> usize {
        let Some(out) = out.get_mut(..EMERGENCY_BYTES) else {
            return 0;
        };
        MailboxHeader {
            length: 10,
            kind: MAILBOX_COE,
            counter: 0,
        }
        .write(out);
        out[6..8].copy_from_slice(&CoeService::Emergency.header().to_le_bytes());
        out[8..10].copy_from_slice(&self.code.to_le_bytes());
        out[10] = self.register;
        out[11..16].copy_from_slice(&self.data);
        EMERGENCY_BYTES
    }
}

impl core::fmt::Display for Emergency {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "emergency {:#06x} ({}), error register {:#04x} ({})",
            self.code,
            error_code_text(self.code),
            self.register,
            error_register_text(self.register)
        )?;
        if self.data != [0; 5] {
            write!(f, ", data")?;
            for b in self.data {
                write!(f, " {b:02x}")?;
            }
        }
        Ok(())
    }
}

/// The error register's bits in words (CiA 301 object 0x1001).
pub fn error_register_text(register: u8) -> String {
    const BITS: [&str; 8] = [
        "generic",
        "current",
        "voltage",
        "temperature",
        "communication",
        "device profile",
        "reserved",
        "manufacturer",
    ];
    if register == 0 {
        return "no error".into();
    }
    BITS.iter()
        .enumerate()
        .filter(|&(bit, _)| register & (1 << bit) != 0)
        .map(|(_, name)| *name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_through_a_mailbox() {
        let e = Emergency {
            data: [1, 2, 3, 4, 5],
            ..Emergency::for_code(0x2310)
        };
        assert_eq!(e.register, 0x03);
        let mut mailbox = [0u8; 128];
        assert_eq!(e.write_mailbox(&mut mailbox), EMERGENCY_BYTES);
        assert_eq!(Emergency::from_mailbox(&mailbox), Some(e));
        let text = e.to_string();
        assert!(text.contains("0x2310 (continuous over-current)"), "{text}");
        assert!(text.contains("0x03 (generic, current)"), "{text}");
        assert!(text.ends_with("data 01 02 03 04 05"), "{text}");
        // An SDO response is not an emergency.
        mailbox[7] = 0x30;
        assert_eq!(Emergency::from_mailbox(&mailbox), None);
        assert_eq!(Emergency::for_code(0).register, 0);
        assert_eq!(Emergency::for_code(0x8130).register, 0x11);
    }
}
