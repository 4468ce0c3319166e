//! An emulated EtherCAT segment of CiA 402 CSP drives, for tests and for
//! trying ecam without hardware.
//!
//! [`EmulatedSegment::process_frame`] takes an Ethernet frame as the master
//! sent it and returns it as it would come back from a line of ESCs: each
//! ESC in turn executes every datagram (register reads and writes, the AL
//! state machine, SII EEPROM reads, DC latches, process data through its
//! FMMUs) and counts the working counter. What is emulated, and what is
//! not, is listed in docs/ethercat.md.

mod coe_server;
mod drive;
mod esc;
mod mailbox;
mod objects;
mod sii;
mod wire;

pub use drive::{DriveBehaviour, DriveModel, ERROR_FOLLOWING, ERROR_WATCHDOG};
pub use esc::Esc;
pub use mailbox::MAILBOX_SIZE;
pub use sii::{EMULATED_NAME, EMULATED_PRODUCT_CODE, EMULATED_VENDOR_ID};
pub use wire::WireEmulation;

use esc::{Cmd, Hop};
use std::time::{Duration, Instant};

/// EtherType of EtherCAT frames.
const ETHERCAT_ETHERTYPE: u16 = 0x88A4;
const ETHERNET_HEADER: usize = 14;
const DATAGRAM_HEADER: usize = 10;

/// What becomes of a frame sent to the segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reply {
    /// Nothing comes back (no ESC reachable, not EtherCAT, or the wire
    /// lost it).
    None,
    /// The processed frame comes back after this long (zero: at once).
    After(Duration),
}

/// What the emulated wire does to replies, so tests can lose and delay
/// them on purpose (the real-interface tests use `tc netem` instead).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Impairment {
    /// Every `drop_every`-th reply is lost (0: none).
    pub drop_every: u32,
    /// The next `hold_count` replies come back `hold` late.
    pub hold_count: u32,
    /// How late a held reply comes back.
    pub hold: Duration,
}

/// A line of emulated drives.
#[derive(Debug)]
pub struct EmulatedSegment {
    escs: Vec<Esc>,
    behaviour: DriveBehaviour,
    reachable: usize,
    started: Instant,
    frames: u64,
    impairment: Impairment,
    watchdog: Option<Duration>,
}

impl EmulatedSegment {
    /// `drives` drives in a line, all behaving as `behaviour`.
    pub fn new(drives: usize, behaviour: DriveBehaviour) -> Self {
        let mut escs: Vec<Esc> = (0..drives)
            .map(|i| Esc::new(u32::try_from(i + 1).unwrap_or(u32::MAX), behaviour))
            .collect();
        for (i, esc) in escs.iter_mut().enumerate() {
            esc.set_links(i + 1 < drives);
        }
        Self {
            escs,
            behaviour,
            reachable: drives,
            started: Instant::now(),
            frames: 0,
            impairment: Impairment::default(),
            watchdog: Some(esc::DEFAULT_WATCHDOG),
        }
    }

    /// Sets the ESCs' process-data watchdog (`None`: off). It starts at
    /// the ESC's default, 100 ms; tests that cycle without a real-time
    /// clock switch it off, since a loaded host may pause them longer.
    pub fn set_watchdog(&mut self, watchdog: Option<Duration>) {
        self.watchdog = watchdog;
    }

    /// Sets what the wire does to the replies from now on.
    pub fn impair(&mut self, impairment: Impairment) {
        self.impairment = impairment;
    }

    /// Power-cycles every drive: each ESC is back in INIT with its
    /// configuration lost, each drive not ready to switch on, holding
    /// where it stood (as after a drive's restart or a power dip).
    pub fn restart(&mut self) {
        let drives = self.escs.len();
        for (i, esc) in self.escs.iter_mut().enumerate() {
            let position = esc.drive().actual();
            *esc = Esc::new(u32::try_from(i + 1).unwrap_or(u32::MAX), self.behaviour);
            esc.drive_mut().place(position);
            esc.set_links(i + 1 < self.reachable.min(drives));
        }
    }

    /// The ESCs in line order.
    pub fn escs(&self) -> &[Esc] {
        &self.escs
    }

    /// One ESC, to inject a fault into its drive.
    pub fn esc_mut(&mut self, position: usize) -> Option<&mut Esc> {
        self.escs.get_mut(position)
    }

    /// Pulls the cable in front of ESC `position`: that ESC and all behind
    /// it stop answering (the ESC before it closes its port, so frames
    /// still come back). `0` leaves the master with no reply at all.
    pub fn cut_cable_before(&mut self, position: usize) {
        self.reachable = position.min(self.escs.len());
        for (i, esc) in self.escs.iter_mut().enumerate() {
            esc.set_links(i + 1 < self.reachable);
        }
    }

    /// Plugs the cable back in.
    pub fn reconnect(&mut self) {
        self.cut_cable_before(self.escs.len());
    }

    /// Frames processed so far.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// Runs one Ethernet frame through the line. `None` when nothing
    /// answers (not an EtherCAT frame, malformed, no ESC reachable, or
    /// the wire lost the reply); a held reply is returned at once.
    pub fn process_frame(&mut self, frame: &[u8]) -> Option<Vec<u8>> {
        let mut out = frame.to_vec();
        match self.process_in_place(&mut out) {
            Reply::After(_) => Some(out),
            Reply::None => None,
        }
    }

    /// Runs one Ethernet frame through the line in place (no allocation:
    /// the cycle's no-allocation test runs the emulation on its thread).
    pub fn process_in_place(&mut self, out: &mut [u8]) -> Reply {
        let Some(end) = self.check_frame(out) else {
            return Reply::None;
        };
        let start = ETHERNET_HEADER + 2;
        let now_ns = u64::try_from(self.started.elapsed().as_nanos())
            .unwrap_or(u64::MAX)
            .saturating_add(1_000_000_000);
        let reachable = self.reachable;
        for (position, esc) in self.escs.iter_mut().take(reachable).enumerate() {
            let hop = Hop {
                position,
                reachable,
                now_ns,
                watchdog_ns: self
                    .watchdog
                    .map(|w| u64::try_from(w.as_nanos()).unwrap_or(u64::MAX)),
            };
            let mut walk = Datagrams::new();
            while let Some(d) = walk.next_in(&out[start..end]) {
                let base = start + d.offset;
                let Some(cmd) = Cmd::from_code(out[base]) else {
                    continue;
                };
                let mut adp = u16::from_le_bytes([out[base + 2], out[base + 3]]);
                let ado = u16::from_le_bytes([out[base + 4], out[base + 5]]);
                let data_at = base + DATAGRAM_HEADER;
                let wkc_at = data_at + d.len;
                let mut wkc = u16::from_le_bytes([out[wkc_at], out[wkc_at + 1]]);
                esc.datagram(cmd, &mut adp, ado, &mut out[data_at..wkc_at], &mut wkc, hop);
                out[base + 2..base + 4].copy_from_slice(&adp.to_le_bytes());
                out[wkc_at..wkc_at + 2].copy_from_slice(&wkc.to_le_bytes());
            }
        }
        // The first ESC sets the locally-administered bit of the source
        // address, so the master can tell its own frames from replies.
        out[6] |= 0x02;
        self.frames = self.frames.saturating_add(1);
        let impairment = &mut self.impairment;
        if impairment.drop_every > 0 && self.frames.is_multiple_of(u64::from(impairment.drop_every))
        {
            return Reply::None;
        }
        if impairment.hold_count > 0 {
            impairment.hold_count -= 1;
            return Reply::After(impairment.hold);
        }
        Reply::After(Duration::ZERO)
    }

    /// Where the datagrams of a well-formed EtherCAT frame end, if it is
    /// one and an ESC is there to answer.
    fn check_frame(&self, frame: &[u8]) -> Option<usize> {
        if self.reachable == 0 || frame.len() < ETHERNET_HEADER + 2 {
            return None;
        }
        if u16::from_be_bytes([frame[12], frame[13]]) != ETHERCAT_ETHERTYPE {
            return None;
        }
        let header = u16::from_le_bytes([frame[14], frame[15]]);
        // Type 1: datagrams follow.
        if header >> 12 != 1 {
            return None;
        }
        let payload_len = usize::from(header & 0x07FF);
        let start = ETHERNET_HEADER + 2;
        let end = start
            .checked_add(payload_len)
            .filter(|&e| e <= frame.len())?;
        let payload = &frame[start..end];
        let mut walk = Datagrams::new();
        while walk.next_in(payload).is_some() {}
        walk.complete.then_some(end)
    }
}

/// Where a datagram sits in the EtherCAT payload.
struct Datagram {
    offset: usize,
    len: usize,
}

/// Walks the datagrams of an EtherCAT payload; `complete` tells, once the
/// walk ends, whether the last one closed the chain (no "more follows").
struct Datagrams {
    offset: usize,
    done: bool,
    complete: bool,
}

impl Datagrams {
    fn new() -> Self {
        Self {
            offset: 0,
            done: false,
            complete: false,
        }
    }

    /// The next datagram of `payload` (the same payload every call; the
    /// caller may change its bytes between calls, not its layout).
    fn next_in(&mut self, payload: &[u8]) -> Option<Datagram> {
        if self.done {
            return None;
        }
        let offset = self.offset;
        let Some(header) = payload.get(offset..offset + DATAGRAM_HEADER) else {
            self.done = true;
            return None;
        };
        let len_field = u16::from_le_bytes([header[6], header[7]]);
        let len = usize::from(len_field & 0x07FF);
        // Data and the 2-byte working counter must fit.
        if payload
            .get(offset + DATAGRAM_HEADER..offset + DATAGRAM_HEADER + len + 2)
            .is_none()
        {
            self.done = true;
            return None;
        }
        self.offset += DATAGRAM_HEADER + len + 2;
        if len_field & 0x8000 == 0 {
            self.done = true;
            self.complete = true;
        }
        Some(Datagram { offset, len })
    }
}
