//! The emulated drive's answers to CoE requests (ETG1000.6 section 5.6):
//! SDO download and upload, expedited (up to four bytes) and normal (a
//! string in one mailbox), aborts with their codes, and the SDO
//! information service (the object list, object and entry
//! descriptions). Complete access and segmented transfers are refused
//! with an abort: every object fits one mailbox.

use super::drive::DriveModel;
use super::mailbox::{MAILBOX_SIZE, Outbox};
use super::objects::{Dictionary, Live, OBJECTS, object};
use crate::coe::{CoeService, MAILBOX_COE, MAILBOX_ERROR, MAILBOX_HEADER, MailboxHeader, SdoAbort};

/// Bytes of the SDO header after the CoE header (command, index,
/// sub-index).
const SDO_HEADER: usize = 4;
/// Where an SDO's data starts in the mailbox.
const SDO_DATA: usize = MAILBOX_HEADER + 2 + SDO_HEADER;
/// Where the SDO information service's data starts (after its opcode,
/// reserved byte and fragments left).
const INFO_DATA: usize = MAILBOX_HEADER + 2 + 4;

/// SDO information opcodes (ETG1000.6 table 44).
mod opcode {
    pub const OD_LIST_REQUEST: u8 = 1;
    pub const OD_LIST_RESPONSE: u8 = 2;
    pub const OBJECT_REQUEST: u8 = 3;
    pub const OBJECT_RESPONSE: u8 = 4;
    pub const ENTRY_REQUEST: u8 = 5;
    pub const ENTRY_RESPONSE: u8 = 6;
    pub const ERROR: u8 = 7;
}

/// What an answer needs of the drive besides the request.
pub(crate) struct Server<'a> {
    /// The object dictionary.
    pub dictionary: &'a mut Dictionary,
    /// The drive.
    pub drive: &'a mut DriveModel,
    /// The ESC's AL state (2, 4, 8).
    pub al: u8,
    /// The SYNC0 cycle, ns.
    pub sync0_cycle_ns: u32,
}

impl Server<'_> {
    /// Answers the request in `request` (the whole SM0 area) into the
    /// outbox.
    pub(crate) fn answer(&mut self, request: &[u8], outbox: &mut Outbox) {
        let Some(header) = MailboxHeader::parse(request) else {
            return;
        };
        let end = MAILBOX_HEADER + usize::from(header.length);
        let Some(message) = request.get(..end) else {
            return;
        };
        let mut reply = [0u8; MAILBOX_SIZE];
        let service = message
            .get(MAILBOX_HEADER..MAILBOX_HEADER + 2)
            .and_then(|b| CoeService::from_header(u16::from_le_bytes([b[0], b[1]])));
        let (length, coe) = match (header.kind, service) {
            (MAILBOX_COE, Some(CoeService::SdoRequest)) => self.sdo(message, &mut reply),
            (MAILBOX_COE, Some(CoeService::SdoInformation)) => {
                self.information(message, &mut reply)
            }
            // ETG1000.4 table 30: 0x0002, protocol not supported.
            _ => mailbox_error(&mut reply, 0x0002),
        };
        if length <= MAILBOX_HEADER {
            return; // nothing to answer (the master aborted)
        }
        MailboxHeader {
            length: u16::try_from(length - MAILBOX_HEADER).unwrap_or(0),
            kind: if coe { MAILBOX_COE } else { MAILBOX_ERROR },
            counter: 0,
        }
        .write(&mut reply);
        if let Some(slot) = outbox.push() {
            *slot = reply;
        }
    }

    /// An SDO transfer; returns the reply's length and that it is CoE.
    fn sdo(&mut self, message: &[u8], reply: &mut [u8; MAILBOX_SIZE]) -> (usize, bool) {
        let Some(sdo) = message.get(MAILBOX_HEADER + 2..SDO_DATA) else {
            return mailbox_error(reply, 0x0003);
        };
        let (command, index, sub) = (sdo[0], u16::from_le_bytes([sdo[1], sdo[2]]), sdo[3]);
        let data = &message[SDO_DATA..];
        let complete_access = command & 0x10 != 0;
        let result = match command >> 5 {
            _ if complete_access && command >> 5 != 4 => Err(SdoAbort::UNSUPPORTED_ACCESS),
            // Initiate download: expedited (data in the header's four
            // bytes) or normal (a size, then the data).
            1 => {
                let bytes = if command & 0x02 != 0 {
                    let size = if command & 0x01 != 0 {
                        4 - usize::from((command >> 2) & 0x03)
                    } else {
                        4
                    };
                    data.get(..size)
                } else {
                    data.get(..4)
                        .map(|s| u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
                        .and_then(|n| data.get(4..4 + usize::try_from(n).unwrap_or(usize::MAX)))
                };
                match bytes {
                    Some(bytes) => self
                        .dictionary
                        .write(index, sub, bytes, self.al, self.drive)
                        .map(|()| {
                            reply[SDO_DATA - SDO_HEADER] = 0x60;
                            SDO_DATA + 4
                        }),
                    // A segmented download would follow: not offered.
                    None => Err(SdoAbort::TOO_LARGE),
                }
            }
            // Initiate upload.
            2 => self.upload(index, sub, reply),
            // The master aborts: nothing to answer.
            4 => {
                return (0, true);
            }
            _ => Err(SdoAbort::COMMAND),
        };
        let length = match result {
            Ok(length) => length,
            Err(abort) => {
                reply[SDO_DATA - SDO_HEADER] = 0x80;
                reply[SDO_DATA..SDO_DATA + 4].copy_from_slice(&abort.0.to_le_bytes());
                SDO_DATA + 4
            }
        };
        // An abort goes out as an SDO request (ETG1000.6 5.6.2.7), the
        // others as responses.
        let service = if reply[SDO_DATA - SDO_HEADER] == 0x80 {
            CoeService::SdoRequest
        } else {
            CoeService::SdoResponse
        };
        reply[MAILBOX_HEADER..MAILBOX_HEADER + 2].copy_from_slice(&service.header().to_le_bytes());
        reply[SDO_DATA - 3..SDO_DATA - 1].copy_from_slice(&index.to_le_bytes());
        reply[SDO_DATA - 1] = sub;
        (length, true)
    }

    fn upload(
        &self,
        index: u16,
        sub: u8,
        reply: &mut [u8; MAILBOX_SIZE],
    ) -> Result<usize, SdoAbort> {
        let live = Live {
            drive: self.drive,
            sync0_cycle_ns: self.sync0_cycle_ns,
        };
        let value = self.dictionary.read(index, sub, live)?;
        let n = value.len();
        if n <= 4 {
            // Expedited, size indicated: bits 2–3 count the unused bytes.
            reply[SDO_DATA - SDO_HEADER] = 0x43 | (((4 - n) as u8) << 2);
            value.write_to(&mut reply[SDO_DATA..SDO_DATA + 4]);
            Ok(SDO_DATA + 4)
        } else if SDO_DATA + 4 + n <= MAILBOX_SIZE {
            // Normal: the complete size, then the data in this mailbox.
            reply[SDO_DATA - SDO_HEADER] = 0x41;
            let size = u32::try_from(n).unwrap_or(u32::MAX);
            reply[SDO_DATA..SDO_DATA + 4].copy_from_slice(&size.to_le_bytes());
            value.write_to(&mut reply[SDO_DATA + 4..]);
            Ok(SDO_DATA + 4 + n)
        } else {
            Err(SdoAbort::TOO_LARGE)
        }
    }

    /// The SDO information service.
    fn information(&mut self, message: &[u8], reply: &mut [u8; MAILBOX_SIZE]) -> (usize, bool) {
        let Some(info) = message.get(MAILBOX_HEADER + 2..INFO_DATA) else {
            return mailbox_error(reply, 0x0003);
        };
        let data = &message[INFO_DATA..];
        reply[MAILBOX_HEADER..MAILBOX_HEADER + 2]
            .copy_from_slice(&CoeService::SdoInformation.header().to_le_bytes());
        let out = &mut reply[INFO_DATA..];
        let result = match info[0] & 0x7F {
            opcode::OD_LIST_REQUEST => od_list(data, out).map(|n| (opcode::OD_LIST_RESPONSE, n)),
            opcode::OBJECT_REQUEST => {
                object_description(data, out).map(|n| (opcode::OBJECT_RESPONSE, n))
            }
            opcode::ENTRY_REQUEST => self
                .entry_description(data, out)
                .map(|n| (opcode::ENTRY_RESPONSE, n)),
            _ => Err(SdoAbort::COMMAND),
        };
        let (op, n) = match result {
            Ok(done) => done,
            Err(abort) => {
                out[..4].copy_from_slice(&abort.0.to_le_bytes());
                (opcode::ERROR, 4)
            }
        };
        // One fragment: every answer fits one mailbox.
        reply[MAILBOX_HEADER + 2] = op;
        reply[MAILBOX_HEADER + 3] = 0;
        reply[MAILBOX_HEADER + 4..INFO_DATA].fill(0);
        (INFO_DATA + n, true)
    }

    fn entry_description(&self, data: &[u8], out: &mut [u8]) -> Result<usize, SdoAbort> {
        let request = data.get(..4).ok_or(SdoAbort::COMMAND)?;
        let index = u16::from_le_bytes([request[0], request[1]]);
        let sub = request[2];
        let object = object(index).ok_or(SdoAbort::NO_OBJECT)?;
        let entry = object
            .entries
            .get(usize::from(sub))
            .ok_or(SdoAbort::NO_SUB_INDEX)?;
        out[0..2].copy_from_slice(&index.to_le_bytes());
        out[2] = sub;
        // Value info: unit, default, minimum and maximum are not given.
        out[3] = request[3] & 0x07;
        out[4..6].copy_from_slice(&entry.data_type.to_le_bytes());
        out[6..8].copy_from_slice(&entry.bits.to_le_bytes());
        out[8..10].copy_from_slice(&self.dictionary.access(index, entry).to_le_bytes());
        Ok(10 + put_name(&mut out[10..], entry.name))
    }
}

/// The object list: list type 0 gives the counts per list, 1 all
/// objects, 2 and 3 those mappable into RxPDOs and TxPDOs, 4 and 5 (backup
/// and settings) none.
fn od_list(data: &[u8], out: &mut [u8]) -> Result<usize, SdoAbort> {
    let list = data
        .get(..2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
        .ok_or(SdoAbort::COMMAND)?;
    let mappable =
        |bit: u16| move |o: &&super::objects::Object| o.entries.iter().any(|e| e.access & bit != 0);
    out[0..2].copy_from_slice(&list.to_le_bytes());
    let indices: Vec<u16> = match list {
        0 => [
            OBJECTS.len(),
            OBJECTS.iter().filter(mappable(0x40)).count(),
            OBJECTS.iter().filter(mappable(0x80)).count(),
            0,
            0,
        ]
        .iter()
        .map(|&n| u16::try_from(n).unwrap_or(u16::MAX))
        .collect(),
        1 => OBJECTS.iter().map(|o| o.index).collect(),
        2 => OBJECTS
            .iter()
            .filter(mappable(0x40))
            .map(|o| o.index)
            .collect(),
        3 => OBJECTS
            .iter()
            .filter(mappable(0x80))
            .map(|o| o.index)
            .collect(),
        4 | 5 => Vec::new(),
        _ => return Err(SdoAbort::VALUE_RANGE),
    };
    let mut n = 2;
    for index in indices {
        let Some(slot) = out.get_mut(n..n + 2) else {
            return Err(SdoAbort::TOO_LARGE);
        };
        slot.copy_from_slice(&index.to_le_bytes());
        n += 2;
    }
    Ok(n)
}

fn object_description(data: &[u8], out: &mut [u8]) -> Result<usize, SdoAbort> {
    let index = data
        .get(..2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
        .ok_or(SdoAbort::COMMAND)?;
    let object = object(index).ok_or(SdoAbort::NO_OBJECT)?;
    out[0..2].copy_from_slice(&index.to_le_bytes());
    out[2..4].copy_from_slice(&object.data_type.to_le_bytes());
    out[4] = u8::try_from(object.entries.len() - 1).unwrap_or(0);
    out[5] = object.code as u8;
    Ok(6 + put_name(&mut out[6..], object.name))
}

fn put_name(out: &mut [u8], name: &str) -> usize {
    let n = name.len().min(out.len());
    out[..n].copy_from_slice(&name.as_bytes()[..n]);
    n
}

/// A mailbox error reply (ETG1000.4 table 30): type 1, then the detail.
fn mailbox_error(reply: &mut [u8; MAILBOX_SIZE], detail: u16) -> (usize, bool) {
    reply[MAILBOX_HEADER..MAILBOX_HEADER + 2].copy_from_slice(&1u16.to_le_bytes());
    reply[MAILBOX_HEADER + 2..MAILBOX_HEADER + 4].copy_from_slice(&detail.to_le_bytes());
    (MAILBOX_HEADER + 4, false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emulation::DriveBehaviour;

    fn request(coe: &[u8]) -> [u8; MAILBOX_SIZE] {
        let mut m = [0u8; MAILBOX_SIZE];
        MailboxHeader {
            length: u16::try_from(coe.len()).unwrap(),
            kind: MAILBOX_COE,
            counter: 1,
        }
        .write(&mut m);
        m[MAILBOX_HEADER..MAILBOX_HEADER + coe.len()].copy_from_slice(coe);
        m
    }

    fn ask(coe: &[u8]) -> [u8; MAILBOX_SIZE] {
        let mut dictionary = Dictionary::new(3, false);
        let mut drive = DriveModel::new(DriveBehaviour::default(), 0);
        let mut outbox = Outbox::new();
        Server {
            dictionary: &mut dictionary,
            drive: &mut drive,
            al: 2,
            sync0_cycle_ns: 0,
        }
        .answer(&request(coe), &mut outbox);
        let mut sm1 = [0u8; MAILBOX_SIZE];
        assert!(outbox.pop_into(&mut sm1));
        sm1
    }

    #[test]
    fn expedited_and_normal_uploads() {
        // Upload 0x1018:02 (product code): expedited, four bytes.
        let r = ask(&[0x00, 0x20, 0x40, 0x18, 0x10, 0x02, 0, 0, 0, 0]);
        assert_eq!(u16::from_le_bytes([r[0], r[1]]), 10);
        assert_eq!(r[5] & 0x0F, MAILBOX_COE);
        assert_eq!(r[7] >> 4, 3, "SDO response");
        assert_eq!(r[8], 0x43);
        assert_eq!(&r[12..16], &0x4543_414Du32.to_le_bytes());
        // 0x1008: a string, normal upload with its size.
        let r = ask(&[0x00, 0x20, 0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0]);
        assert_eq!(r[8], 0x41);
        let n = u32::from_le_bytes([r[12], r[13], r[14], r[15]]) as usize;
        assert_eq!(&r[16..16 + n], super::super::EMULATED_NAME.as_bytes());
        // An object that does not exist: abort 0x06020000.
        let r = ask(&[0x00, 0x20, 0x40, 0x00, 0x20, 0x00, 0, 0, 0, 0]);
        assert_eq!(r[8], 0x80);
        assert_eq!(&r[12..16], &0x0602_0000u32.to_le_bytes());
        // Complete access is refused.
        let r = ask(&[0x00, 0x20, 0x50, 0x00, 0x1C, 0x00, 0, 0, 0, 0]);
        assert_eq!(&r[12..16], &0x0601_0000u32.to_le_bytes());
    }

    #[test]
    fn expedited_download_and_the_information_service() {
        // 0x6065 = 1000 (four bytes, size indicated).
        let r = ask(&[0x00, 0x20, 0x23, 0x65, 0x60, 0x00, 0xE8, 0x03, 0, 0]);
        assert_eq!(r[8], 0x60, "download response");
        // One byte into a four-byte object: length does not match.
        let r = ask(&[0x00, 0x20, 0x2F, 0x65, 0x60, 0x00, 1, 0, 0, 0]);
        assert_eq!(&r[12..16], &0x0607_0010u32.to_le_bytes());
        // Object list, all objects.
        let r = ask(&[0x00, 0x80, 0x01, 0, 0, 0, 0x01, 0x00]);
        assert_eq!(r[8], 2);
        let len = usize::from(u16::from_le_bytes([r[0], r[1]]));
        assert_eq!((len - 8) / 2, OBJECTS.len());
        assert_eq!(u16::from_le_bytes([r[14], r[15]]), 0x1000);
        // Description of 0x1018 and of its entry 1.
        let r = ask(&[0x00, 0x80, 0x03, 0, 0, 0, 0x18, 0x10]);
        assert_eq!((r[8], r[16], r[17]), (4, 4, 9), "4 entries, a record");
        assert_eq!(&r[18..26], b"Identity");
        let r = ask(&[0x00, 0x80, 0x05, 0, 0, 0, 0x18, 0x10, 1, 7]);
        assert_eq!(r[8], 6);
        assert_eq!(u16::from_le_bytes([r[18], r[19]]), 32, "bits");
        assert_eq!(&r[22..31], b"Vendor ID");
        let r = ask(&[0x00, 0x80, 0x05, 0, 0, 0, 0x18, 0x10, 9, 7]);
        assert_eq!(r[8], 7, "info error");
        assert_eq!(&r[12..16], &0x0609_0011u32.to_le_bytes());
    }
}
