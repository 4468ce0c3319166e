//! The drives on a fieldbus as clients see them (`ecam serve --ethercat`):
//! status as input registers from 20000 and JSON, and three commands
//! (enable, disable, fault reset) as coils 14000/14001 and HTTP posts.
//!
//! The fieldbus cycle (in the binary) publishes a [`BusSnapshot`] every
//! cycle and takes the queued [`BusCommand`]s; this module only maps both
//! to Modbus. The areas are new addresses outside the contract's D/M/X/Y
//! areas, so nothing a client used before moves; without `--ethercat`
//! they are gaps (exception 02), as before.
//!
//! | address | object | meaning |
//! |---|---|---|
//! | 14000 | coil | read: the drives are enabled or enabling; write 1: enable, 0: disable |
//! | 14001 | coil | read: a fault holds the line; write 1: fault reset (0 does nothing) |
//! | 20000–20015 | input registers | the line (see [`HEADER_WORDS`]) |
//! | 20016 + 16·n … | input registers | drive n (see [`DRIVE_WORDS`]) |

use std::collections::VecDeque;
use std::sync::Mutex;

use serde::Serialize;

use crate::pdu::Exception;
use crate::state::lock;

/// Coil of "drives enabled" (read) / enable and disable (write).
pub const ENABLE_COIL: u16 = 14000;
/// Coil of "line faulted" (read) / fault reset (write 1).
pub const FAULT_COIL: u16 = 14001;
/// First input register of the bus area.
pub const BUS_REGISTER_BASE: u16 = 20000;
/// Words of the line's block at 20000: 0 drives on the segment, 1 line
/// state (0 stopped, 1 enabling, 2 running, 3 faulted), 2 faults holding
/// the line, 3–4 cycle time µs, 5–6 cycles run, 7–8 working-counter
/// errors (32-bit values low word first, as the PLC's), 9 worst wake-up
/// lateness µs, 10 mean lateness µs, 11 overruns (16-bit values saturate),
/// 12–15 reserved (0).
pub const HEADER_WORDS: u16 = 16;
/// Words of each drive's block: 0 CiA 402 state (0 not ready to switch
/// on, 1 switch on disabled, 2 ready to switch on, 3 switched on, 4
/// operation enabled, 5 quick stop active, 6 fault reaction active, 7
/// fault), 1 statusword, 2 error code (0x603F), 3 flags (bit 0 answers, 1
/// enabled, 2 faulted, 3 follows an output), 4–5 actual position, 6–7
/// target position, 8–9 following error (32-bit, low word first, the
/// drive's own modulo-2³² counts), 10 the output it follows (0–3, 0xFFFF
/// none), 11–15 reserved (0).
pub const DRIVE_WORDS: u16 = 16;

/// Where the line of drives is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum BusLineState {
    /// Drives disabled.
    #[default]
    Stopped,
    /// Drives being enabled.
    Enabling,
    /// Every drive follows.
    Running,
    /// A fault stopped the line; a fault reset clears it.
    Faulted,
}

impl BusLineState {
    fn code(self) -> u16 {
        match self {
            Self::Stopped => 0,
            Self::Enabling => 1,
            Self::Running => 2,
            Self::Faulted => 3,
        }
    }
}

/// One drive's status.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct DriveView {
    /// Position in the line.
    pub position: usize,
    /// The name the drive's EEPROM gives.
    pub name: String,
    /// CiA 402 state code (see [`DRIVE_WORDS`]).
    pub state_code: u16,
    /// CiA 402 state in words.
    pub state: String,
    /// Raw statusword.
    pub statusword: u16,
    /// Error code (0x603F).
    pub error_code: u16,
    /// The drive answered in the last exchange.
    pub reachable: bool,
    /// Operation enabled.
    pub enabled: bool,
    /// The fault it reports, if any.
    pub fault: Option<String>,
    /// Actual position, unwrapped.
    pub actual: i64,
    /// Target sent last, if it follows an output.
    pub target: Option<i64>,
    /// Following error.
    pub following_error: i64,
    /// The pulse output it follows (0–3), if any.
    pub output: Option<u8>,
}

/// The line and its drives after a cycle.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct BusSnapshot {
    /// Interface, or `emulated (N drives)`.
    pub transport: String,
    /// Cycle time, µs.
    pub cycle_us: u32,
    /// Line state.
    pub state: BusLineState,
    /// The faults holding the line, in words.
    pub faults: Vec<String>,
    /// Cycles run.
    pub cycles: u64,
    /// Cycles whose working counter was short.
    pub working_counter_errors: u64,
    /// Worst wake-up lateness, µs.
    pub lateness_max_us: f64,
    /// Mean wake-up lateness, µs.
    pub lateness_mean_us: f64,
    /// Deadlines missed by more than a cycle.
    pub overruns: u64,
    /// The drives, in line order.
    pub drives: Vec<DriveView>,
}

/// What a client asks of the line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum BusCommand {
    /// Enable the drives (from stopped).
    Enable,
    /// Disable the drives.
    Disable,
    /// Clear the faults (the line is stopped afterwards).
    Reset,
    /// Make an emulated drive fault with `code` (`--emulated` only: to try
    /// the fault reaction without hardware).
    EmulateFault {
        /// Drive position.
        drive: usize,
        /// Its error code (0x603F).
        code: u16,
    },
}

/// The snapshot the cycle publishes and the commands it takes.
#[derive(Debug, Default)]
pub struct BusFace {
    snapshot: Mutex<BusSnapshot>,
    commands: Mutex<VecDeque<BusCommand>>,
}

/// Most commands waiting for the cycle; more are refused (exception 06).
const MAX_QUEUED: usize = 64;

fn low(v: u32) -> u16 {
    (v & 0xFFFF) as u16
}

fn high(v: u32) -> u16 {
    (v >> 16) as u16
}

fn sat16(v: u64) -> u16 {
    u16::try_from(v).unwrap_or(u16::MAX)
}

impl BusFace {
    /// A face with an empty snapshot and no commands.
    pub fn new() -> Self {
        Self::default()
    }

    /// Publishes the line's state (the cycle, once per cycle).
    pub fn publish(&self, snapshot: BusSnapshot) {
        *lock(&self.snapshot) = snapshot;
    }

    /// A copy of the last published state.
    pub fn snapshot(&self) -> BusSnapshot {
        lock(&self.snapshot).clone()
    }

    /// Queues a command for the next cycle.
    ///
    /// # Errors
    /// [`Exception::ServerDeviceBusy`] when the cycle has not taken the
    /// last 64 commands (it has stopped).
    pub fn command(&self, command: BusCommand) -> Result<(), Exception> {
        let mut queue = lock(&self.commands);
        if queue.len() >= MAX_QUEUED {
            return Err(Exception::ServerDeviceBusy);
        }
        queue.push_back(command);
        Ok(())
    }

    /// Takes the queued commands, oldest first (the cycle).
    pub fn take_commands(&self) -> Vec<BusCommand> {
        lock(&self.commands).drain(..).collect()
    }

    /// Whether a coil range falls in the bus area (14000–14001).
    pub fn owns_coils(address: u16) -> bool {
        (ENABLE_COIL..=FAULT_COIL).contains(&address)
    }

    /// Reads coils 14000–14001.
    ///
    /// # Errors
    /// 02 when the range leaves the area, 03 for quantity 0.
    pub fn read_coils(&self, address: u16, quantity: u16) -> Result<Vec<bool>, Exception> {
        let range = coil_offsets(address, quantity)?;
        let state = lock(&self.snapshot).state;
        let bits = [
            matches!(state, BusLineState::Enabling | BusLineState::Running),
            state == BusLineState::Faulted,
        ];
        Ok(range.map(|i| bits[i]).collect())
    }

    /// Writes coils 14000–14001 as commands.
    ///
    /// # Errors
    /// 02 when the range leaves the area, 03 for no values, 06 when the
    /// queue is full.
    pub fn write_coils(&self, address: u16, values: &[bool]) -> Result<(), Exception> {
        let quantity = u16::try_from(values.len()).map_err(|_| Exception::IllegalDataValue)?;
        let range = coil_offsets(address, quantity)?;
        for (offset, &on) in range.zip(values) {
            match (offset, on) {
                (0, true) => self.command(BusCommand::Enable)?,
                (0, false) => self.command(BusCommand::Disable)?,
                (_, true) => self.command(BusCommand::Reset)?,
                (_, false) => {}
            }
        }
        Ok(())
    }

    /// Whether an input-register address falls in the bus area.
    pub fn owns_registers(address: u16) -> bool {
        address >= BUS_REGISTER_BASE
    }

    /// Reads input registers of the bus area.
    ///
    /// # Errors
    /// 02 when the range runs past the last drive's block, 03 for quantity 0.
    pub fn read_registers(&self, address: u16, quantity: u16) -> Result<Vec<u16>, Exception> {
        if quantity == 0 {
            return Err(Exception::IllegalDataValue);
        }
        let snapshot = lock(&self.snapshot);
        let words = registers(&snapshot);
        let start = usize::from(address.saturating_sub(BUS_REGISTER_BASE));
        words
            .get(start..start + usize::from(quantity))
            .map(<[u16]>::to_vec)
            .ok_or(Exception::IllegalDataAddress)
    }
}

/// Offsets 0..2 of a coil range inside 14000–14001.
fn coil_offsets(address: u16, quantity: u16) -> Result<std::ops::Range<usize>, Exception> {
    if quantity == 0 {
        return Err(Exception::IllegalDataValue);
    }
    let start = address
        .checked_sub(ENABLE_COIL)
        .ok_or(Exception::IllegalDataAddress)?;
    let end = usize::from(start) + usize::from(quantity);
    if end > 2 {
        return Err(Exception::IllegalDataAddress);
    }
    Ok(usize::from(start)..end)
}

/// The whole register image of a snapshot.
fn registers(s: &BusSnapshot) -> Vec<u16> {
    let mut w = vec![0u16; usize::from(HEADER_WORDS) + s.drives.len() * usize::from(DRIVE_WORDS)];
    fn put32(w: &mut [u16], at: usize, v: u32) {
        w[at] = low(v);
        w[at + 1] = high(v);
    }
    w[0] = sat16(s.drives.len() as u64);
    w[1] = s.state.code();
    w[2] = sat16(s.faults.len() as u64);
    put32(&mut w, 3, s.cycle_us);
    put32(&mut w, 5, s.cycles as u32);
    put32(&mut w, 7, s.working_counter_errors as u32);
    w[9] = sat16(s.lateness_max_us as u64);
    w[10] = sat16(s.lateness_mean_us as u64);
    w[11] = sat16(s.overruns);
    for (n, d) in s.drives.iter().enumerate() {
        let at = usize::from(HEADER_WORDS) + n * usize::from(DRIVE_WORDS);
        w[at] = d.state_code;
        w[at + 1] = d.statusword;
        w[at + 2] = d.error_code;
        w[at + 3] = u16::from(d.reachable)
            | u16::from(d.enabled) << 1
            | u16::from(d.fault.is_some()) << 2
            | u16::from(d.output.is_some()) << 3;
        // The drive's own 32-bit counts: truncation is its modulo 2^32.
        put32(&mut w, at + 4, d.actual as u32);
        put32(&mut w, at + 6, d.target.unwrap_or(d.actual) as u32);
        put32(&mut w, at + 8, d.following_error as u32);
        w[at + 10] = d.output.map_or(0xFFFF, u16::from);
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    fn face() -> BusFace {
        let face = BusFace::new();
        face.publish(BusSnapshot {
            transport: "emulated".into(),
            cycle_us: 100_000,
            state: BusLineState::Faulted,
            faults: vec!["drive 1: drive fault".into()],
            cycles: 0x1_0002,
            working_counter_errors: 3,
            lateness_max_us: 70_000.4,
            lateness_mean_us: 12.6,
            overruns: 1,
            drives: vec![
                DriveView {
                    position: 0,
                    state_code: 4,
                    statusword: 0x1237,
                    reachable: true,
                    enabled: true,
                    actual: -2,
                    target: Some(5_000_000_000),
                    following_error: 7,
                    output: Some(0),
                    ..DriveView::default()
                },
                DriveView {
                    position: 1,
                    state_code: 7,
                    error_code: 0x7500,
                    reachable: true,
                    fault: Some("fault".into()),
                    actual: 9,
                    ..DriveView::default()
                },
            ],
        });
        face
    }

    #[test]
    fn registers_carry_the_line_and_each_drive() {
        let f = face();
        let h = f.read_registers(20000, 16).unwrap();
        assert_eq!(&h[..12], &[2, 3, 1, 0x86A0, 1, 2, 1, 3, 0, 65535, 12, 1]);
        let d0 = f.read_registers(20016, 16).unwrap();
        // 5e9 mod 2^32 = 705032704 = 0x2A05_F200.
        assert_eq!(
            &d0[..11],
            &[
                4, 0x1237, 0, 0b1011, 0xFFFE, 0xFFFF, 0xF200, 0x2A05, 7, 0, 0
            ]
        );
        let d1 = f.read_registers(20032, 16).unwrap();
        assert_eq!(&d1[..11], &[7, 0, 0x7500, 0b0101, 9, 0, 9, 0, 0, 0, 0xFFFF]);
        assert_eq!(f.read_registers(20047, 1), Ok(vec![0]));
        assert_eq!(
            f.read_registers(20047, 2),
            Err(Exception::IllegalDataAddress)
        );
        assert_eq!(
            f.read_registers(20048, 1),
            Err(Exception::IllegalDataAddress)
        );
        assert_eq!(f.read_registers(20000, 0), Err(Exception::IllegalDataValue));
    }

    #[test]
    fn coils_read_the_state_and_queue_commands() {
        let f = face();
        assert_eq!(f.read_coils(14000, 2), Ok(vec![false, true]));
        assert_eq!(f.read_coils(14001, 2), Err(Exception::IllegalDataAddress));
        f.write_coils(14001, &[true]).unwrap();
        f.write_coils(14000, &[true, false]).unwrap();
        f.write_coils(14000, &[false]).unwrap();
        assert_eq!(
            f.take_commands(),
            vec![BusCommand::Reset, BusCommand::Enable, BusCommand::Disable]
        );
        assert!(f.take_commands().is_empty());
        for _ in 0..MAX_QUEUED {
            f.command(BusCommand::Enable).unwrap();
        }
        assert_eq!(
            f.command(BusCommand::Enable),
            Err(Exception::ServerDeviceBusy)
        );
    }
}
