//! Why a client's write was not made, and how each face answers it
//! (docs/modbus.md, "Writes into cam blocks").

use core::fmt;

use ecam_plc::WriteRefusal;

use crate::journal::JournalError;
use crate::pdu::Exception;

/// A client's write that was not made; device memory is as it was.
#[derive(Debug)]
pub enum WriteError {
    /// The program's cams refuse it: it would leave a running cam's table
    /// invalid, or a table load aims where no table may go.
    Refused(WriteRefusal),
    /// The journal could not be written (`--state`), so the write was not
    /// applied either.
    Journal(JournalError),
}

impl WriteError {
    /// The Modbus exception a client gets: 03 (illegal data value) for a
    /// write the cams refuse, 04 (server device failure) for one that
    /// could not be made durable.
    pub fn exception(&self) -> Exception {
        match self {
            Self::Refused(_) => Exception::IllegalDataValue,
            Self::Journal(_) => Exception::ServerDeviceFailure,
        }
    }

    /// The HTTP status a client gets: 409 (conflict with the running
    /// program) for a refusal, except 400 for a table load into the
    /// special registers (never right); 500 when it could not be made
    /// durable.
    pub fn http_status(&self) -> u16 {
        match self {
            Self::Refused(WriteRefusal::SpecialRegisters { .. }) => 400,
            Self::Refused(_) => 409,
            Self::Journal(_) => 500,
        }
    }

    /// The PLC error code behind a refusal, if any (6781, 6782, 6783).
    pub fn code(&self) -> Option<u16> {
        match self {
            Self::Refused(refusal) => refusal.code(),
            Self::Journal(_) => None,
        }
    }
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Refused(refusal) => write!(f, "{refusal}"),
            Self::Journal(err) => write!(f, "not written: {err}"),
        }
    }
}

impl std::error::Error for WriteError {}

impl From<WriteRefusal> for WriteError {
    fn from(refusal: WriteRefusal) -> Self {
        Self::Refused(refusal)
    }
}

impl From<JournalError> for WriteError {
    fn from(err: JournalError) -> Self {
        Self::Journal(err)
    }
}
