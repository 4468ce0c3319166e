//! The SII EEPROM content of the emulated drive (ETG2010 layout): identity
//! and mailbox words, then categories (strings, general, FMMU, sync
//! managers, PDOs).

use super::mailbox::{MAILBOX_IN_START, MAILBOX_OUT_START, MAILBOX_SIZE};
use crate::pdo::{PdoEntry, RX_PDO_ENTRIES, TX_PDO_ENTRIES};

/// Vendor id the emulated drive reports (0 is the "unassigned" id, so it
/// cannot be mistaken for a real product).
pub const EMULATED_VENDOR_ID: u32 = 0x0000_0000;
/// Product code of the emulated CSP drive ("ECAM" in ASCII).
pub const EMULATED_PRODUCT_CODE: u32 = 0x4543_414D;
/// The name the drive reports (its order string).
pub const EMULATED_NAME: &str = "ecam emulated CSP drive";

/// Physical address of the outputs sync manager (SM2) in the ESC memory.
pub const SM2_START: u16 = 0x1100;
/// Physical address of the inputs sync manager (SM3).
pub const SM3_START: u16 = 0x1180;

const CATEGORY_STRINGS: u16 = 10;
const CATEGORY_GENERAL: u16 = 30;
const CATEGORY_FMMU: u16 = 40;
const CATEGORY_SYNC_MANAGER: u16 = 41;
const CATEGORY_TX_PDO: u16 = 50;
const CATEGORY_RX_PDO: u16 = 51;
const CATEGORY_END: u16 = 0xFFFF;

/// Mailbox protocols word: CoE only (ETG2010 table 2).
const PROTOCOL_COE: u16 = 0x0004;
/// CoE details of the general category: SDO, SDO information, PDO
/// assignment, PDO configuration (no complete access).
const COE_DETAILS: u8 = 0x0F;

/// Builds the EEPROM image (bytes, little-endian words) for drive
/// `serial`; with `fixed_mapping` its TxPDO lists the inputs in the order
/// [`super::DriveBehaviour::fixed_mapping`] gives them, and PDO
/// configuration is not offered.
pub fn drive_eeprom(serial: u32, fixed_mapping: bool) -> Vec<u8> {
    let mut words = vec![0u8; 0x40 * 2];
    put_u32(&mut words, 0x08, EMULATED_VENDOR_ID);
    put_u32(&mut words, 0x0A, EMULATED_PRODUCT_CODE);
    put_u32(&mut words, 0x0C, 1);
    put_u32(&mut words, 0x0E, serial);
    // Standard mailbox: receive (master → drive) offset and size, send
    // offset and size, then the protocols.
    let size = MAILBOX_SIZE as u16;
    put_u16(&mut words, 0x18, MAILBOX_OUT_START);
    put_u16(&mut words, 0x19, size);
    put_u16(&mut words, 0x1A, MAILBOX_IN_START);
    put_u16(&mut words, 0x1B, size);
    put_u16(&mut words, 0x1C, PROTOCOL_COE);
    // Word 0x3E: EEPROM size in kbit minus one; 0x3F: version.
    put_u16(&mut words, 0x3E, 1);
    put_u16(&mut words, 0x3F, 1);

    // Strings: 1 = name/order, 2 = PDO names.
    let mut strings = vec![2u8];
    for s in [EMULATED_NAME, "CSP"] {
        strings.push(u8::try_from(s.len()).unwrap_or(u8::MAX));
        strings.extend_from_slice(s.as_bytes());
    }
    category(&mut words, CATEGORY_STRINGS, &strings);

    // General: order string 1, name string 1; 32 bytes.
    let mut general = vec![0u8; 32];
    general[2] = 1; // order index
    general[3] = 1; // name index
    general[5] = if fixed_mapping {
        COE_DETAILS & !0x08
    } else {
        COE_DETAILS
    };
    category(&mut words, CATEGORY_GENERAL, &general);

    // FMMU usage, listed per sync manager so FMMU n serves SM n.
    category(&mut words, CATEGORY_FMMU, &[0xFF, 0xFF, 0x01, 0x02]);

    let mut sms = Vec::new();
    // SM0/SM1: the mailboxes (master writes SM0, reads SM1).
    sms.extend_from_slice(&sync_manager(MAILBOX_OUT_START, size, 0x26, true, 1));
    sms.extend_from_slice(&sync_manager(MAILBOX_IN_START, size, 0x22, true, 2));
    // SM2: outputs, buffered, master writes; SM3: inputs, buffered.
    sms.extend_from_slice(&sync_manager(SM2_START, 0, 0x64, true, 3));
    sms.extend_from_slice(&sync_manager(SM3_START, 0, 0x20, true, 4));
    category(&mut words, CATEGORY_SYNC_MANAGER, &sms);

    let mut tx = TX_PDO_ENTRIES.to_vec();
    if fixed_mapping {
        // Statusword, error code, position, following error.
        tx.swap(1, 3);
        tx.swap(2, 3);
    }
    category(&mut words, CATEGORY_TX_PDO, &pdo(0x1A00, 3, &tx));
    category(&mut words, CATEGORY_RX_PDO, &pdo(0x1600, 2, RX_PDO_ENTRIES));
    words.extend_from_slice(&CATEGORY_END.to_le_bytes());
    words.extend_from_slice(&[0u8; 16]);
    words
}

fn put_u16(buf: &mut [u8], word: usize, value: u16) {
    buf[word * 2..word * 2 + 2].copy_from_slice(&value.to_le_bytes());
}

fn put_u32(buf: &mut [u8], word: usize, value: u32) {
    buf[word * 2..word * 2 + 4].copy_from_slice(&value.to_le_bytes());
}

fn category(out: &mut Vec<u8>, kind: u16, data: &[u8]) {
    let mut data = data.to_vec();
    if data.len() % 2 == 1 {
        data.push(0);
    }
    out.extend_from_slice(&kind.to_le_bytes());
    let words = u16::try_from(data.len() / 2).unwrap_or(u16::MAX);
    out.extend_from_slice(&words.to_le_bytes());
    out.extend_from_slice(&data);
}

fn sync_manager(start: u16, len: u16, control: u8, enable: bool, usage: u8) -> [u8; 8] {
    let [s0, s1] = start.to_le_bytes();
    let [l0, l1] = len.to_le_bytes();
    [s0, s1, l0, l1, control, 0, u8::from(enable), usage]
}

fn pdo(index: u16, sync_manager: u8, entries: &[PdoEntry]) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(&index.to_le_bytes());
    out.push(u8::try_from(entries.len()).unwrap_or(u8::MAX));
    out.push(sync_manager);
    out.extend_from_slice(&[0, 2, 0, 0]); // DC sync, name string 2, flags
    for entry in entries {
        out.extend_from_slice(&entry.index.to_le_bytes());
        out.push(entry.sub_index);
        out.push(0); // name
        out.push(entry.data_type);
        out.push(entry.bits);
        out.extend_from_slice(&[0, 0]);
    }
    out
}
