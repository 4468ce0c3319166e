//! The drives on a fieldbus as clients see them (`ecam serve --ethercat`):
//! status as input registers from 20000 and JSON, and three commands
//! (enable, disable, fault reset) as coils 14000/14001 and HTTP posts.
//!
//! The fieldbus cycle (ecam-ethercat's driver) publishes its status
//! without a lock; a [`BusSource`] (the binary's wiring) turns it into a
//! [`BusSnapshot`] when a client asks and queues [`BusCommand`]s for the
//! cycle; this module maps both to Modbus and JSON. The areas are new addresses outside the contract's D/M/X/Y
//! areas, so nothing a client used before moves; without `--ethercat`
//! they are gaps (exception 02), as before.
//!
//! | address | object | meaning |
//! |---|---|---|
//! | 14000 | coil | read: the drives are enabled or enabling; write 1: enable, 0: disable |
//! | 14001 | coil | read: a fault holds the line; write 1: fault reset (0 does nothing) |
//! | 20000–20015 | input registers | the line (see [`HEADER_WORDS`]) |
//! | 20016 + 16·n … | input registers | drive n (see [`DRIVE_WORDS`]) |

use serde::Serialize;

use crate::pdu::Exception;

/// Coil of "drives enabled" (read) / enable and disable (write).
pub const ENABLE_COIL: u16 = 14000;
/// Coil of "line faulted" (read) / fault reset (write 1).
pub const FAULT_COIL: u16 = 14001;
/// First input register of the bus area.
pub const BUS_REGISTER_BASE: u16 = 20000;
/// Words of the line's block at 20000: 0 drives on the segment, 1 line
/// state (0 stopped, 1 enabling, 2 running, 3 faulted, 4 stopping, 5
/// recovering), 2 faults holding the line, 3–4 cycle time µs, 5–6 cycles
/// run, 7–8 working-counter errors (32-bit values low word first, as the
/// PLC's), 9 worst wake-up lateness µs, 10 mean lateness µs, 11 overruns,
/// 12–13 lost cycles (replies not back in time), 14 late replies
/// discarded, 15 lead of the last frame before SYNC0, µs (16-bit values
/// saturate).
pub const HEADER_WORDS: u16 = 16;
/// Words of each drive's block: 0 CiA 402 state (0 not ready to switch
/// on, 1 switch on disabled, 2 ready to switch on, 3 switched on, 4
/// operation enabled, 5 quick stop active, 6 fault reaction active, 7
/// fault), 1 statusword, 2 error code (0x603F), 3 flags (bit 0 answers, 1
/// enabled, 2 faulted, 3 follows an output), 4–5 actual position, 6–7
/// target position, 8–9 following error (32-bit, low word first, the
/// drive's own modulo-2³² counts), 10 the output it follows (0–3, 0xFFFF
/// none), 11 EtherCAT state (0 none, 1 INIT, 2 PRE-OP, 4 SAFE-OP, 8 OP),
/// 12 cycles in a row without its answer, 13–15 reserved (0).
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
    /// The motion decelerates to rest before the drives are disabled.
    Stopping,
    /// A reset brings drives back to OP and out of their faults.
    Recovering,
}

impl BusLineState {
    fn code(self) -> u16 {
        match self {
            Self::Stopped => 0,
            Self::Enabling => 1,
            Self::Running => 2,
            Self::Faulted => 3,
            Self::Stopping => 4,
            Self::Recovering => 5,
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
    /// EtherCAT state code (0 none, 1 INIT, 2 PRE-OP, 4 SAFE-OP, 8 OP).
    pub al_state_code: u16,
    /// EtherCAT state in words.
    pub al_state: String,
    /// The error code (0x603F) in words.
    pub error: String,
    /// Cycles in a row without its answer.
    pub missed_cycles: u32,
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
    /// Cycles whose reply did not come back in time.
    pub lost_cycles: u64,
    /// The longest run of lost cycles.
    pub lost_in_a_row_max: u64,
    /// More lost cycles in a row than this fault the line.
    pub max_lost_cycles: u32,
    /// Late replies discarded.
    pub late_replies: u64,
    /// Lead of the last frame before the drives' SYNC0 edge, µs.
    pub sync0_lead_us: f64,
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

/// Where the face reads the line's state and sends its commands.
pub trait BusSource: Send + Sync {
    /// The line and its drives now.
    fn snapshot(&self) -> BusSnapshot;
    /// Queues a command for the cycle; false when the cycle has stopped
    /// taking them.
    fn command(&self, command: BusCommand) -> bool;
}

/// The line as Modbus and HTTP clients see it.
pub struct BusFace {
    source: Box<dyn BusSource>,
}

impl core::fmt::Debug for BusFace {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("BusFace").finish_non_exhaustive()
    }
}

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
    /// A face onto `source`.
    pub fn new(source: impl BusSource + 'static) -> Self {
        Self {
            source: Box::new(source),
        }
    }

    /// The line and its drives now.
    pub fn snapshot(&self) -> BusSnapshot {
        self.source.snapshot()
    }

    /// Queues a command for the next cycle.
    ///
    /// # Errors
    /// [`Exception::ServerDeviceBusy`] when the cycle has not taken the
    /// commands queued before (it has stopped).
    pub fn command(&self, command: BusCommand) -> Result<(), Exception> {
        if self.source.command(command) {
            Ok(())
        } else {
            Err(Exception::ServerDeviceBusy)
        }
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
        let state = self.snapshot().state;
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
        let words = registers(&self.snapshot());
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
    put32(&mut w, 12, s.lost_cycles as u32);
    w[14] = sat16(s.late_replies);
    w[15] = sat16(s.sync0_lead_us.max(0.0) as u64);
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
        w[at + 11] = d.al_state_code;
        w[at + 12] = sat16(u64::from(d.missed_cycles));
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// A source that returns a fixed snapshot and keeps the commands.
    struct Fixed(BusSnapshot, Mutex<Vec<BusCommand>>);

    impl BusSource for Fixed {
        fn snapshot(&self) -> BusSnapshot {
            self.0.clone()
        }
        fn command(&self, command: BusCommand) -> bool {
            let mut queue = self.1.lock().unwrap();
            if queue.len() >= 4 {
                return false;
            }
            queue.push(command);
            true
        }
    }

    fn snapshot() -> BusSnapshot {
        BusSnapshot {
            transport: "emulated".into(),
            cycle_us: 100_000,
            state: BusLineState::Faulted,
            faults: vec!["drive 1: drive fault".into()],
            cycles: 0x1_0002,
            working_counter_errors: 3,
            lateness_max_us: 70_000.4,
            lateness_mean_us: 12.6,
            overruns: 1,
            lost_cycles: 0x2_0005,
            late_replies: 4,
            sync0_lead_us: 499.6,
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
                    al_state_code: 8,
                    ..DriveView::default()
                },
                DriveView {
                    position: 1,
                    state_code: 7,
                    error_code: 0x7500,
                    reachable: true,
                    fault: Some("fault".into()),
                    actual: 9,
                    al_state_code: 4,
                    missed_cycles: 70_000,
                    ..DriveView::default()
                },
            ],
            ..BusSnapshot::default()
        }
    }

    fn face() -> BusFace {
        BusFace::new(Fixed(snapshot(), Mutex::new(Vec::new())))
    }

    #[test]
    fn registers_carry_the_line_and_each_drive() {
        let f = face();
        let h = f.read_registers(20000, 16).unwrap();
        assert_eq!(
            h,
            vec![2, 3, 1, 0x86A0, 1, 2, 1, 3, 0, 65535, 12, 1, 5, 2, 4, 499]
        );
        let d0 = f.read_registers(20016, 16).unwrap();
        // 5e9 mod 2^32 = 705032704 = 0x2A05_F200.
        assert_eq!(
            &d0[..11],
            &[
                4, 0x1237, 0, 0b1011, 0xFFFE, 0xFFFF, 0xF200, 0x2A05, 7, 0, 0
            ]
        );
        let d1 = f.read_registers(20032, 16).unwrap();
        assert_eq!(
            &d1[..13],
            &[7, 0, 0x7500, 0b0101, 9, 0, 9, 0, 0, 0, 0xFFFF, 4, 0xFFFF]
        );
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
        let source = Fixed(snapshot(), Mutex::new(Vec::new()));
        let f = BusFace::new(source);
        f.write_coils(14001, &[true]).unwrap();
        f.write_coils(14000, &[true, false]).unwrap();
        f.write_coils(14000, &[false, true]).unwrap();
        assert_eq!(
            f.write_coils(14001, &[true]),
            Err(Exception::ServerDeviceBusy),
            "the fifth command finds the queue full"
        );
    }
}
