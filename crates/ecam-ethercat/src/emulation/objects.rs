//! The emulated drive's object dictionary: the CiA 301 communication
//! objects (identity, PDO mapping and assignment, the sync managers'
//! synchronisation parameters 0x1C32/0x1C33 of ETG1020) and the CiA 402
//! objects a CSP drive has. Descriptions are static (the SDO information
//! service lists them); values live here or in the drive model.

use super::drive::DriveModel;
use super::sii::{EMULATED_NAME, EMULATED_PRODUCT_CODE, EMULATED_VENDOR_ID};
use crate::coe::{Emergency, SdoAbort};

/// CoE data types (ETG1000.6 table 64, CiA 301).
pub(crate) mod data_type {
    pub const INTEGER8: u16 = 0x0002;
    pub const INTEGER16: u16 = 0x0003;
    pub const INTEGER32: u16 = 0x0004;
    pub const UNSIGNED8: u16 = 0x0005;
    pub const UNSIGNED16: u16 = 0x0006;
    pub const UNSIGNED32: u16 = 0x0007;
    pub const VISIBLE_STRING: u16 = 0x0009;
    pub const PDO_MAPPING: u16 = 0x0021;
    pub const IDENTITY: u16 = 0x0023;
}
use data_type::*;

/// Object access bits of an entry description (ETG1000.6 table 57):
/// read in PRE-OP, SAFE-OP, OP; write in PRE-OP, SAFE-OP, OP; mappable
/// into an RxPDO, a TxPDO.
const READ: u16 = 0x07;
const WRITE_PRE_OP: u16 = 0x08;
const WRITE: u16 = 0x38;
const RO: u16 = READ;
const RW: u16 = READ | WRITE;
const RW_PRE_OP: u16 = READ | WRITE_PRE_OP;
const RX_MAP: u16 = 0x40;
const TX_MAP: u16 = 0x80;

/// CiA 301 object codes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ObjectCode {
    /// One value.
    Var = 7,
    /// Entries of one type.
    Array = 8,
    /// Entries of their own types.
    Record = 9,
}

/// One sub-index.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Entry {
    pub name: &'static str,
    pub data_type: u16,
    pub bits: u16,
    pub access: u16,
}

/// One object.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Object {
    pub index: u16,
    pub name: &'static str,
    pub code: ObjectCode,
    /// The data type the object description gives.
    pub data_type: u16,
    /// Sub-index 0 first.
    pub entries: &'static [Entry],
}

const fn e(name: &'static str, data_type: u16, bits: u16, access: u16) -> Entry {
    Entry {
        name,
        data_type,
        bits,
        access,
    }
}

const fn var(index: u16, name: &'static str, entry: &'static [Entry]) -> Object {
    Object {
        index,
        name,
        code: ObjectCode::Var,
        data_type: entry[0].data_type,
        entries: entry,
    }
}

const COUNT_RO: Entry = e("Number of entries", UNSIGNED8, 8, RO);
const COUNT_PRE_OP: Entry = e("Number of entries", UNSIGNED8, 8, RW_PRE_OP);
const MAP: Entry = e("Mapped object", UNSIGNED32, 32, RW_PRE_OP);
const ASSIGN: Entry = e("Assigned PDO", UNSIGNED16, 16, RW_PRE_OP);
/// Entries a PDO mapping object holds.
pub(crate) const MAX_MAPPED: usize = 8;
const MAPPING: &[Entry] = &[COUNT_PRE_OP, MAP, MAP, MAP, MAP, MAP, MAP, MAP, MAP];
const SYNC: &[Entry] = &[
    e("Number of entries", UNSIGNED8, 8, RO),
    e("Synchronization type", UNSIGNED16, 16, RW_PRE_OP),
    e("Cycle time", UNSIGNED32, 32, RW_PRE_OP),
    e("Shift time", UNSIGNED32, 32, RO),
    e("Synchronization types supported", UNSIGNED16, 16, RO),
    e("Minimum cycle time", UNSIGNED32, 32, RO),
    e("Calc and copy time", UNSIGNED32, 32, RO),
    e("Minimum delay time", UNSIGNED32, 32, RO),
    e("Get cycle time", UNSIGNED16, 16, RW),
    e("Delay time", UNSIGNED32, 32, RO),
    e("Sync0 cycle time", UNSIGNED32, 32, RO),
    e("SM-event missed", UNSIGNED16, 16, RO),
    e("Cycle time too small", UNSIGNED16, 16, RO),
];
const SOFTWARE_VERSION: &str = env!("CARGO_PKG_VERSION");

const fn text_bits(s: &str) -> u16 {
    (s.len() * 8) as u16
}

/// Every object, by index.
pub(crate) static OBJECTS: &[Object] = &[
    var(
        0x1000,
        "Device type",
        &[e("Device type", UNSIGNED32, 32, RO)],
    ),
    var(
        0x1001,
        "Error register",
        &[e("Error register", UNSIGNED8, 8, RO)],
    ),
    var(
        0x1008,
        "Manufacturer device name",
        &[e(
            "Manufacturer device name",
            VISIBLE_STRING,
            text_bits(EMULATED_NAME),
            RO,
        )],
    ),
    var(
        0x100A,
        "Manufacturer software version",
        &[e(
            "Manufacturer software version",
            VISIBLE_STRING,
            text_bits(SOFTWARE_VERSION),
            RO,
        )],
    ),
    Object {
        index: 0x1018,
        name: "Identity",
        code: ObjectCode::Record,
        data_type: IDENTITY,
        entries: &[
            COUNT_RO,
            e("Vendor ID", UNSIGNED32, 32, RO),
            e("Product code", UNSIGNED32, 32, RO),
            e("Revision number", UNSIGNED32, 32, RO),
            e("Serial number", UNSIGNED32, 32, RO),
        ],
    },
    Object {
        index: 0x1600,
        name: "RxPDO 1 mapping",
        code: ObjectCode::Record,
        data_type: PDO_MAPPING,
        entries: MAPPING,
    },
    Object {
        index: 0x1A00,
        name: "TxPDO 1 mapping",
        code: ObjectCode::Record,
        data_type: PDO_MAPPING,
        entries: MAPPING,
    },
    Object {
        index: 0x1C00,
        name: "Sync manager communication type",
        code: ObjectCode::Array,
        data_type: UNSIGNED8,
        entries: &[
            COUNT_RO,
            e("SM0 (mailbox out)", UNSIGNED8, 8, RO),
            e("SM1 (mailbox in)", UNSIGNED8, 8, RO),
            e("SM2 (outputs)", UNSIGNED8, 8, RO),
            e("SM3 (inputs)", UNSIGNED8, 8, RO),
        ],
    },
    Object {
        index: 0x1C12,
        name: "RxPDO assign",
        code: ObjectCode::Array,
        data_type: UNSIGNED16,
        entries: &[COUNT_PRE_OP, ASSIGN],
    },
    Object {
        index: 0x1C13,
        name: "TxPDO assign",
        code: ObjectCode::Array,
        data_type: UNSIGNED16,
        entries: &[COUNT_PRE_OP, ASSIGN],
    },
    Object {
        index: 0x1C32,
        name: "SM output parameter",
        code: ObjectCode::Record,
        data_type: 0,
        entries: SYNC,
    },
    Object {
        index: 0x1C33,
        name: "SM input parameter",
        code: ObjectCode::Record,
        data_type: 0,
        entries: SYNC,
    },
    var(
        0x603F,
        "Error code",
        &[e("Error code", UNSIGNED16, 16, RO | TX_MAP)],
    ),
    var(
        0x6040,
        "Controlword",
        &[e("Controlword", UNSIGNED16, 16, RW | RX_MAP)],
    ),
    var(
        0x6041,
        "Statusword",
        &[e("Statusword", UNSIGNED16, 16, RO | TX_MAP)],
    ),
    var(
        0x605A,
        "Quick stop option code",
        &[e("Quick stop option code", INTEGER16, 16, RW)],
    ),
    var(
        0x6060,
        "Modes of operation",
        &[e("Modes of operation", INTEGER8, 8, RW | RX_MAP)],
    ),
    var(
        0x6061,
        "Modes of operation display",
        &[e("Modes of operation display", INTEGER8, 8, RO | TX_MAP)],
    ),
    var(
        0x6064,
        "Position actual value",
        &[e("Position actual value", INTEGER32, 32, RO | TX_MAP)],
    ),
    var(
        0x6065,
        "Following error window",
        &[e("Following error window", UNSIGNED32, 32, RW)],
    ),
    var(
        0x6066,
        "Following error time out",
        &[e("Following error time out", UNSIGNED16, 16, RW)],
    ),
    var(
        0x607A,
        "Target position",
        &[e("Target position", INTEGER32, 32, RW | RX_MAP)],
    ),
    var(
        0x6085,
        "Quick stop deceleration",
        &[e("Quick stop deceleration", UNSIGNED32, 32, RW)],
    ),
    Object {
        index: 0x60C2,
        name: "Interpolation time period",
        code: ObjectCode::Record,
        data_type: 0,
        entries: &[
            COUNT_RO,
            e("Interpolation time period value", UNSIGNED8, 8, RW),
            e("Interpolation time index", INTEGER8, 8, RW),
        ],
    },
    var(
        0x60F4,
        "Following error actual value",
        &[e(
            "Following error actual value",
            INTEGER32,
            32,
            RO | TX_MAP,
        )],
    ),
    var(
        0x6502,
        "Supported drive modes",
        &[e("Supported drive modes", UNSIGNED32, 32, RO)],
    ),
];

/// The object at `index`.
pub(crate) fn object(index: u16) -> Option<&'static Object> {
    OBJECTS.iter().find(|o| o.index == index)
}

/// A value read from the dictionary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Value {
    /// A number of 1, 2 or 4 bytes (little-endian in `raw`).
    Int {
        /// The bits, zero-extended.
        raw: u32,
        /// Its width in bytes.
        bytes: u8,
    },
    /// A string.
    Text(&'static str),
}

impl Value {
    const fn u8(v: u8) -> Self {
        Self::Int {
            raw: v as u32,
            bytes: 1,
        }
    }
    const fn u16(v: u16) -> Self {
        Self::Int {
            raw: v as u32,
            bytes: 2,
        }
    }
    const fn u32(v: u32) -> Self {
        Self::Int { raw: v, bytes: 4 }
    }
    const fn i8(v: i8) -> Self {
        Self::u8(v as u8)
    }
    const fn i16(v: i16) -> Self {
        Self::u16(v as u16)
    }
    const fn i32(v: i32) -> Self {
        Self::u32(v as u32)
    }

    /// Its length in bytes.
    pub(crate) fn len(&self) -> usize {
        match self {
            Self::Int { bytes, .. } => usize::from(*bytes),
            Self::Text(s) => s.len(),
        }
    }

    /// Copies its bytes into `out` (as many as fit); returns how many.
    pub(crate) fn write_to(&self, out: &mut [u8]) -> usize {
        let raw;
        let bytes: &[u8] = match self {
            Self::Int { raw: r, bytes } => {
                raw = r.to_le_bytes();
                &raw[..usize::from(*bytes)]
            }
            Self::Text(s) => s.as_bytes(),
        };
        let n = bytes.len().min(out.len());
        out[..n].copy_from_slice(&bytes[..n]);
        n
    }
}

/// A PDO mapping object's content.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Mapping {
    /// Entries as `index << 16 | sub_index << 8 | bits`.
    pub entries: [u32; MAX_MAPPED],
    /// Sub-index 0: how many are in force.
    pub count: u8,
}

impl Mapping {
    fn of(entries: &[u32]) -> Self {
        let mut out = Self {
            entries: [0; MAX_MAPPED],
            count: 0,
        };
        for (slot, &v) in out.entries.iter_mut().zip(entries) {
            *slot = v;
            out.count += 1;
        }
        out
    }

    /// The entries in force.
    pub(crate) fn active(&self) -> &[u32] {
        &self.entries[..usize::from(self.count).min(MAX_MAPPED)]
    }

    /// Bytes the entries in force take.
    pub(crate) fn bytes(&self) -> usize {
        self.active()
            .iter()
            .map(|&m| (m & 0xFF) as usize)
            .sum::<usize>()
            / 8
    }
}

/// ETG1020 synchronisation parameters of one sync manager.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SyncParameters {
    /// 0 free run, 1 synchronous with the SM event, 2 DC SYNC0.
    pub mode: u16,
    /// The cycle the master announced, ns.
    pub cycle_ns: u32,
}

/// Shortest cycle the emulated drive accepts, ns (its 0x1C32:05).
pub(crate) const MIN_CYCLE_NS: u32 = 50_000;
/// 0x6502 bit of CSP.
const SUPPORTS_CSP: u32 = 1 << 7;
/// 0x6502 bit of profile position.
const SUPPORTS_PP: u32 = 1;

/// The values the dictionary keeps (the others are the drive's).
#[derive(Clone, Debug)]
pub(crate) struct Dictionary {
    serial: u32,
    fixed_mapping: bool,
    /// 0x1600, 0x1A00.
    pub rx: Mapping,
    /// 0x1A00.
    pub tx: Mapping,
    /// 0x1C12: count and the one PDO it may name.
    rx_assign: (u8, u16),
    /// 0x1C13.
    tx_assign: (u8, u16),
    /// 0x1C32, 0x1C33.
    pub sync: [SyncParameters; 2],
    quick_stop_option: i16,
    following_error_timeout: u16,
    quick_stop_deceleration: u32,
    interpolation: (u8, i8),
}

/// What a read sees besides the dictionary.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Live<'a> {
    /// The drive.
    pub drive: &'a DriveModel,
    /// The SYNC0 cycle the ESC runs, ns.
    pub sync0_cycle_ns: u32,
}

/// The CSP mappings: in the order of [`crate::pdo`], or for a drive with
/// a fixed mapping, its inputs in another order.
fn default_tx(fixed: bool) -> Mapping {
    let order: &[u16] = if fixed {
        &[0x6041, 0x603F, 0x6064, 0x60F4]
    } else {
        &[0x6041, 0x6064, 0x60F4, 0x603F]
    };
    let entries: Vec<u32> = order
        .iter()
        .filter_map(|&i| {
            crate::pdo::TX_PDO_ENTRIES
                .iter()
                .find(|e| e.index == i)
                .map(|e| e.mapping())
        })
        .collect();
    Mapping::of(&entries)
}

impl Dictionary {
    /// The dictionary of drive `serial` as it powers up.
    pub(crate) fn new(serial: u32, fixed_mapping: bool) -> Self {
        let rx: Vec<u32> = crate::pdo::RX_PDO_ENTRIES
            .iter()
            .map(|e| e.mapping())
            .collect();
        Self {
            serial,
            fixed_mapping,
            rx: Mapping::of(&rx),
            tx: default_tx(fixed_mapping),
            rx_assign: (1, 0x1600),
            tx_assign: (1, 0x1A00),
            sync: [SyncParameters {
                mode: 2,
                cycle_ns: 0,
            }; 2],
            quick_stop_option: 2,
            following_error_timeout: 10,
            quick_stop_deceleration: 100_000,
            interpolation: (1, -3),
        }
    }

    /// The RxPDO mapping in force (empty when none is assigned).
    pub(crate) fn rx_mapping(&self) -> &[u32] {
        if self.rx_assign.0 > 0 {
            self.rx.active()
        } else {
            &[]
        }
    }

    /// The TxPDO mapping in force.
    pub(crate) fn tx_mapping(&self) -> &[u32] {
        if self.tx_assign.0 > 0 {
            self.tx.active()
        } else {
            &[]
        }
    }

    /// Reads `index:sub`.
    pub(crate) fn read(&self, index: u16, sub: u8, live: Live<'_>) -> Result<Value, SdoAbort> {
        let object = object(index).ok_or(SdoAbort::NO_OBJECT)?;
        if usize::from(sub) >= object.entries.len() {
            return Err(SdoAbort::NO_SUB_INDEX);
        }
        let count = |o: &Object| Value::u8(u8::try_from(o.entries.len() - 1).unwrap_or(0));
        let drive = live.drive;
        let inputs = drive.inputs();
        Ok(match (index, sub) {
            (0x1000, _) => Value::u32(0x0002_0192),
            (0x1001, _) => Value::u8(Emergency::for_code(inputs.error_code).register),
            (0x1008, _) => Value::Text(EMULATED_NAME),
            (0x100A, _) => Value::Text(SOFTWARE_VERSION),
            (0x1018, 0) => count(object),
            (0x1018, 1) => Value::u32(EMULATED_VENDOR_ID),
            (0x1018, 2) => Value::u32(EMULATED_PRODUCT_CODE),
            (0x1018, 3) => Value::u32(1),
            (0x1018, _) => Value::u32(self.serial),
            (0x1600 | 0x1A00, 0) => Value::u8(self.mapping(index).count),
            (0x1600 | 0x1A00, n) => Value::u32(self.mapping(index).entries[usize::from(n) - 1]),
            (0x1C00, 0) => count(object),
            (0x1C00, n) => Value::u8(n),
            (0x1C12, 0) => Value::u8(self.rx_assign.0),
            (0x1C12, _) => Value::u16(self.rx_assign.1),
            (0x1C13, 0) => Value::u8(self.tx_assign.0),
            (0x1C13, _) => Value::u16(self.tx_assign.1),
            (0x1C32 | 0x1C33, sub) => {
                let p = self.sync[usize::from(index - 0x1C32)];
                match sub {
                    0 => count(object),
                    1 => Value::u16(p.mode),
                    2 => Value::u32(p.cycle_ns),
                    // DC SYNC0 only (ETG1020: bits 2–4 = 001).
                    4 => Value::u16(0x0004),
                    5 => Value::u32(MIN_CYCLE_NS),
                    8 | 11 | 12 => Value::u16(0),
                    10 => Value::u32(live.sync0_cycle_ns),
                    _ => Value::u32(0),
                }
            }
            (0x603F, _) => Value::u16(inputs.error_code),
            (0x6040, _) => Value::u16(drive.controlword()),
            (0x6041, _) => Value::u16(inputs.statusword),
            (0x605A, _) => Value::i16(self.quick_stop_option),
            (0x6060, _) => Value::i8(drive.requested_mode()),
            (0x6061, _) => Value::i8(drive.mode_display()),
            (0x6064, _) => Value::i32(inputs.position_actual),
            (0x6065, _) => Value::u32(drive.behaviour().following_error_window),
            (0x6066, _) => Value::u16(self.following_error_timeout),
            (0x607A, _) => Value::i32(drive.target()),
            (0x6085, _) => Value::u32(self.quick_stop_deceleration),
            (0x60C2, 0) => count(object),
            (0x60C2, 1) => Value::u8(self.interpolation.0),
            (0x60C2, _) => Value::i8(self.interpolation.1),
            (0x60F4, _) => Value::i32(inputs.following_error),
            (0x6502, _) => Value::u32(
                SUPPORTS_PP
                    | if drive.behaviour().csp {
                        SUPPORTS_CSP
                    } else {
                        0
                    },
            ),
            _ => return Err(SdoAbort::NO_OBJECT),
        })
    }

    fn mapping(&self, index: u16) -> &Mapping {
        if index == 0x1600 { &self.rx } else { &self.tx }
    }

    fn mapping_mut(&mut self, index: u16) -> &mut Mapping {
        if index == 0x1600 {
            &mut self.rx
        } else {
            &mut self.tx
        }
    }

    /// The access bits of an entry as this drive has them (a fixed
    /// mapping is read-only).
    pub(crate) fn access(&self, index: u16, entry: &Entry) -> u16 {
        if self.fixed_mapping && matches!(index, 0x1600 | 0x1A00 | 0x1C12 | 0x1C13) {
            entry.access & !(WRITE | WRITE_PRE_OP)
        } else {
            entry.access
        }
    }

    /// Writes `data` to `index:sub` in AL state `al` (2 PRE-OP, 4
    /// SAFE-OP, 8 OP).
    pub(crate) fn write(
        &mut self,
        index: u16,
        sub: u8,
        data: &[u8],
        al: u8,
        drive: &mut DriveModel,
    ) -> Result<(), SdoAbort> {
        let object = object(index).ok_or(SdoAbort::NO_OBJECT)?;
        let entry = object
            .entries
            .get(usize::from(sub))
            .ok_or(SdoAbort::NO_SUB_INDEX)?;
        let access = self.access(index, entry);
        if access & (WRITE | WRITE_PRE_OP) == 0 {
            return Err(SdoAbort::READ_ONLY);
        }
        let state_bit = match al {
            2 => WRITE_PRE_OP,
            4 => 0x10,
            8 => 0x20,
            _ => 0,
        };
        if access & state_bit == 0 {
            return Err(SdoAbort::DEVICE_STATE);
        }
        if data.len() != usize::from(entry.bits / 8) {
            return Err(SdoAbort::LENGTH);
        }
        let mut raw = [0u8; 4];
        raw[..data.len()].copy_from_slice(data);
        let v = u32::from_le_bytes(raw);
        match (index, sub) {
            (0x1600 | 0x1A00, 0) => {
                let n = usize::try_from(v).unwrap_or(usize::MAX);
                if n > MAX_MAPPED {
                    return Err(SdoAbort::VALUE_RANGE);
                }
                let direction = if index == 0x1600 { RX_MAP } else { TX_MAP };
                let mapping = self.mapping(index);
                for &m in &mapping.entries[..n] {
                    if !mappable(m, direction) {
                        return Err(SdoAbort::NOT_MAPPABLE);
                    }
                }
                self.mapping_mut(index).count = n as u8;
            }
            (0x1600 | 0x1A00, n) => {
                let mapping = self.mapping_mut(index);
                if mapping.count != 0 {
                    return Err(SdoAbort::SUB_INDEX_0_FIRST);
                }
                mapping.entries[usize::from(n) - 1] = v;
            }
            (0x1C12 | 0x1C13, 0) => {
                let pdo = if index == 0x1C12 { 0x1600 } else { 0x1A00 };
                let assign = self.assign_mut(index);
                if v > 1 || (v == 1 && assign.1 != pdo) {
                    return Err(SdoAbort::VALUE_RANGE);
                }
                assign.0 = v as u8;
            }
            (0x1C12 | 0x1C13, _) => {
                let pdo = if index == 0x1C12 { 0x1600 } else { 0x1A00 };
                let assign = self.assign_mut(index);
                if assign.0 != 0 {
                    return Err(SdoAbort::SUB_INDEX_0_FIRST);
                }
                if v != pdo && v != 0 {
                    return Err(SdoAbort::VALUE_RANGE);
                }
                assign.1 = v as u16;
            }
            (0x1C32 | 0x1C33, 1) => {
                // The emulated drive runs on SYNC0 only.
                if v != 2 {
                    return Err(SdoAbort::VALUE_RANGE);
                }
                self.sync[usize::from(index - 0x1C32)].mode = 2;
            }
            (0x1C32 | 0x1C33, 2) => {
                if v != 0 && v < MIN_CYCLE_NS {
                    return Err(SdoAbort::VALUE_RANGE);
                }
                self.sync[usize::from(index - 0x1C32)].cycle_ns = v;
            }
            (0x605A, _) => self.quick_stop_option = v as u16 as i16,
            (0x6060, _) => drive.set_mode(v as u8 as i8),
            (0x6065, _) => drive.set_following_error_window(v),
            (0x6066, _) => self.following_error_timeout = v as u16,
            (0x6085, _) => self.quick_stop_deceleration = v,
            (0x60C2, 1) => self.interpolation.0 = v as u8,
            (0x60C2, _) => self.interpolation.1 = v as u8 as i8,
            // Controlword and target by SDO: taken, then overwritten by
            // the process data (they are mapped).
            _ => {}
        }
        Ok(())
    }

    fn assign_mut(&mut self, index: u16) -> &mut (u8, u16) {
        if index == 0x1C12 {
            &mut self.rx_assign
        } else {
            &mut self.tx_assign
        }
    }
}

/// `mapping` names an entry that may go into a PDO of `direction` with
/// its own width.
fn mappable(mapping: u32, direction: u16) -> bool {
    let index = (mapping >> 16) as u16;
    let sub = usize::from((mapping >> 8) as u8);
    let bits = (mapping & 0xFF) as u16;
    object(index)
        .and_then(|o| o.entries.get(sub))
        .is_some_and(|entry| entry.access & direction != 0 && entry.bits == bits)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emulation::DriveBehaviour;

    fn drive() -> DriveModel {
        DriveModel::new(DriveBehaviour::default(), 0)
    }

    #[test]
    fn objects_are_sorted_and_fit_one_list_reply() {
        assert!(OBJECTS.windows(2).all(|w| w[0].index < w[1].index));
        // 128-byte mailbox: 6 + 6 header bytes, the list type, the indices.
        assert!(12 + 2 + 2 * OBJECTS.len() <= 128);
    }

    #[test]
    fn mapping_is_changed_the_profile_way() {
        let mut d = Dictionary::new(1, false);
        let mut m = drive();
        let w =
            |d: &mut Dictionary, m: &mut DriveModel, i, s, data: &[u8]| d.write(i, s, data, 2, m);
        assert_eq!(
            w(&mut d, &mut m, 0x1A00, 1, &0x6041_0010u32.to_le_bytes()),
            Err(SdoAbort::SUB_INDEX_0_FIRST)
        );
        w(&mut d, &mut m, 0x1A00, 0, &[0]).unwrap();
        w(&mut d, &mut m, 0x1A00, 1, &0x6064_0020u32.to_le_bytes()).unwrap();
        w(&mut d, &mut m, 0x1A00, 2, &0x6040_0010u32.to_le_bytes()).unwrap();
        assert_eq!(
            w(&mut d, &mut m, 0x1A00, 0, &[2]),
            Err(SdoAbort::NOT_MAPPABLE),
            "the controlword is not an input"
        );
        w(&mut d, &mut m, 0x1A00, 0, &[1]).unwrap();
        assert_eq!(d.tx_mapping(), &[0x6064_0020]);
        assert_eq!(
            d.write(0x1A00, 0, &[0], 8, &mut m),
            Err(SdoAbort::DEVICE_STATE)
        );
        assert_eq!(
            w(&mut d, &mut m, 0x1C13, 1, &0x1A01u16.to_le_bytes()),
            Err(SdoAbort::SUB_INDEX_0_FIRST)
        );
        assert_eq!(
            w(&mut d, &mut m, 0x6041, 0, &[0, 0]),
            Err(SdoAbort::READ_ONLY)
        );
        assert_eq!(w(&mut d, &mut m, 0x6065, 0, &[1, 0]), Err(SdoAbort::LENGTH));
        w(&mut d, &mut m, 0x6065, 0, &500u32.to_le_bytes()).unwrap();
        assert_eq!(m.behaviour().following_error_window, 500);
        assert_eq!(w(&mut d, &mut m, 0x2000, 0, &[0]), Err(SdoAbort::NO_OBJECT));
    }

    #[test]
    fn a_fixed_mapping_refuses_writes_and_a_drive_without_csp_keeps_its_mode() {
        let mut d = Dictionary::new(1, true);
        let mut m = DriveModel::new(
            DriveBehaviour {
                csp: false,
                ..DriveBehaviour::default()
            },
            0,
        );
        assert_eq!(
            d.write(0x1C13, 0, &[0], 2, &mut m),
            Err(SdoAbort::READ_ONLY)
        );
        assert_eq!(d.tx.bytes(), 12);
        assert_eq!(d.tx_mapping()[1], 0x603F_0010);
        d.write(0x6060, 0, &[8], 2, &mut m).unwrap();
        let live = Live {
            drive: &m,
            sync0_cycle_ns: 0,
        };
        assert_eq!(d.read(0x6060, 0, live), Ok(Value::i8(8)));
        assert_eq!(d.read(0x6061, 0, live), Ok(Value::i8(0)));
        assert_eq!(d.read(0x6502, 0, live), Ok(Value::u32(1)));
        assert_eq!(d.read(0x1018, 5, live), Err(SdoAbort::NO_SUB_INDEX));
        assert_eq!(d.read(0x1008, 0, live), Ok(Value::Text(EMULATED_NAME)));
    }
}
