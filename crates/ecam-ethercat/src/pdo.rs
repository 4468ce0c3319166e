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

/// Where each CSP object sits in a drive's process data, as its PDO
/// mapping places it: the master writes the mapping it wants, reads back
/// what the drive took, and packs and unpacks by that, so a drive that
/// keeps its own order is still decoded right.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PdoLayout {
    /// Byte offsets of controlword, target position, mode of operation.
    outputs: [usize; 3],
    /// Byte offsets of statusword, position actual, following error,
    /// error code.
    inputs: [usize; 4],
}

/// A mapping that is not the CSP objects (in whatever order).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MappingError {
    /// An object the CSP process data does not carry (or a gap).
    Unknown {
        /// The mapping entry (index, sub-index, bits).
        entry: u32,
        /// In the outputs (RxPDO) or the inputs (TxPDO).
        outputs: bool,
    },
    /// A CSP object mapped with another width.
    Width {
        /// The mapping entry.
        entry: u32,
    },
    /// A CSP object mapped twice.
    Twice {
        /// The object's index.
        index: u16,
    },
    /// A CSP object not mapped.
    Missing {
        /// The object's index.
        index: u16,
    },
}

impl core::fmt::Display for MappingError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let entry = |e: u32| {
            format!(
                "{:#06x}:{:02x} ({} bits)",
                e >> 16,
                (e >> 8) & 0xFF,
                e & 0xFF
            )
        };
        match *self {
            Self::Unknown { entry: e, outputs } => write!(
                f,
                "its {} map {}, which CSP does not carry",
                if outputs {
                    "outputs (RxPDO)"
                } else {
                    "inputs (TxPDO)"
                },
                entry(e)
            ),
            Self::Width { entry: e } => write!(f, "it maps {} with another width", entry(e)),
            Self::Twice { index } => write!(f, "it maps {index:#06x} twice"),
            Self::Missing { index } => write!(f, "it does not map {index:#06x}"),
        }
    }
}

impl std::error::Error for MappingError {}

/// Offsets of `wanted` objects in a mapping list.
fn offsets<const N: usize>(
    mapping: &[u32],
    wanted: &[PdoEntry],
    outputs: bool,
) -> Result<[usize; N], MappingError> {
    let mut found = [None; N];
    let mut at = 0usize;
    for &entry in mapping {
        let index = (entry >> 16) as u16;
        let sub_index = ((entry >> 8) & 0xFF) as u8;
        let bits = (entry & 0xFF) as u8;
        let Some(k) = wanted
            .iter()
            .position(|w| w.index == index && w.sub_index == sub_index)
        else {
            return Err(MappingError::Unknown { entry, outputs });
        };
        if wanted[k].bits != bits {
            return Err(MappingError::Width { entry });
        }
        if found[k].replace(at).is_some() {
            return Err(MappingError::Twice { index });
        }
        at += usize::from(bits / 8);
    }
    let mut out = [0; N];
    for (k, slot) in found.iter().enumerate() {
        out[k] = slot.ok_or(MappingError::Missing {
            index: wanted[k].index,
        })?;
    }
    Ok(out)
}

impl PdoLayout {
    /// The order of [`RX_PDO_ENTRIES`] and [`TX_PDO_ENTRIES`].
    pub const CSP: Self = Self {
        outputs: [0, 2, 6],
        inputs: [0, 2, 6, 10],
    };

    /// The layout of a drive's mapping (entries as `index << 16 |
    /// sub_index << 8 | bits`, in PDO order): exactly the CSP objects, in
    /// any order.
    ///
    /// # Errors
    /// The mapping carries other objects, misses one, or maps one twice
    /// or with another width.
    pub fn from_mapping(outputs: &[u32], inputs: &[u32]) -> Result<Self, MappingError> {
        Ok(Self {
            outputs: offsets(outputs, RX_PDO_ENTRIES, true)?,
            inputs: offsets(inputs, TX_PDO_ENTRIES, false)?,
        })
    }

    /// Writes `out` into a drive's output slice.
    ///
    /// # Errors
    /// The slice is not [`OUTPUTS_LEN`] bytes.
    pub fn pack(&self, out: &CspOutputs, buf: &mut [u8]) -> Result<(), PdoSizeError> {
        check(buf, OUTPUTS_LEN)?;
        let [cw, target, mode] = self.outputs;
        buf[cw..cw + 2].copy_from_slice(&out.controlword.to_le_bytes());
        buf[target..target + 4].copy_from_slice(&out.target_position.to_le_bytes());
        buf[mode] = out.mode.to_le_bytes()[0];
        Ok(())
    }

    /// Reads a drive's input slice.
    ///
    /// # Errors
    /// The slice is not [`INPUTS_LEN`] bytes.
    pub fn unpack(&self, buf: &[u8]) -> Result<CspInputs, PdoSizeError> {
        check(buf, INPUTS_LEN)?;
        let [sw, position, ferr, code] = self.inputs;
        let u16_at = |at: usize| u16::from_le_bytes([buf[at], buf[at + 1]]);
        let i32_at =
            |at: usize| i32::from_le_bytes([buf[at], buf[at + 1], buf[at + 2], buf[at + 3]]);
        Ok(CspInputs {
            statusword: u16_at(sw),
            position_actual: i32_at(position),
            following_error: i32_at(ferr),
            error_code: u16_at(code),
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
    fn a_reordered_mapping_is_decoded_by_its_layout() {
        let m = |entries: &[PdoEntry]| entries.iter().map(PdoEntry::mapping).collect::<Vec<_>>();
        let rx = m(RX_PDO_ENTRIES);
        let mut tx = m(TX_PDO_ENTRIES);
        assert_eq!(PdoLayout::from_mapping(&rx, &tx), Ok(PdoLayout::CSP));
        // Statusword, error code, position, following error.
        tx.swap(1, 3);
        tx.swap(2, 3);
        let layout = PdoLayout::from_mapping(&rx, &tx).unwrap();
        let mut buf = [0u8; INPUTS_LEN];
        buf[0..2].copy_from_slice(&0x0237u16.to_le_bytes());
        buf[2..4].copy_from_slice(&0x2310u16.to_le_bytes());
        buf[4..8].copy_from_slice(&(-7i32).to_le_bytes());
        buf[8..12].copy_from_slice(&3i32.to_le_bytes());
        let inputs = layout.unpack(&buf).unwrap();
        assert_eq!(
            inputs,
            CspInputs {
                statusword: 0x0237,
                position_actual: -7,
                following_error: 3,
                error_code: 0x2310
            }
        );
        assert_ne!(
            CspInputs::unpack(&buf).unwrap(),
            inputs,
            "the fixed order misreads it"
        );
        let out = CspOutputs {
            controlword: 0x0F,
            target_position: 9,
            mode: 8,
        };
        let mut o = [0u8; OUTPUTS_LEN];
        PdoLayout::CSP.pack(&out, &mut o).unwrap();
        assert_eq!(CspOutputs::unpack(&o).unwrap(), out);
    }

    #[test]
    fn a_mapping_of_other_objects_is_refused() {
        let rx: Vec<u32> = RX_PDO_ENTRIES.iter().map(PdoEntry::mapping).collect();
        let tx: Vec<u32> = TX_PDO_ENTRIES.iter().map(PdoEntry::mapping).collect();
        let mut other = tx.clone();
        other[2] = 0x606C_0020; // velocity actual instead of following error
        assert_eq!(
            PdoLayout::from_mapping(&rx, &other),
            Err(MappingError::Unknown {
                entry: 0x606C_0020,
                outputs: false
            })
        );
        assert_eq!(
            PdoLayout::from_mapping(&rx, &tx[..3]),
            Err(MappingError::Missing { index: 0x603F })
        );
        let twice = [tx[0], tx[0], tx[1], tx[2], tx[3]];
        assert_eq!(
            PdoLayout::from_mapping(&rx, &twice),
            Err(MappingError::Twice { index: 0x6041 })
        );
        let wide = [rx[0], rx[1], 0x6060_0010];
        let e = PdoLayout::from_mapping(&wide, &tx).unwrap_err();
        assert_eq!(e, MappingError::Width { entry: 0x6060_0010 });
        assert!(e.to_string().contains("0x6060:00 (16 bits)"), "{e}");
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
