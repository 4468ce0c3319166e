//! The process data of a CSP drive: what goes out (RxPDO 0x1600) and what
//! comes back (TxPDO 0x1A00) each cycle, packed little-endian in mapping
//! order as EtherCAT carries it.

/// One mapped object: index, sub-index, CoE data type and width.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PdoEntry {
    /// Object index (e.g. 0x6040).
    pub index: u16,
    /// Sub-index.
    pub sub_index: u8,
    /// CoE data type code (0x0002 INTEGER8, 0x0004 INTEGER32, 0x0006
    /// UNSIGNED16).
    pub data_type: u8,
    /// Width in bits.
    pub bits: u8,
}

impl PdoEntry {
    /// The 32-bit mapping value (index, sub-index, bit length) written to
    /// a PDO mapping object (0x16xx/0x1Axx sub-indices).
    pub const fn mapping(&self) -> u32 {
        ((self.index as u32) << 16) | ((self.sub_index as u32) << 8) | self.bits as u32
    }
}

const INTEGER8: u8 = 0x02;
const INTEGER32: u8 = 0x04;
const UNSIGNED16: u8 = 0x06;

/// Outputs, master to drive: controlword, target position, mode.
pub const RX_PDO_ENTRIES: &[PdoEntry] = &[
    PdoEntry {
        index: 0x6040,
        sub_index: 0,
        data_type: UNSIGNED16,
        bits: 16,
    },
    PdoEntry {
        index: 0x607A,
        sub_index: 0,
        data_type: INTEGER32,
        bits: 32,
    },
    PdoEntry {
        index: 0x6060,
        sub_index: 0,
        data_type: INTEGER8,
        bits: 8,
    },
];

/// Inputs, drive to master: statusword, position actual, following error
/// actual, error code.
pub const TX_PDO_ENTRIES: &[PdoEntry] = &[
    PdoEntry {
        index: 0x6041,
        sub_index: 0,
        data_type: UNSIGNED16,
        bits: 16,
    },
    PdoEntry {
        index: 0x6064,
        sub_index: 0,
        data_type: INTEGER32,
        bits: 32,
    },
    PdoEntry {
        index: 0x60F4,
        sub_index: 0,
        data_type: INTEGER32,
        bits: 32,
    },
    PdoEntry {
        index: 0x603F,
        sub_index: 0,
        data_type: UNSIGNED16,
        bits: 16,
    },
];

/// Bytes of [`CspOutputs`] in the process image.
pub const OUTPUTS_LEN: usize = 7;
/// Bytes of [`CspInputs`] in the process image.
pub const INPUTS_LEN: usize = 12;

/// A process image slice of the wrong size: the drive's mapping is not the
/// CSP mapping this crate expects.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PdoSizeError {
    /// Bytes the CSP mapping needs.
    pub expected: usize,
    /// Bytes the drive maps.
    pub found: usize,
}

impl core::fmt::Display for PdoSizeError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "process data is {} bytes, the CSP mapping needs {} (check the drive's PDO assignment)",
            self.found, self.expected
        )
    }
}

impl std::error::Error for PdoSizeError {}

fn check(buf: &[u8], expected: usize) -> Result<(), PdoSizeError> {
    if buf.len() == expected {
        Ok(())
    } else {
        Err(PdoSizeError {
            expected,
            found: buf.len(),
        })
    }
}

/// The outputs of one CSP drive for one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CspOutputs {
    /// 0x6040 controlword.
    pub controlword: u16,
    /// 0x607A target position (drive counts, wrapping 32 bit).
    pub target_position: i32,
    /// 0x6060 mode of operation (8 = CSP).
    pub mode: i8,
}

impl CspOutputs {
    /// Writes these outputs into the drive's output slice.
    pub fn pack(&self, buf: &mut [u8]) -> Result<(), PdoSizeError> {
        check(buf, OUTPUTS_LEN)?;
        buf[0..2].copy_from_slice(&self.controlword.to_le_bytes());
        buf[2..6].copy_from_slice(&self.target_position.to_le_bytes());
        buf[6..7].copy_from_slice(&self.mode.to_le_bytes());
        Ok(())
    }

    /// Reads outputs from a drive's output slice.
    pub fn unpack(buf: &[u8]) -> Result<Self, PdoSizeError> {
        check(buf, OUTPUTS_LEN)?;
        Ok(Self {
            controlword: u16::from_le_bytes([buf[0], buf[1]]),
            target_position: i32::from_le_bytes([buf[2], buf[3], buf[4], buf[5]]),
            mode: i8::from_le_bytes([buf[6]]),
        })
    }
}

/// The inputs of one CSP drive for one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CspInputs {
    /// 0x6041 statusword.
    pub statusword: u16,
    /// 0x6064 position actual value (drive counts, wrapping 32 bit).
    pub position_actual: i32,
    /// 0x60F4 following error actual value.
    pub following_error: i32,
    /// 0x603F error code (0 = none).
    pub error_code: u16,
}

impl CspInputs {
    /// Writes these inputs into the drive's input slice.
    pub fn pack(&self, buf: &mut [u8]) -> Result<(), PdoSizeError> {
        check(buf, INPUTS_LEN)?;
        buf[0..2].copy_from_slice(&self.statusword.to_le_bytes());
        buf[2..6].copy_from_slice(&self.position_actual.to_le_bytes());
        buf[6..10].copy_from_slice(&self.following_error.to_le_bytes());
        buf[10..12].copy_from_slice(&self.error_code.to_le_bytes());
        Ok(())
    }

    /// Reads inputs from a drive's input slice.
    pub fn unpack(buf: &[u8]) -> Result<Self, PdoSizeError> {
        check(buf, INPUTS_LEN)?;
        Ok(Self {
            statusword: u16::from_le_bytes([buf[0], buf[1]]),
            position_actual: i32::from_le_bytes([buf[2], buf[3], buf[4], buf[5]]),
            following_error: i32::from_le_bytes([buf[6], buf[7], buf[8], buf[9]]),
            error_code: u16::from_le_bytes([buf[10], buf[11]]),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_match_the_mapping() {
        let bits =
            |entries: &[PdoEntry]| entries.iter().map(|e| usize::from(e.bits)).sum::<usize>();
        assert_eq!(bits(RX_PDO_ENTRIES), OUTPUTS_LEN * 8);
        assert_eq!(bits(TX_PDO_ENTRIES), INPUTS_LEN * 8);
        assert_eq!(RX_PDO_ENTRIES[1].mapping(), 0x607A_0020);
    }

    #[test]
    fn round_trip_and_layout() {
        let out = CspOutputs {
            controlword: 0x000F,
            target_position: -2,
            mode: 8,
        };
        let mut buf = [0u8; OUTPUTS_LEN];
        out.pack(&mut buf).unwrap();
        assert_eq!(buf, [0x0F, 0, 0xFE, 0xFF, 0xFF, 0xFF, 8]);
        assert_eq!(CspOutputs::unpack(&buf).unwrap(), out);
        let inputs = CspInputs {
            statusword: 0x1237,
            position_actual: i32::MIN,
            following_error: 5,
            error_code: 0x8611,
        };
        let mut buf = [0u8; INPUTS_LEN];
        inputs.pack(&mut buf).unwrap();
        assert_eq!(CspInputs::unpack(&buf).unwrap(), inputs);
    }

    #[test]
    fn wrong_sizes_are_refused() {
        let err = CspInputs::unpack(&[0u8; 8]).unwrap_err();
        assert_eq!(
            err,
            PdoSizeError {
                expected: 12,
                found: 8
            }
        );
        assert!(err.to_string().contains("PDO assignment"));
        assert!(CspOutputs::default().pack(&mut [0u8; 9]).is_err());
    }
}
