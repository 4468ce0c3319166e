//! What the real-time cycle shows the rest of the process, and what it
//! takes from it, without a lock or an allocation on its side.
//!
//! [`LineMonitor`] is a sequence-locked image of atomics: the cycle writes
//! it once per cycle ([`LineMonitor::publish`]); readers (status lines,
//! Modbus, HTTP) copy it out with [`LineMonitor::snapshot`], retrying if
//! a write overlapped. Commands go the other way through a bounded ring:
//! senders take a lock only among themselves, the cycle reads without
//! one.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering, fence};

use crate::cia402::DriveState;
use crate::coe::Emergency;
use crate::segment::AlState;
use crate::supervisor::{FaultCause, LineFault, LineState};

/// A command for the line, taken by the cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineCommand {
    /// Enable the drives (from stopped).
    Enable,
    /// Stop: decelerate to rest, then disable.
    Disable,
    /// Clear the faults (drives that left OP are brought back).
    Reset,
    /// Make an emulated drive fault with `code` (emulated segments only).
    InjectFault {
        /// Drive position.
        drive: usize,
        /// Its error code (0x603F).
        code: u16,
    },
}

impl LineCommand {
    fn encode(self) -> u64 {
        match self {
            Self::Enable => 1,
            Self::Disable => 2,
            Self::Reset => 3,
            Self::InjectFault { drive, code } => {
                4 | (u64::from(code) << 8) | ((drive as u64 & 0xFFFF_FFFF) << 24)
            }
        }
    }

    fn decode(word: u64) -> Option<Self> {
        Some(match word & 0xFF {
            1 => Self::Enable,
            2 => Self::Disable,
            3 => Self::Reset,
            4 => Self::InjectFault {
                code: ((word >> 8) & 0xFFFF) as u16,
                drive: usize::try_from(word >> 24).ok()?,
            },
            _ => return None,
        })
    }
}

/// Commands that may wait; more are refused.
pub const COMMAND_SLOTS: usize = 64;
/// Faults the image holds.
pub const MAX_FAULTS: usize = 66;

/// The line's counters and timing, as published.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LineCounters {
    /// Cycles run.
    pub cycles: u64,
    /// Cycles whose reply did not come back in time.
    pub lost_cycles: u64,
    /// The longest run of lost cycles.
    pub lost_in_a_row_max: u64,
    /// Late replies discarded.
    pub late_replies: u64,
    /// Cycles whose working counter was short (lost ones included).
    pub working_counter_errors: u64,
    /// Exchanges that failed outright.
    pub exchange_errors: u64,
    /// Virtual master position (cam lines).
    pub virtual_master: i64,
    /// Worst wake-up lateness, ns.
    pub lateness_max_ns: u64,
    /// Mean wake-up lateness, ns.
    pub lateness_mean_ns: u64,
    /// Deadlines missed by more than a cycle.
    pub overruns: u64,
    /// Lead of the last frame before SYNC0, ns.
    pub sync0_lead_ns: i64,
}

/// One drive, as published.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DriveCell {
    /// CiA 402 state.
    pub state: DriveState,
    /// Raw statusword.
    pub statusword: u16,
    /// Error code (0x603F).
    pub error_code: u16,
    /// EtherCAT state.
    pub al_state: AlState,
    /// It answered the last exchange.
    pub reachable: bool,
    /// Operation enabled.
    pub enabled: bool,
    /// Cycles in a row without an answer.
    pub missed: u32,
    /// Actual position, unwrapped.
    pub actual: i64,
    /// Target sent last.
    pub target: i64,
    /// Following error.
    pub following_error: i64,
}

/// The whole published image, copied out.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LineSnapshot {
    /// Line state.
    pub state: Option<LineState>,
    /// Counters and timing.
    pub counters: LineCounters,
    /// The drives, in line order.
    pub drives: Vec<DriveCell>,
    /// The faults holding the line.
    pub faults: Vec<LineFault>,
    /// Faults seen since start (the list above is cleared by a reset).
    pub fault_events: u64,
}

const COUNTER_WORDS: usize = 11;
const DRIVE_WORDS: usize = 5;

/// The image and the command ring.
#[derive(Debug)]
pub struct LineMonitor {
    seq: AtomicU64,
    state: AtomicU64,
    counters: [AtomicU64; COUNTER_WORDS],
    drives: Vec<[AtomicU64; DRIVE_WORDS]>,
    /// Two words per fault: the fault, its emergency.
    faults: Vec<[AtomicU64; 2]>,
    fault_count: AtomicUsize,
    fault_events: AtomicU64,
    commands: [AtomicU64; COMMAND_SLOTS],
    head: AtomicUsize,
    tail: AtomicUsize,
    senders: Mutex<()>,
    stop: AtomicBool,
    scheduling: std::sync::OnceLock<String>,
}

/// How long [`LineMonitor::snapshot`] waits for a publish in progress to
/// end before it reads the image as it stands.
pub const SNAPSHOT_PATIENCE: std::time::Duration = std::time::Duration::from_millis(50);

fn zeros<const N: usize>() -> [AtomicU64; N] {
    std::array::from_fn(|_| AtomicU64::new(0))
}

fn state_from(code: u64) -> Option<LineState> {
    [
        LineState::Stopped,
        LineState::Enabling,
        LineState::Running,
        LineState::Faulted,
        LineState::Stopping,
        LineState::Recovering,
    ]
    .into_iter()
    .find(|s| u64::from(s.code()) + 1 == code)
}

fn al_from(code: u64) -> AlState {
    [
        AlState::Init,
        AlState::PreOp,
        AlState::Boot,
        AlState::SafeOp,
        AlState::Op,
    ]
    .into_iter()
    .find(|s| u64::from(crate::supervisor::al_state_code(*s)) == code)
    .unwrap_or(AlState::Unknown)
}

/// The fault as two words: kind (bits 0–6), emergency present (bit 7),
/// drive (8–15, 0xFF: none), a (16–31), b (32–63); then the emergency:
/// code (0–15), error register (16–23), data (24–63).
fn encode_fault(f: &LineFault) -> [u64; 2] {
    let drive = f.drive.map_or(0xFF, |d| d.min(0xFE) as u64);
    let (kind, a, b) = match f.cause {
        FaultCause::Drive { code } => (1, u64::from(code), 0),
        FaultCause::Lost { cycles } => (2, 0, u64::from(cycles)),
        FaultCause::LeftOp { state, code } => (
            3,
            u64::from(code.unwrap_or(0)),
            u64::from(crate::supervisor::al_state_code(state)) | (u64::from(code.is_some()) << 8),
        ),
        FaultCause::EnableTimeout => (4, 0, 0),
        FaultCause::RecoveryFailed => (5, 0, 0),
    };
    let (flag, emergency) = match f.emergency {
        Some(e) => {
            let mut data = [0u8; 8];
            data[3..].copy_from_slice(&e.data);
            (
                0x80,
                u64::from(e.code) | (u64::from(e.register) << 16) | u64::from_le_bytes(data),
            )
        }
        None => (0, 0),
    };
    [
        kind | flag | (drive << 8) | (a << 16) | (b << 32),
        emergency,
    ]
}

fn decode_fault([w, e]: [u64; 2]) -> Option<LineFault> {
    let drive = match (w >> 8) & 0xFF {
        0xFF => None,
        d => usize::try_from(d).ok(),
    };
    let a = (w >> 16) & 0xFFFF;
    let b = w >> 32;
    let emergency = (w & 0x80 != 0).then(|| {
        let bytes = e.to_le_bytes();
        let mut data = [0u8; 5];
        data.copy_from_slice(&bytes[3..]);
        Emergency {
            code: (e & 0xFFFF) as u16,
            register: bytes[2],
            data,
        }
    });
    let cause = match w & 0x7F {
        1 => FaultCause::Drive { code: a as u16 },
        2 => FaultCause::Lost {
            cycles: u32::try_from(b).unwrap_or(u32::MAX),
        },
        3 => FaultCause::LeftOp {
            state: al_from(b & 0xFF),
            code: (b & 0x100 != 0).then_some(a as u16),
        },
        4 => FaultCause::EnableTimeout,
        5 => FaultCause::RecoveryFailed,
        _ => return None,
    };
    Some(LineFault {
        drive,
        cause,
        emergency,
    })
}

impl LineMonitor {
    /// An image for a segment of `drives`.
    pub fn new(drives: usize) -> Self {
        Self {
            seq: AtomicU64::new(0),
            state: AtomicU64::new(0),
            counters: zeros(),
            drives: (0..drives).map(|_| zeros()).collect(),
            faults: (0..MAX_FAULTS).map(|_| zeros()).collect(),
            fault_count: AtomicUsize::new(0),
            fault_events: AtomicU64::new(0),
            commands: zeros(),
            head: AtomicUsize::new(0),
            tail: AtomicUsize::new(0),
            senders: Mutex::new(()),
            stop: AtomicBool::new(false),
            scheduling: std::sync::OnceLock::new(),
        }
    }

    /// Records what scheduling the cycle got (the driver, before its
    /// first cycle).
    pub fn set_scheduling(&self, text: String) {
        let _ = self.scheduling.set(text);
    }

    /// What scheduling the cycle got, once it runs.
    pub fn scheduling(&self) -> Option<&str> {
        self.scheduling.get().map(String::as_str)
    }

    /// Drives in the image.
    pub fn drive_count(&self) -> usize {
        self.drives.len()
    }

    /// Asks the cycle to stop the line and end (Ctrl-C, SIGTERM, the end
    /// of a server).
    pub fn request_stop(&self) {
        self.stop.store(true, Ordering::Release);
    }

    /// A stop was asked.
    pub fn stop_requested(&self) -> bool {
        self.stop.load(Ordering::Acquire)
    }

    /// Queues a command for the next cycle; false when the ring is full
    /// (the cycle has stopped taking them).
    pub fn command(&self, command: LineCommand) -> bool {
        let _senders = self.senders.lock().unwrap_or_else(|p| p.into_inner());
        let tail = self.tail.load(Ordering::Relaxed);
        let head = self.head.load(Ordering::Acquire);
        if tail.wrapping_sub(head) >= COMMAND_SLOTS {
            return false;
        }
        self.commands[tail % COMMAND_SLOTS].store(command.encode(), Ordering::Relaxed);
        self.tail.store(tail.wrapping_add(1), Ordering::Release);
        true
    }

    /// The oldest waiting command (the cycle; no lock).
    pub fn take_command(&self) -> Option<LineCommand> {
        let head = self.head.load(Ordering::Relaxed);
        if head == self.tail.load(Ordering::Acquire) {
            return None;
        }
        let word = self.commands[head % COMMAND_SLOTS].load(Ordering::Relaxed);
        self.head.store(head.wrapping_add(1), Ordering::Release);
        LineCommand::decode(word)
    }

    /// Writes the image (the cycle; no lock, no allocation). `drives`
    /// yields each drive's cell in line order.
    pub fn publish(
        &self,
        state: LineState,
        counters: &LineCounters,
        drives: impl Iterator<Item = DriveCell>,
        faults: &[LineFault],
        fault_events: u64,
    ) {
        let s = self.seq.load(Ordering::Relaxed);
        self.seq.store(s.wrapping_add(1), Ordering::Relaxed);
        fence(Ordering::Release);
        self.state
            .store(u64::from(state.code()) + 1, Ordering::Relaxed);
        let c = counters;
        let words = [
            c.cycles,
            c.lost_cycles,
            c.lost_in_a_row_max,
            c.late_replies,
            c.working_counter_errors,
            c.exchange_errors,
            c.virtual_master as u64,
            c.lateness_max_ns,
            c.lateness_mean_ns,
            c.overruns,
            c.sync0_lead_ns as u64,
        ];
        for (slot, w) in self.counters.iter().zip(words) {
            slot.store(w, Ordering::Relaxed);
        }
        for (slot, d) in self.drives.iter().zip(drives) {
            let flags = u64::from(d.reachable) | u64::from(d.enabled) << 1;
            let head = u64::from(d.statusword)
                | u64::from(d.error_code) << 16
                | u64::from(d.state.code()) << 32
                | u64::from(crate::supervisor::al_state_code(d.al_state)) << 40
                | flags << 48;
            let words = [
                head,
                u64::from(d.missed),
                d.actual as u64,
                d.target as u64,
                d.following_error as u64,
            ];
            for (w, v) in slot.iter().zip(words) {
                w.store(v, Ordering::Relaxed);
            }
        }
        let n = faults.len().min(MAX_FAULTS);
        for (slot, f) in self.faults.iter().zip(&faults[..n]) {
            for (w, v) in slot.iter().zip(encode_fault(f)) {
                w.store(v, Ordering::Relaxed);
            }
        }
        self.fault_count.store(n, Ordering::Relaxed);
        self.fault_events.store(fault_events, Ordering::Relaxed);
        self.seq.store(s.wrapping_add(2), Ordering::Release);
    }

    /// Copies the image out (a reader; retries while a write overlaps).
    ///
    /// The cycle thread may be preempted in the middle of a publish on a
    /// loaded host, so a reader first spins, then yields its time slice,
    /// and only after [`SNAPSHOT_PATIENCE`] takes the image as it stands:
    /// a reader never gets an empty image (no drives) because the writer
    /// was slow, which a Modbus client would see as its drive blocks
    /// vanishing.
    pub fn snapshot(&self) -> LineSnapshot {
        let start = std::time::Instant::now();
        let mut attempt = 0u32;
        loop {
            let before = self.seq.load(Ordering::Acquire);
            if before.is_multiple_of(2) {
                let out = self.read();
                fence(Ordering::Acquire);
                if self.seq.load(Ordering::Relaxed) == before {
                    return out;
                }
            }
            if start.elapsed() > SNAPSHOT_PATIENCE {
                return self.read();
            }
            attempt = attempt.saturating_add(1);
            if attempt < 100 {
                std::hint::spin_loop();
            } else {
                std::thread::yield_now();
            }
        }
    }

    fn read(&self) -> LineSnapshot {
        let c: Vec<u64> = self
            .counters
            .iter()
            .map(|a| a.load(Ordering::Relaxed))
            .collect();
        let counters = LineCounters {
            cycles: c[0],
            lost_cycles: c[1],
            lost_in_a_row_max: c[2],
            late_replies: c[3],
            working_counter_errors: c[4],
            exchange_errors: c[5],
            virtual_master: c[6] as i64,
            lateness_max_ns: c[7],
            lateness_mean_ns: c[8],
            overruns: c[9],
            sync0_lead_ns: c[10] as i64,
        };
        let drives = self
            .drives
            .iter()
            .map(|slot| {
                let w: Vec<u64> = slot.iter().map(|a| a.load(Ordering::Relaxed)).collect();
                let flags = w[0] >> 48;
                DriveCell {
                    statusword: (w[0] & 0xFFFF) as u16,
                    error_code: ((w[0] >> 16) & 0xFFFF) as u16,
                    state: DriveState::ALL
                        .into_iter()
                        .find(|s| u64::from(s.code()) == (w[0] >> 32) & 0xFF)
                        .unwrap_or(DriveState::NotReadyToSwitchOn),
                    al_state: al_from((w[0] >> 40) & 0xFF),
                    reachable: flags & 1 != 0,
                    enabled: flags & 2 != 0,
                    missed: u32::try_from(w[1]).unwrap_or(u32::MAX),
                    actual: w[2] as i64,
                    target: w[3] as i64,
                    following_error: w[4] as i64,
                }
            })
            .collect();
        let n = self.fault_count.load(Ordering::Relaxed).min(MAX_FAULTS);
        let faults = self.faults[..n]
            .iter()
            .filter_map(|[a, b]| {
                decode_fault([a.load(Ordering::Relaxed), b.load(Ordering::Relaxed)])
            })
            .collect();
        LineSnapshot {
            state: state_from(self.state.load(Ordering::Relaxed)),
            counters,
            drives,
            faults,
            fault_events: self.fault_events.load(Ordering::Relaxed),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn image_round_trips() {
        let m = LineMonitor::new(2);
        assert_eq!(m.snapshot().state, None, "nothing published yet");
        let faults = [
            LineFault {
                emergency: Some(Emergency {
                    data: [1, 2, 3, 4, 0xFF],
                    ..Emergency::for_code(0x2310)
                }),
                ..LineFault::new(Some(1), FaultCause::Drive { code: 0x2310 })
            },
            LineFault::new(
                Some(0),
                FaultCause::LeftOp {
                    state: AlState::SafeOp,
                    code: Some(0x001B),
                },
            ),
            LineFault::new(None, FaultCause::Lost { cycles: 4_000_000 }),
        ];
        let cell = DriveCell {
            state: DriveState::OperationEnabled,
            statusword: 0x1237,
            error_code: 0,
            al_state: AlState::Op,
            reachable: true,
            enabled: true,
            missed: 0,
            actual: -5_000_000_000,
            target: 7,
            following_error: -3,
        };
        let counters = LineCounters {
            cycles: 9,
            lost_cycles: 2,
            virtual_master: -4,
            sync0_lead_ns: 250_000,
            ..LineCounters::default()
        };
        m.publish(
            LineState::Faulted,
            &counters,
            [cell, DriveCell::default()].into_iter(),
            &faults,
            3,
        );
        let s = m.snapshot();
        assert_eq!(s.state, Some(LineState::Faulted));
        assert_eq!(s.counters, counters);
        assert_eq!(s.drives[0], cell);
        assert_eq!(s.faults, faults);
        assert_eq!(s.fault_events, 3);
    }

    #[test]
    fn a_reader_never_gets_an_empty_image_from_a_stalled_writer() {
        let m = LineMonitor::new(2);
        m.publish(
            LineState::Running,
            &LineCounters::default(),
            [DriveCell::default(), DriveCell::default()].into_iter(),
            &[],
            0,
        );
        // A writer preempted between its two sequence stores.
        m.seq.fetch_add(1, Ordering::Relaxed);
        let s = m.snapshot();
        assert_eq!(s.drives.len(), 2, "the drives stay in the image");
        assert_eq!(s.state, Some(LineState::Running));
    }

    #[test]
    fn commands_queue_in_order_and_refuse_when_full() {
        let m = LineMonitor::new(1);
        assert!(m.command(LineCommand::Reset));
        assert!(m.command(LineCommand::InjectFault {
            drive: 3,
            code: 0x7500
        }));
        assert_eq!(m.take_command(), Some(LineCommand::Reset));
        assert_eq!(
            m.take_command(),
            Some(LineCommand::InjectFault {
                drive: 3,
                code: 0x7500
            })
        );
        assert_eq!(m.take_command(), None);
        for _ in 0..COMMAND_SLOTS {
            assert!(m.command(LineCommand::Enable));
        }
        assert!(!m.command(LineCommand::Enable));
    }
}
