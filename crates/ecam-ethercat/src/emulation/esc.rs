//! One emulated EtherCAT slave controller (ESC): register memory, the
//! datagram commands, the AL state machine, the SII EEPROM interface,
//! the mailbox sync managers, FMMUs for process data and the
//! distributed-clock registers. Register addresses follow the ESC
//! datasheets' map (ETG1000.4 section 6).

use super::coe_server::Server;
use super::drive::{DriveBehaviour, DriveModel};
use super::mailbox::{MAILBOX_IN_START, MAILBOX_OUT_START, MAILBOX_SIZE, Outbox};
use super::objects::{Dictionary, Live};
use super::sii::{self, SM2_START, SM3_START};
use crate::coe::{Emergency, SdoAbort};
use crate::pdo::CspOutputs;

/// Size of the emulated ESC memory (registers and process RAM).
const MEMORY: usize = 0x2000;

const REG_TYPE: usize = 0x0000;
const REG_FMMU_COUNT: usize = 0x0004;
const REG_SM_COUNT: usize = 0x0005;
const REG_RAM_SIZE: usize = 0x0006;
const REG_SUPPORT: usize = 0x0008;
const REG_STATION_ADDRESS: usize = 0x0010;
const REG_DL_STATUS: usize = 0x0110;
const REG_AL_CONTROL: usize = 0x0120;
const REG_AL_STATUS: usize = 0x0130;
const REG_AL_STATUS_CODE: usize = 0x0134;
const REG_SII_CONTROL: usize = 0x0502;
const REG_SII_ADDRESS: usize = 0x0504;
const REG_SII_DATA: usize = 0x0508;
const REG_FMMU: usize = 0x0600;
const REG_SM: usize = 0x0800;
const REG_DC_PORT_TIMES: usize = 0x0900;
const REG_DC_SYSTEM_TIME: usize = 0x0910;
const REG_DC_RECEIVE_TIME: usize = 0x0918;
const REG_DC_OFFSET: usize = 0x0920;
const REG_DC_SYNC_ACTIVE: usize = 0x0981;
const REG_DC_SYNC0_CYCLE: usize = 0x09A0;

/// SII control: read size 8 bytes (bit 6).
const SII_READ_8: u16 = 1 << 6;
/// SII control: read command (bit 8).
const SII_READ: u16 = 1 << 8;
/// SII control: write command (bit 9).
const SII_WRITE: u16 = 1 << 9;
/// SII control: command error (bit 13).
const SII_COMMAND_ERROR: u16 = 1 << 13;

/// SM status: the mailbox is full (bit 3).
const SM_MAILBOX_FULL: u8 = 0x08;

/// AL status codes the emulated drive reports (ETG1000.6 table 11).
const AL_INVALID_STATE_CHANGE: u16 = 0x0011;
const AL_INVALID_MAILBOX_CONFIG: u16 = 0x0016;
const AL_INVALID_OUTPUT_CONFIG: u16 = 0x001D;
const AL_INVALID_INPUT_CONFIG: u16 = 0x001E;
const AL_INVALID_DC_SYNC: u16 = 0x0030;
const AL_SYNC_MANAGER_WATCHDOG: u16 = 0x001B;

/// The process-data watchdog an ESC starts with (ETG1000.4: divider 2498
/// of 25 MHz = 100 µs ticks, 1000 ticks).
pub(crate) const DEFAULT_WATCHDOG: std::time::Duration = std::time::Duration::from_millis(100);

/// Delay the emulation books for each ESC a frame passes, per direction.
const HOP_NS: u32 = 100;

/// The EtherCAT datagram commands (ETG1000.4 table 12).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Cmd {
    Nop,
    Aprd,
    Apwr,
    Aprw,
    Fprd,
    Fpwr,
    Fprw,
    Brd,
    Bwr,
    Brw,
    Lrd,
    Lwr,
    Lrw,
    Armw,
    Frmw,
}

impl Cmd {
    pub(crate) fn from_code(code: u8) -> Option<Self> {
        Some(match code {
            0 => Self::Nop,
            1 => Self::Aprd,
            2 => Self::Apwr,
            3 => Self::Aprw,
            4 => Self::Fprd,
            5 => Self::Fpwr,
            6 => Self::Fprw,
            7 => Self::Brd,
            8 => Self::Bwr,
            9 => Self::Brw,
            10 => Self::Lrd,
            11 => Self::Lwr,
            12 => Self::Lrw,
            13 => Self::Armw,
            14 => Self::Frmw,
            _ => return None,
        })
    }
}

/// Where a datagram finds one ESC on its way.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hop {
    /// Position of this ESC in the line (0 = next to the master).
    pub(crate) position: usize,
    /// ESCs that answer (the line may be cut).
    pub(crate) reachable: usize,
    /// Local clock of this ESC when the frame arrived, ns.
    pub(crate) now_ns: u64,
    /// The process-data watchdog, ns (`None`: off).
    pub(crate) watchdog_ns: Option<u64>,
}

/// One emulated ESC with a CSP drive behind it.
#[derive(Clone, Debug)]
pub struct Esc {
    memory: Vec<u8>,
    eeprom: Vec<u8>,
    drive: DriveModel,
    /// When outputs last arrived in OP (`None`: not since entering OP).
    last_outputs_ns: Option<u64>,
    dictionary: Dictionary,
    /// Messages waiting for SM1.
    outbox: Outbox,
}

impl Esc {
    /// A powered-up ESC in INIT with drive `serial` behind it.
    pub fn new(serial: u32, behaviour: DriveBehaviour) -> Self {
        let mut memory = vec![0u8; MEMORY];
        memory[REG_TYPE] = 0x11; // an ET1100-class ESC
        memory[REG_FMMU_COUNT] = 8;
        memory[REG_SM_COUNT] = 8;
        memory[REG_RAM_SIZE] = 8;
        // DC supported, 64-bit system time, enhanced DC sync activation.
        put(&mut memory, REG_SUPPORT, &0x010Cu16.to_le_bytes());
        put(&mut memory, REG_AL_STATUS, &1u16.to_le_bytes());
        put(&mut memory, REG_SII_CONTROL, &SII_READ_8.to_le_bytes());
        Self {
            memory,
            eeprom: sii::drive_eeprom(serial, behaviour.fixed_mapping),
            drive: DriveModel::new(behaviour, 0),
            last_outputs_ns: None,
            dictionary: Dictionary::new(serial, behaviour.fixed_mapping),
            outbox: Outbox::new(),
        }
    }

    /// Reads an object of the drive's dictionary as an SDO upload would
    /// (to check what a master configured).
    ///
    /// # Errors
    /// The abort the drive would answer.
    pub fn sdo_read(&self, index: u16, sub_index: u8) -> Result<Vec<u8>, SdoAbort> {
        let value = self.dictionary.read(index, sub_index, self.live())?;
        let mut out = vec![0; value.len()];
        value.write_to(&mut out);
        Ok(out)
    }

    fn live(&self) -> Live<'_> {
        Live {
            drive: &self.drive,
            sync0_cycle_ns: self.sync0_cycle_ns(),
        }
    }

    /// The process-data watchdog ran out (no outputs for its time in OP):
    /// the ESC falls back to SAFE-OP with the error flag and AL status code
    /// 0x001B, and a drive with its power stage on faults.
    pub fn watchdog_expired(&mut self) {
        if self.al_state() == 8 {
            put(&mut self.memory, REG_AL_STATUS, &0x0014u16.to_le_bytes());
            put(
                &mut self.memory,
                REG_AL_STATUS_CODE,
                &AL_SYNC_MANAGER_WATCHDOG.to_le_bytes(),
            );
            self.last_outputs_ns = None;
            self.drive.communication_lost();
            self.post_emergencies();
            self.publish_inputs();
        }
    }

    /// The drive behind this ESC.
    pub fn drive(&self) -> &DriveModel {
        &self.drive
    }

    /// The drive behind this ESC, to inject faults.
    pub fn drive_mut(&mut self) -> &mut DriveModel {
        &mut self.drive
    }

    /// AL state (1 INIT, 2 PRE-OP, 4 SAFE-OP, 8 OP).
    pub fn al_state(&self) -> u8 {
        self.memory[REG_AL_STATUS] & 0x0F
    }

    /// SYNC0 cycle time the master programmed, ns (0 = none).
    pub fn sync0_cycle_ns(&self) -> u32 {
        u32::from_le_bytes(word4(&self.memory, REG_DC_SYNC0_CYCLE))
    }

    /// SYNC0 is active (cyclic operation and SYNC0 enabled).
    pub fn sync0_active(&self) -> bool {
        self.memory[REG_DC_SYNC_ACTIVE] & 0x03 == 0x03
    }

    fn station_address(&self) -> u16 {
        u16::from_le_bytes([
            self.memory[REG_STATION_ADDRESS],
            self.memory[REG_STATION_ADDRESS + 1],
        ])
    }

    /// Sets the link bits of DL status for a line: port 0 towards the
    /// master, port 1 open when another ESC follows.
    pub(crate) fn set_links(&mut self, has_next: bool) {
        // Bit 4..7 physical link on port 0..3; 9/11 communication on 0/1;
        // bit 10 loop closed on port 1 when nothing follows.
        let mut dl: u16 = (1 << 4) | (1 << 9);
        if has_next {
            dl |= (1 << 5) | (1 << 11);
        } else {
            dl |= 1 << 10;
        }
        put(&mut self.memory, REG_DL_STATUS, &dl.to_le_bytes());
    }

    /// Processes one datagram passing this ESC. `adp` is the address
    /// field as it arrives (auto-increment ESCs add one to it).
    pub(crate) fn datagram(
        &mut self,
        cmd: Cmd,
        adp: &mut u16,
        ado: u16,
        data: &mut [u8],
        wkc: &mut u16,
        hop: Hop,
    ) {
        let logical = u32::from(ado) << 16 | u32::from(*adp);
        if let (Some(last), Some(limit)) = (self.last_outputs_ns, hop.watchdog_ns) {
            if hop.now_ns.saturating_sub(last) > limit {
                self.watchdog_expired();
            }
        }
        match cmd {
            Cmd::Nop => {}
            Cmd::Aprd | Cmd::Apwr | Cmd::Aprw | Cmd::Armw => {
                let addressed = *adp == 0;
                *adp = adp.wrapping_add(1);
                if cmd == Cmd::Armw {
                    self.read_multiple_write(addressed, ado, data, wkc, hop);
                } else if addressed {
                    self.physical(cmd, ado, data, wkc, hop);
                }
            }
            Cmd::Fprd | Cmd::Fpwr | Cmd::Fprw | Cmd::Frmw => {
                let addressed = *adp == self.station_address();
                if cmd == Cmd::Frmw {
                    self.read_multiple_write(addressed, ado, data, wkc, hop);
                } else if addressed {
                    self.physical(cmd, ado, data, wkc, hop);
                }
            }
            Cmd::Brd | Cmd::Bwr | Cmd::Brw => {
                *adp = adp.wrapping_add(1);
                self.physical(cmd, ado, data, wkc, hop);
            }
            Cmd::Lrd | Cmd::Lwr | Cmd::Lrw => self.logical(cmd, logical, data, wkc, hop.now_ns),
        }
    }

    fn read_multiple_write(
        &mut self,
        addressed: bool,
        ado: u16,
        data: &mut [u8],
        wkc: &mut u16,
        hop: Hop,
    ) {
        if addressed {
            self.physical(Cmd::Fprd, ado, data, wkc, hop);
        } else {
            self.physical(Cmd::Fpwr, ado, data, wkc, hop);
        }
    }

    fn physical(&mut self, cmd: Cmd, ado: u16, data: &mut [u8], wkc: &mut u16, hop: Hop) {
        let start = usize::from(ado);
        let Some(end) = start.checked_add(data.len()).filter(|&end| end <= MEMORY) else {
            return;
        };
        let (read, write) = match cmd {
            Cmd::Aprd | Cmd::Fprd | Cmd::Brd => (true, false),
            Cmd::Apwr | Cmd::Fpwr | Cmd::Bwr => (false, true),
            _ => (true, true),
        };
        // The read mailbox (SM1) answers only while it holds a message;
        // a read that reaches its last byte empties it.
        let mailbox_in = self.mailbox_area(1).filter(|&(s, e)| start < e && s < end);
        if read && mailbox_in.is_some() && !self.sm1_full() {
            return;
        }
        if read {
            self.refresh_clock(hop.now_ns);
            if cmd == Cmd::Brd {
                // A broadcast read returns the OR of every ESC's memory.
                for (d, m) in data.iter_mut().zip(&self.memory[start..end]) {
                    *d |= m;
                }
            } else if !write {
                data.copy_from_slice(&self.memory[start..end]);
            }
            *wkc = wkc.wrapping_add(1);
            if let Some((_, area_end)) = mailbox_in {
                if end >= area_end {
                    self.set_sm1_full(false);
                    self.refill_mailbox();
                }
            }
        }
        if write {
            for (offset, byte) in data.iter_mut().enumerate() {
                let address = start + offset;
                let old = self.memory[address];
                if writable(address) {
                    self.memory[address] = *byte;
                }
                if read {
                    // Read-write commands return the memory as it was.
                    *byte = old;
                }
            }
            self.after_write(start, end, hop);
            *wkc = wkc.wrapping_add(if read { 2 } else { 1 });
        }
    }

    /// Process data through the FMMUs: inputs are copied out, outputs in,
    /// then the drive runs one cycle on the new outputs.
    fn logical(&mut self, cmd: Cmd, logical: u32, data: &mut [u8], wkc: &mut u16, now_ns: u64) {
        let al = self.al_state();
        if al != 4 && al != 8 {
            return;
        }
        let mut read_hit = false;
        let mut write_hit = false;
        let mut outputs_complete = false;
        let datagram_len = u32::try_from(data.len()).unwrap_or(u32::MAX);
        for index in 0..8 {
            let base = REG_FMMU + index * 16;
            let mut f = [0u8; 16];
            f.copy_from_slice(&self.memory[base..base + 16]);
            if f[12] & 1 == 0 {
                continue;
            }
            let log_start = u32::from_le_bytes([f[0], f[1], f[2], f[3]]);
            let len = u32::from(u16::from_le_bytes([f[4], f[5]]));
            let phys = usize::from(u16::from_le_bytes([f[8], f[9]]));
            let (fmmu_read, fmmu_write) = (f[11] & 1 != 0, f[11] & 2 != 0);
            // Overlap of [log_start, log_start+len) with the datagram.
            let lo = log_start.max(logical);
            let hi = log_start
                .saturating_add(len)
                .min(logical.saturating_add(datagram_len));
            if lo >= hi {
                continue;
            }
            let n = usize::try_from(hi - lo).unwrap_or(0);
            let in_data = usize::try_from(lo - logical).unwrap_or(0);
            let in_mem = phys + usize::try_from(lo - log_start).unwrap_or(0);
            if in_mem + n > MEMORY {
                continue;
            }
            if fmmu_read && matches!(cmd, Cmd::Lrd | Cmd::Lrw) {
                data[in_data..in_data + n].copy_from_slice(&self.memory[in_mem..in_mem + n]);
                read_hit = true;
            }
            if fmmu_write && matches!(cmd, Cmd::Lwr | Cmd::Lrw) {
                self.memory[in_mem..in_mem + n].copy_from_slice(&data[in_data..in_data + n]);
                write_hit = true;
                // A buffered sync manager hands the outputs over when its
                // last byte is written (the master may split them over
                // two frames).
                let outputs = self.dictionary.rx.bytes().max(1);
                let last = usize::from(SM2_START) + outputs - 1;
                outputs_complete |= (in_mem..in_mem + n).contains(&last);
            }
        }
        if read_hit {
            *wkc = wkc.wrapping_add(1);
        }
        if write_hit {
            *wkc = wkc.wrapping_add(if cmd == Cmd::Lrw { 2 } else { 1 });
        }
        // The drive's application takes new outputs only in OP
        // (SAFE-OP: inputs valid, outputs ignored), once per cycle.
        if outputs_complete && al == 8 {
            self.last_outputs_ns = Some(now_ns);
            self.run_drive();
        } else if read_hit {
            self.publish_inputs();
        }
    }

    /// Takes the outputs the RxPDO mapping carries (objects it does not
    /// map keep their last value) and runs the drive one cycle.
    fn run_drive(&mut self) {
        let mut outputs = CspOutputs {
            controlword: self.drive.controlword(),
            target_position: self.drive.target(),
            mode: self.drive.requested_mode(),
        };
        let mut at = usize::from(SM2_START);
        let mapping = self.dictionary.rx;
        for &m in mapping.active() {
            let n = (m & 0xFF) as usize / 8;
            let mut raw = [0u8; 4];
            raw[..n.min(4)].copy_from_slice(&self.memory[at..at + n.min(4)]);
            let v = u32::from_le_bytes(raw);
            match m >> 16 {
                0x6040 => outputs.controlword = v as u16,
                0x607A => outputs.target_position = v as i32,
                0x6060 => outputs.mode = v as u8 as i8,
                _ => {}
            }
            at += n;
        }
        self.drive.cycle(outputs);
        self.post_emergencies();
        self.publish_inputs();
    }

    /// Writes the objects the TxPDO mapping carries, in its order.
    fn publish_inputs(&mut self) {
        let mut at = usize::from(SM3_START);
        let mapping = self.dictionary.tx;
        let live = Live {
            drive: &self.drive,
            sync0_cycle_ns: 0,
        };
        for &m in mapping.active() {
            let n = (m & 0xFF) as usize / 8;
            if let Ok(value) = self.dictionary.read((m >> 16) as u16, (m >> 8) as u8, live) {
                value.write_to(&mut self.memory[at..at + n]);
            }
            at += n;
        }
    }

    /// Queues an emergency for each error the drive reported (and for
    /// each reset), while the mailbox runs.
    fn post_emergencies(&mut self) {
        while let Some(code) = self.drive.take_emergency() {
            if self.mailbox_area(1).is_some() && self.al_state() >= 2 {
                if let Some(slot) = self.outbox.push() {
                    Emergency::for_code(code).write_mailbox(slot);
                }
            }
        }
        self.refill_mailbox();
    }

    /// Where mailbox `sm` (0: from the master, 1: to it) lies, while its
    /// sync manager is enabled in mailbox mode.
    fn mailbox_area(&self, sm: usize) -> Option<(usize, usize)> {
        let base = REG_SM + sm * 8;
        let start = usize::from(u16::from_le_bytes([
            self.memory[base],
            self.memory[base + 1],
        ]));
        let len = usize::from(u16::from_le_bytes([
            self.memory[base + 2],
            self.memory[base + 3],
        ]));
        let mailbox_mode = self.memory[base + 4] & 0x03 == 0x02;
        let enabled = self.memory[base + 6] & 1 != 0;
        (mailbox_mode && enabled && len > 0 && start + len <= MEMORY)
            .then_some((start, start + len))
    }

    fn sm1_full(&self) -> bool {
        self.memory[REG_SM + 8 + 5] & SM_MAILBOX_FULL != 0
    }

    fn set_sm1_full(&mut self, full: bool) {
        let status = &mut self.memory[REG_SM + 8 + 5];
        if full {
            *status |= SM_MAILBOX_FULL;
        } else {
            *status &= !SM_MAILBOX_FULL;
        }
    }

    /// Moves the next waiting message into SM1 when it is empty.
    fn refill_mailbox(&mut self) {
        let Some((start, end)) = self.mailbox_area(1) else {
            return;
        };
        if !self.sm1_full() && self.outbox.pop_into(&mut self.memory[start..end]) {
            self.set_sm1_full(true);
        }
    }

    /// The master wrote the last byte of SM0: the drive answers the
    /// request (in PRE-OP, SAFE-OP and OP).
    fn mailbox_request(&mut self) {
        let Some((start, end)) = self.mailbox_area(0) else {
            return;
        };
        let al = self.al_state();
        if !matches!(al, 2 | 4 | 8) {
            return;
        }
        let mut request = [0u8; MAILBOX_SIZE];
        let n = (end - start).min(MAILBOX_SIZE);
        request[..n].copy_from_slice(&self.memory[start..start + n]);
        let sync0_cycle_ns = self.sync0_cycle_ns();
        Server {
            dictionary: &mut self.dictionary,
            drive: &mut self.drive,
            al,
            sync0_cycle_ns,
        }
        .answer(&request[..n], &mut self.outbox);
        self.post_emergencies();
    }

    /// Drops the mailbox's content (INIT, or SM1 switched off).
    fn reset_mailbox(&mut self) {
        self.outbox.clear();
        self.set_sm1_full(false);
    }

    fn refresh_clock(&mut self, now_ns: u64) {
        let offset = u64::from_le_bytes(word8(&self.memory, REG_DC_OFFSET));
        put(
            &mut self.memory,
            REG_DC_SYSTEM_TIME,
            &now_ns.wrapping_add(offset).to_le_bytes(),
        );
    }

    fn after_write(&mut self, start: usize, end: usize, hop: Hop) {
        let touches = |register: usize, len: usize| start < register + len && register < end;
        if touches(REG_AL_CONTROL, 2) {
            self.al_control();
        }
        if touches(REG_SM + 8, 8) && self.mailbox_area(1).is_none() {
            self.reset_mailbox();
        }
        if let Some((_, area_end)) = self.mailbox_area(0) {
            if start < area_end && area_end <= end {
                self.mailbox_request();
            }
        }
        if touches(REG_SII_CONTROL, 2) {
            self.sii_command();
        }
        if touches(REG_DC_PORT_TIMES, 1) {
            self.latch_receive_times(hop);
        }
    }

    fn latch_receive_times(&mut self, hop: Hop) {
        // Time at port 0 on the way out; port 1 on the way back from the
        // rest of the line (two hops per ESC behind this one).
        let position = u32::try_from(hop.position).unwrap_or(u32::MAX);
        let behind = u32::try_from(hop.reachable.saturating_sub(hop.position + 1)).unwrap_or(0);
        let local = hop
            .now_ns
            .wrapping_add(u64::from(position.saturating_mul(HOP_NS)));
        let port0 = local as u32;
        let port1 = if behind > 0 {
            port0.wrapping_add(2 * behind * HOP_NS)
        } else {
            0
        };
        put(&mut self.memory, REG_DC_PORT_TIMES, &port0.to_le_bytes());
        put(
            &mut self.memory,
            REG_DC_PORT_TIMES + 4,
            &port1.to_le_bytes(),
        );
        put(&mut self.memory, REG_DC_PORT_TIMES + 8, &0u32.to_le_bytes());
        put(
            &mut self.memory,
            REG_DC_PORT_TIMES + 12,
            &0u32.to_le_bytes(),
        );
        put(&mut self.memory, REG_DC_RECEIVE_TIME, &local.to_le_bytes());
    }

    fn sii_command(&mut self) {
        let control = u16::from_le_bytes([
            self.memory[REG_SII_CONTROL],
            self.memory[REG_SII_CONTROL + 1],
        ]);
        let status = if control & SII_READ != 0 {
            let word = u32::from_le_bytes(word4(&self.memory, REG_SII_ADDRESS));
            let at = usize::try_from(word)
                .unwrap_or(usize::MAX)
                .saturating_mul(2);
            for i in 0..8 {
                self.memory[REG_SII_DATA + i] = self
                    .eeprom
                    .get(at.saturating_add(i))
                    .copied()
                    .unwrap_or(0xFF);
            }
            SII_READ_8
        } else if control & SII_WRITE != 0 {
            // The emulated EEPROM is read-only.
            SII_READ_8 | SII_COMMAND_ERROR
        } else {
            // Error reset or ownership: keep only the read size.
            SII_READ_8
        };
        put(&mut self.memory, REG_SII_CONTROL, &status.to_le_bytes());
    }

    fn al_control(&mut self) {
        let requested = self.memory[REG_AL_CONTROL] & 0x0F;
        let current = self.al_state();
        let result = match (current, requested) {
            (_, 1) => Ok(1u8),
            (1, 2) => self.check_mailbox().map(|()| 2),
            (2, 2) | (4 | 8, 2) => Ok(2),
            (2 | 4 | 8, 4) => self.check_process_data().map(|()| 4),
            (4 | 8, 8) => self.check_dc().map(|()| 8),
            _ => Err(AL_INVALID_STATE_CHANGE),
        };
        let (status, code) = match result {
            Ok(state) => (u16::from(state), 0),
            Err(code) => (u16::from(current) | 0x10, code),
        };
        put(&mut self.memory, REG_AL_STATUS, &status.to_le_bytes());
        put(&mut self.memory, REG_AL_STATUS_CODE, &code.to_le_bytes());
        if status & 0x0F != 8 {
            // The watchdog starts again with the first outputs in OP.
            self.last_outputs_ns = None;
        }
        if status & 0x0F == 1 {
            self.reset_mailbox();
        }
        if status & 0x0F == 4 {
            self.publish_inputs();
        }
    }

    /// PRE-OP needs SM0/SM1 set up as the SII's mailboxes.
    fn check_mailbox(&self) -> Result<(), u16> {
        let expected = [(MAILBOX_OUT_START, 0x06u8), (MAILBOX_IN_START, 0x02u8)];
        for (sm, (start, mode)) in expected.into_iter().enumerate() {
            let base = REG_SM + sm * 8;
            let area = self.mailbox_area(sm);
            let control = self.memory[base + 4] & 0x0F;
            if area != Some((usize::from(start), usize::from(start) + MAILBOX_SIZE))
                || control != mode
            {
                return Err(AL_INVALID_MAILBOX_CONFIG);
            }
        }
        Ok(())
    }

    /// SAFE-OP needs SM2/SM3 configured for the mapped process data.
    fn check_process_data(&self) -> Result<(), u16> {
        let sm = |n: usize| {
            let base = REG_SM + n * 8;
            let start = u16::from_le_bytes([self.memory[base], self.memory[base + 1]]);
            let len = usize::from(u16::from_le_bytes([
                self.memory[base + 2],
                self.memory[base + 3],
            ]));
            let enabled = self.memory[base + 6] & 1 != 0;
            (start, len, enabled)
        };
        let outputs = self
            .dictionary
            .rx_mapping()
            .iter()
            .map(|&m| (m & 0xFF) as usize)
            .sum::<usize>()
            / 8;
        let inputs = self
            .dictionary
            .tx_mapping()
            .iter()
            .map(|&m| (m & 0xFF) as usize)
            .sum::<usize>()
            / 8;
        if sm(2) != (SM2_START, outputs, outputs > 0) {
            return Err(AL_INVALID_OUTPUT_CONFIG);
        }
        if sm(3) != (SM3_START, inputs, inputs > 0) {
            return Err(AL_INVALID_INPUT_CONFIG);
        }
        Ok(())
    }

    /// OP needs SYNC0 running (the drive is DC-synchronous only).
    fn check_dc(&self) -> Result<(), u16> {
        if self.sync0_active() && self.sync0_cycle_ns() > 0 {
            Ok(())
        } else {
            Err(AL_INVALID_DC_SYNC)
        }
    }
}

/// Registers the master cannot write (identity, status, the sync
/// managers' status bytes, latched times).
fn writable(address: usize) -> bool {
    let sm_status = (REG_SM..REG_SM + 8 * 8).contains(&address) && (address - REG_SM) % 8 == 5;
    !sm_status
        && !matches!(address,
            0x0000..=0x000F
            | 0x0110..=0x0111
            | 0x0130..=0x0135
            | 0x0900..=0x091F
            | 0x092C..=0x092F)
}

fn put(memory: &mut [u8], at: usize, bytes: &[u8]) {
    memory[at..at + bytes.len()].copy_from_slice(bytes);
}

fn word4(memory: &[u8], at: usize) -> [u8; 4] {
    [memory[at], memory[at + 1], memory[at + 2], memory[at + 3]]
}

fn word8(memory: &[u8], at: usize) -> [u8; 8] {
    let mut out = [0u8; 8];
    out.copy_from_slice(&memory[at..at + 8]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const HOP: Hop = Hop {
        position: 0,
        reachable: 1,
        now_ns: 1_000,
        watchdog_ns: None,
    };

    fn write(esc: &mut Esc, register: u16, bytes: &[u8]) -> u16 {
        let mut data = bytes.to_vec();
        let mut wkc = 0;
        let mut adp = 0;
        esc.datagram(Cmd::Apwr, &mut adp, register, &mut data, &mut wkc, HOP);
        wkc
    }

    fn read(esc: &mut Esc, register: u16, len: usize) -> Vec<u8> {
        let mut data = vec![0; len];
        let mut wkc = 0;
        let mut adp = 0;
        esc.datagram(Cmd::Aprd, &mut adp, register, &mut data, &mut wkc, HOP);
        assert_eq!(wkc, 1);
        assert_eq!(adp, 1, "auto-increment address counts up");
        data
    }

    #[test]
    fn al_state_machine_refuses_what_a_drive_refuses() {
        let mut esc = Esc::new(1, DriveBehaviour::default());
        assert_eq!(write(&mut esc, 0x0120, &[8, 0]), 1);
        assert_eq!(
            read(&mut esc, 0x0130, 2),
            vec![0x11, 0],
            "INIT → OP refused, error flag"
        );
        assert_eq!(read(&mut esc, 0x0134, 2), vec![0x11, 0]);
        write(&mut esc, 0x0120, &[2, 0]);
        assert_eq!(read(&mut esc, 0x0134, 2), vec![0x16, 0], "no mailbox");
        mailboxes(&mut esc);
        write(&mut esc, 0x0120, &[2, 0]);
        assert_eq!(esc.al_state(), 2);
        write(&mut esc, 0x0120, &[4, 0]);
        assert_eq!(
            read(&mut esc, 0x0134, 2),
            vec![0x1D, 0],
            "no output sync manager"
        );
        // SM2 at 0x1100, 7 bytes, enabled; SM3 at 0x1180, 12 bytes.
        write(&mut esc, 0x0810, &[0x00, 0x11, 7, 0, 0x64, 0, 1, 0]);
        write(&mut esc, 0x0818, &[0x80, 0x11, 12, 0, 0x20, 0, 1, 0]);
        write(&mut esc, 0x0120, &[4, 0]);
        assert_eq!(esc.al_state(), 4);
        write(&mut esc, 0x0120, &[8, 0]);
        assert_eq!(read(&mut esc, 0x0134, 2), vec![0x30, 0], "OP needs SYNC0");
        write(&mut esc, 0x09A0, &1_000_000u32.to_le_bytes());
        write(&mut esc, 0x0981, &[3]);
        write(&mut esc, 0x0120, &[8, 0]);
        assert_eq!(esc.al_state(), 8);
    }

    /// SM0 at 0x1000 and SM1 at 0x1080, 128 bytes each, enabled.
    fn mailboxes(esc: &mut Esc) {
        write(esc, 0x0800, &[0x00, 0x10, 128, 0, 0x26, 0, 1, 0]);
        write(esc, 0x0808, &[0x80, 0x10, 128, 0, 0x22, 0, 1, 0]);
    }

    /// Sends a CoE message through SM0 and reads SM1 once it is full.
    fn coe(esc: &mut Esc, body: &[u8]) -> Vec<u8> {
        let mut request = vec![0u8; 128];
        request[0] = u8::try_from(body.len()).unwrap();
        request[5] = 0x13; // CoE, counter 1
        request[6..6 + body.len()].copy_from_slice(body);
        write(esc, 0x1000, &request);
        assert_eq!(read(esc, 0x080D, 1)[0] & 0x08, 0x08, "SM1 full");
        let reply = read(esc, 0x1080, 128);
        assert_eq!(read(esc, 0x080D, 1)[0] & 0x08, 0, "read empties SM1");
        reply
    }

    #[test]
    fn sdo_through_the_mailbox_and_an_emergency_on_a_fault() {
        let mut esc = Esc::new(5, DriveBehaviour::default());
        mailboxes(&mut esc);
        write(&mut esc, 0x0120, &[2, 0]);
        assert_eq!(esc.al_state(), 2);
        // Upload 0x1018:04, the serial number.
        let reply = coe(&mut esc, &[0x00, 0x20, 0x40, 0x18, 0x10, 0x04, 0, 0, 0, 0]);
        assert_eq!(reply[8], 0x43);
        assert_eq!(&reply[12..16], &5u32.to_le_bytes());
        // SM1 empty: a read is refused (no working counter).
        let mut data = vec![0; 128];
        let (mut wkc, mut adp) = (0, 0);
        esc.datagram(Cmd::Aprd, &mut adp, 0x1080, &mut data, &mut wkc, HOP);
        assert_eq!(wkc, 0);
        // A fault posts an emergency unasked.
        esc.drive_mut().inject_fault(0x2310);
        esc.run_drive();
        assert_eq!(read(&mut esc, 0x080D, 1)[0] & 0x08, 0x08);
        let message = read(&mut esc, 0x1080, 128);
        let emergency = Emergency::from_mailbox(&message).unwrap();
        assert_eq!(emergency.code, 0x2310);
        // INIT drops what waits.
        esc.drive_mut().inject_fault(0x3210);
        esc.run_drive();
        write(&mut esc, 0x0120, &[1, 0]);
        assert_eq!(read(&mut esc, 0x080D, 1)[0] & 0x08, 0);
    }

    #[test]
    fn sii_reads_eight_bytes_and_identity_registers_are_read_only() {
        let mut esc = Esc::new(7, DriveBehaviour::default());
        // Read word 0x0E: the serial number.
        write(&mut esc, 0x0502, &[0x00, 0x01, 0x0E, 0x00, 0, 0]);
        let control = read(&mut esc, 0x0502, 2);
        assert_eq!(
            u16::from_le_bytes([control[0], control[1]]) & 0x8000,
            0,
            "not busy"
        );
        assert_eq!(read(&mut esc, 0x0508, 4), 7u32.to_le_bytes().to_vec());
        write(&mut esc, 0x0000, &[0xFF]);
        assert_eq!(read(&mut esc, 0x0000, 1), vec![0x11]);
    }

    #[test]
    fn read_write_commands_count_three() {
        let mut esc = Esc::new(1, DriveBehaviour::default());
        let mut data = vec![0x34, 0x12];
        let (mut wkc, mut adp) = (0, 0);
        esc.datagram(Cmd::Aprw, &mut adp, 0x0010, &mut data, &mut wkc, HOP);
        assert_eq!(wkc, 3);
        assert_eq!(data, vec![0, 0], "returns the old value");
        assert_eq!(read(&mut esc, 0x0010, 2), vec![0x34, 0x12]);
    }
}
