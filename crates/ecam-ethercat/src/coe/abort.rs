//! SDO abort codes (ETG1000.6 table 41, after CiA 301): what the emulated
//! drive answers when it refuses a transfer, and their text.

use ethercrab::EtherCrabWireRead;

/// An SDO abort code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SdoAbort(pub u32);

impl SdoAbort {
    /// Client/server command specifier not valid or unknown.
    pub const COMMAND: Self = Self(0x0504_0001);
    /// Unsupported access to an object (e.g. complete access).
    pub const UNSUPPORTED_ACCESS: Self = Self(0x0601_0000);
    /// Attempt to write a read-only object.
    pub const READ_ONLY: Self = Self(0x0601_0002);
    /// Sub-index 0 must be 0 before the entries may be written.
    pub const SUB_INDEX_0_FIRST: Self = Self(0x0601_0003);
    /// Object length exceeds the mailbox.
    pub const TOO_LARGE: Self = Self(0x0601_0005);
    /// The object does not exist.
    pub const NO_OBJECT: Self = Self(0x0602_0000);
    /// The object cannot be mapped into the PDO.
    pub const NOT_MAPPABLE: Self = Self(0x0604_0041);
    /// The mapped objects exceed the PDO length.
    pub const PDO_TOO_LONG: Self = Self(0x0604_0042);
    /// Data type does not match (length of the service parameter).
    pub const LENGTH: Self = Self(0x0607_0010);
    /// The sub-index does not exist.
    pub const NO_SUB_INDEX: Self = Self(0x0609_0011);
    /// Value range of the parameter exceeded.
    pub const VALUE_RANGE: Self = Self(0x0609_0030);
    /// Not in the present device state (e.g. a mapping outside PRE-OP).
    pub const DEVICE_STATE: Self = Self(0x0800_0022);
}

impl core::fmt::Display for SdoAbort {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(&abort_text(self.0))
    }
}

/// An abort code in words, as `0x06020000: The object does not exist …`
/// (ethercrab's table of ETG1000.6's codes).
pub fn abort_text(code: u32) -> String {
    match ethercrab::error::CoeAbortCode::unpack_from_slice(&code.to_le_bytes()) {
        Ok(known) => known.to_string(),
        Err(_) => format!("{code:#010x}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_in_words() {
        assert!(
            SdoAbort::NO_OBJECT
                .to_string()
                .contains("object does not exist")
        );
        assert!(abort_text(0x1234_5678).starts_with("0x12345678"));
    }
}
