//! `DECAM S1 S2 S3 D1 D2`: the E-cam instruction of document 003 on top of
//! the engine.
//!
//! The instruction has two halves, as on the device:
//! - [`Decam::execute`] runs at the instruction's place in every scan. It
//!   records the power flow, writes the version (offset 0) and table offset
//!   (offset 39) and checks the whole register block. A bad block is
//!   reported as operation error 6781/6782/6783 (the scan puts it in D8067 and
//!   sets M8067), in the error register (offset 2) and flag bits 3–5; the
//!   cam that is running keeps running unchanged, a cam that is not running
//!   does not start, and all of it clears once the block is corrected.
//! - [`Decam::hardware_tick`] runs every hardware tick (100 µs by default):
//!   it reads the master and the start register, starts and stops the cam,
//!   ticks the engine, emits the pulses through
//!   `hardware::record_pulses` (so D8140… always equal the slave
//!   position), drives the direction and sync outputs and updates the
//!   status registers.
//!
//! While armed or following, the cam holds its pulse output
//! (`Hardware::claim_output`); a start while another
//! instruction holds the output waits until it is free.
//!
//! The register map, every ambiguity of the manual and the choice made are
//! listed in `docs/plc.md`.
//!
//! ```
//! use ecam_plc::decam::{Decam, DecamOperands, MasterOperand};
//! use ecam_plc::{Device, Devices};
//! use ecam_plc::Hardware;
//!
//! let mut dev = Devices::new();
//! let mut hw = Hardware::new();
//! // Table at D2038…: master 0..1000, slave 0..100 (D2038 = 2 points).
//! dev.set_word(2038, 2)?;
//! dev.set_dword(2044, 1000)?;
//! dev.set_dword(2046, 100)?;
//! dev.set_dword(10, 0)?; // the master: D10/D11
//! let ops = DecamOperands::new(MasterOperand::Register(10), 2000, Device::X(0), 0, Device::Y(4))?;
//! let mut cam = Decam::new(ops);
//! dev.set_word(2005, 1)?; // cyclic
//! cam.execute(true, &mut dev, 0)?;
//! for t in 0..10u64 {
//!     dev.set_dword(10, (t * 50) as i32)?; // the master moves 50 counts a tick
//!     cam.hardware_tick(&mut dev, &mut hw, t * 100, 100);
//! }
//! assert_eq!(dev.dword(8140)?, 45); // Y0's pulse counter = slave at master 450
//! assert_eq!(dev.word(2000)?, 5200);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod address;
mod block;
mod block_error;
pub mod flags;
mod master;
pub mod offsets;
mod operands;
mod run;
mod start_gate;
mod sync_output;
mod table_load;

pub use address::{BlockAddressError, LAST_START, block_at};
pub use block_error::BlockError;
pub use operands::{DecamOperands, MasterOperand};
pub use start_gate::CamMode;
pub use table_load::load_table;

pub(crate) use block::{LiveSettings, StartSetup};
pub(crate) use master::MasterReader;
pub(crate) use start_gate::{GateAction, StartGate};
pub(crate) use sync_output::SyncOutput;

use core::sync::atomic::{AtomicU64, Ordering};

use ecam_engine::MasterPosition;

use self::block::Block;
use self::run::{Origin, Run, Start};
use crate::devices::Devices;
use crate::hardware::{Hardware, OutputOwner, record_pulses};
use crate::operation_error::OperationError;

/// Document 003 section 4.2.1: a noncyclic cam re-armed for the next start
/// signal accepts it no sooner than 5 ms after the previous run ended.
pub(crate) const NONCYCLIC_REARM_US: u64 = 5_000;

/// Numbers the DECAM instances of the process, so that each one has its own
/// [`OutputOwner`].
static NEXT_INSTANCE: AtomicU64 = AtomicU64::new(0);

/// Where the instruction is between starts; each phase holds what only it
/// has.
#[derive(Clone, Debug)]
enum Phase {
    /// No mode accepted.
    Idle,
    /// A mode with external start (function bit 5) waits for a rising edge
    /// of S3, accepted from `ready_at` on; `announced` once flag bit 0 was
    /// set for this readiness.
    Ready {
        start: Start,
        ready_at: u64,
        announced: bool,
    },
    /// The engine is armed (delay, start position), following, or sending
    /// the last pulses it owes.
    Running(Box<Run>),
    /// Stopped at a cycle end or by M8145…: the start register must go
    /// through 0 to start again.
    Done,
}

/// Checks the table words of the block at `D{block}` as `devices` hold
/// them, as [`Decam::check_table`] does for its own block.
pub(crate) fn check_table_at(devices: &Devices, block: u16) -> Result<(), BlockError> {
    Block::new(devices, block).table_check()
}

/// One DECAM instruction of a program.
pub struct Decam {
    operands: DecamOperands,
    /// This instance's identity towards the pulse output (one driver each).
    owner: OutputOwner,
    master: MasterReader,
    enabled: bool,
    gate: StartGate,
    /// The last register block that passed the checks.
    setup: Option<StartSetup>,
    /// The last valid run-time settings (offsets 4, 8–12).
    live: Option<LiveSettings>,
    error: Option<BlockError>,
    phase: Phase,
    start_level: bool,
    sync: SyncOutput,
    /// Flag bit 9, latched when a run ends at a cycle end; cleared at the
    /// next start.
    cycle_done: bool,
    /// Pending writes to the program-owned flag bits 0 and 1.
    set_latched: u16,
    clear_latched: u16,
    /// The engine stopped the cam on a runtime fault (e.g. a slave position
    /// past 64 bits): flag bit 3 ("something is error, E-cam stop running")
    /// until the next start.
    runtime_fault: Option<ecam_engine::EngineError>,
    /// The fault not yet returned to the scan (D8067/M8067).
    fault_to_report: Option<ecam_engine::EngineError>,
}

impl Decam {
    /// A DECAM instruction with checked operands, not yet executed.
    pub fn new(operands: DecamOperands) -> Self {
        Self {
            operands,
            owner: OutputOwner::Cam(NEXT_INSTANCE.fetch_add(1, Ordering::Relaxed)),
            master: MasterReader::new(operands.master),
            enabled: false,
            gate: StartGate::new(),
            setup: None,
            live: None,
            error: None,
            phase: Phase::Idle,
            start_level: false,
            sync: SyncOutput::new(),
            cycle_done: false,
            set_latched: 0,
            clear_latched: 0,
            runtime_fault: None,
            fault_to_report: None,
        }
    }

    fn run(&self) -> Option<&Run> {
        match &self.phase {
            Phase::Running(run) => Some(run),
            _ => None,
        }
    }

    /// The operands.
    pub fn operands(&self) -> &DecamOperands {
        &self.operands
    }

    /// This instance's identity as the driver of its pulse output: while
    /// the cam is armed or following, [`Hardware::owner`] of D1 is this.
    pub fn output_owner(&self) -> OutputOwner {
        self.owner
    }

    /// The block error found by the last [`Decam::execute`], if any.
    pub fn error(&self) -> Option<&BlockError> {
        self.error.as_ref()
    }

    /// The mode the start register has engaged, if any.
    pub fn mode(&self) -> Option<CamMode> {
        self.gate.active()
    }

    /// True while the engine is armed or following a cam (or sending the
    /// last pulses it owes).
    pub fn is_running(&self) -> bool {
        self.run().is_some()
    }

    /// The master span (last point's master − first's, in table counts)
    /// of the table the running cam follows: its cycle length after the
    /// master zoom. A table written into the block meanwhile waits for the
    /// next seam, so this is not read from the block's words. `None` while
    /// no cam runs.
    pub fn running_table_span(&self) -> Option<i64> {
        self.run().map(Run::table_span)
    }

    /// Checks the table words of the block (offset 31 and the table from
    /// offset 38) as `devices` hold them, the way a start or a seam takes
    /// them; the rest of the block is left aside.
    ///
    /// # Errors
    /// The [`BlockError`] the block would show (6781 for offset 31, 6782,
    /// 6783).
    pub fn check_table(&self, devices: &Devices) -> Result<(), BlockError> {
        check_table_at(devices, self.operands.block)
    }

    /// The instruction at its place in the scan; `enabled` is its power flow.
    ///
    /// # Errors
    /// The block's [`BlockError`] as operation error 6781, 6782 or 6783.
    pub fn execute(
        &mut self,
        enabled: bool,
        devices: &mut Devices,
        _now_us: u64,
    ) -> Result<(), OperationError> {
        self.enabled = enabled;
        if !enabled {
            return Ok(());
        }
        let base = self.operands.block;
        let _ = devices.set_word(self.operands.reg(offsets::VERSION), offsets::VERSION_NUMBER);
        let _ = devices.set_word(
            self.operands.reg(offsets::TABLE_OFFSET),
            offsets::TABLE as i16,
        );
        let block = Block::new(devices, base);
        let operands = self.operands;
        let checked = block
            .start_setup()
            .and_then(|setup| Ok((setup, live_settings(&block, &operands)?)));
        let result = match checked {
            Ok((setup, live)) => {
                if let Phase::Running(run) = &mut self.phase {
                    run.offer_table(&setup.table, setup.single_pass);
                }
                self.setup = Some(setup);
                self.live = Some(live);
                self.error = None;
                Ok(())
            }
            Err(e) => {
                let err = e.to_operation_error(base);
                self.error = Some(e);
                Err(err)
            }
        };
        let shown = self.error.as_ref().map_or(0, BlockError::register_value);
        let _ = devices.set_word(self.operands.reg(offsets::ERROR), shown as i16);
        self.write_flags(devices);
        match (result, self.fault_to_report.take()) {
            (Ok(()), Some(fault)) => Err(OperationError::cam(
                fault.kind(),
                format!("DECAM block D{base}: {fault}"),
            )),
            (result, _) => result,
        }
    }

    /// One hardware tick of `dt_us` ending at `now_us`.
    pub fn hardware_tick(
        &mut self,
        devices: &mut Devices,
        hardware: &mut Hardware,
        now_us: u64,
        dt_us: u32,
    ) {
        if !self.enabled {
            let was_active = !matches!(self.phase, Phase::Idle) || self.gate.active().is_some();
            self.gate.power_off(now_us);
            if was_active {
                self.stop_now(devices, hardware);
                self.clear_latched |= flags::INIT_DONE;
                self.write_flags(devices);
            }
            self.master.reset();
            return;
        }
        self.master.read(devices, dt_us);
        if let Ok(live) = live_settings(&Block::new(devices, self.operands.block), &self.operands) {
            self.live = Some(live);
        }
        let level = devices.bit(self.operands.start).unwrap_or(false);
        let edge = level && !self.start_level;
        self.start_level = level;

        let start_register = Block::new(devices, self.operands.block).word(offsets::START);
        match self.gate.observe(start_register, now_us) {
            GateAction::Hold => {}
            GateAction::Stop => {
                self.stop_now(devices, hardware);
                self.clear_latched |= flags::INIT_DONE;
            }
            GateAction::Start(mode) => self.start(mode, devices, hardware),
        }
        if let Phase::Ready {
            ready_at,
            announced,
            ..
        } = &mut self.phase
            && now_us >= *ready_at
        {
            if !*announced {
                self.set_latched |= flags::INIT_DONE;
                *announced = true;
            }
            if edge {
                self.trigger(devices, hardware);
            }
        }
        if matches!(self.phase, Phase::Running(_)) {
            self.follow(devices, hardware, now_us, dt_us);
        } else {
            self.sync.release(devices);
            let _ = devices.set_word(self.operands.reg(offsets::MASTER_REMAINING), 0);
        }
        self.write_flags(devices);
    }

    /// Accepts a mode from the start register when the block is valid, the
    /// output is not held by its stop flag and no other instruction drives
    /// the output (PLSY/DPLSY or another DECAM: the FX allows one driver per
    /// pulse output); otherwise the start waits and is taken as soon as it
    /// can be, while the start register still asks for it.
    fn start(&mut self, mode: CamMode, devices: &mut Devices, hardware: &mut Hardware) {
        let output = self.operands.pulse_output;
        if self.error.is_some()
            || Hardware::output_stopped(devices, output)
            || !hardware.output_free_for(output, self.owner)
        {
            return;
        }
        let Some(setup) = self.setup.as_ref() else {
            return;
        };
        let start = Start {
            mode,
            external_start: setup.external_start,
        };
        self.gate.started(mode);
        self.cycle_done = false;
        self.runtime_fault = None;
        self.set_latched |= flags::INIT_DONE;
        self.clear_latched &= !flags::INIT_DONE;
        self.phase = Phase::Ready {
            start,
            ready_at: 0,
            announced: true,
        };
        if !start.external_start {
            self.trigger(devices, hardware);
        }
    }

    /// The start condition came: builds the engine axis and arms it. A start
    /// signal while the block is bad, or while another instruction drives
    /// the output (an external-start cam does not hold the output while it
    /// waits for S3), is ignored.
    fn trigger(&mut self, devices: &mut Devices, hardware: &mut Hardware) {
        if self.error.is_some() || !hardware.output_free_for(self.operands.pulse_output, self.owner)
        {
            return;
        }
        let (Some(setup), Phase::Ready { start, .. }) = (self.setup.as_ref(), &self.phase) else {
            return;
        };
        let block = Block::new(devices, self.operands.block);
        let origin = Origin {
            master_raw: i64::from(block.dword(offsets::MASTER_RAW)),
            slave_zoomed: i64::from(block.dword(offsets::SLAVE_ZOOMED)),
            output_counter: crate::special::D_PULSE_COUNT
                .get(usize::from(self.operands.pulse_output))
                .and_then(|&d| devices.dword(d).ok())
                .map_or(0, i64::from),
        };
        // The time base reads 0 at the start instant, so a start position
        // of 0 fires and a noncyclic cam engages at 0.
        self.master.restart_time_base();
        match Run::arm(
            *start,
            setup,
            origin,
            self.master.is_time_base(),
            self.master.position(),
        ) {
            Ok(run) => {
                self.phase = Phase::Running(Box::new(run));
                self.cycle_done = false;
                // Free for this instance: checked on entry.
                hardware.claim_output(self.operands.pulse_output, self.owner);
            }
            Err(e) => {
                // The block checks rule out every refusal the engine knows;
                // should one slip through, report it like a parameter error.
                self.error = Some(BlockError::Parameter {
                    offset: offsets::FUNCTION,
                    reason: engine_refusal(e),
                });
                self.phase = Phase::Done;
            }
        }
    }

    /// One engine tick while armed, following or sending owed pulses.
    fn follow(&mut self, devices: &mut Devices, hardware: &mut Hardware, now_us: u64, dt_us: u32) {
        let output = self.operands.pulse_output;
        if Hardware::output_stopped(devices, output) {
            // M8145…: stop at once; the start register must go through 0.
            self.stop_now(devices, hardware);
            self.phase = Phase::Done;
            return;
        }
        let MasterPosition {
            counts: master,
            fraction,
        } = self.master.current();
        let live = self.live;
        let Phase::Running(run) = &mut self.phase else {
            return;
        };
        let out = run.tick(master, fraction, dt_us, live);
        let pulses =
            i32::try_from(out.pulses).unwrap_or(if out.pulses < 0 { i32::MIN } else { i32::MAX });
        if pulses != 0 {
            record_pulses(devices, hardware, self.owner, output, pulses);
            let _ = devices.set_bit(self.operands.direction, pulses > 0);
        }
        if out.events.cycle_completed {
            self.set_latched |= flags::CYCLE_COMPLETE;
        }
        if let Some(fault) = out.fault {
            self.runtime_fault = Some(fault);
            self.fault_to_report = Some(fault);
        }
        let reg = |offset| self.operands.reg(offset);
        let remaining = run.master_remaining();
        let _ = devices.set_word(reg(offsets::MASTER_REMAINING), remaining.min(32767) as i16);
        let engaged = out.state.is_engaged() || out.events.finished || out.events.stopped;
        if engaged {
            let _ = devices.set_dword(reg(offsets::SLAVE_ZOOMED), out.slave as i32);
            let _ = devices.set_dword(reg(offsets::SLAVE_RAW), out.slave_unzoomed as i32);
            let _ = devices.set_dword(reg(offsets::MASTER_ZOOMED), out.master_in_cycle as i32);
            let _ = devices.set_dword(reg(offsets::MASTER_RAW), out.master_in_cycle_raw as i32);
        }
        match live {
            Some(l) if l.sync_enabled => {
                self.sync
                    .drive(devices, Some(l.sync_output), run.in_sync(live))
            }
            _ => self.sync.release(devices),
        }
        if !run.over() {
            return;
        }
        // A cam the engine had to stop did not finish: no bit 9, no re-arm.
        let faulted = self.runtime_fault.is_some();
        let start = run.start;
        let rearm = start.mode == CamMode::Noncyclic
            && start.external_start
            && !run.stop_requested
            && !faulted;
        hardware.release_output(output, self.owner);
        self.cycle_done = !faulted;
        self.sync.release(devices);
        if start.mode == CamMode::Noncyclic {
            // Section 4.2.1 step 4: the controller clears bit 0 when the run ends.
            self.clear_latched |= flags::INIT_DONE;
            self.set_latched &= !flags::INIT_DONE;
        }
        self.phase = if rearm {
            Phase::Ready {
                start,
                ready_at: now_us.saturating_add(NONCYCLIC_REARM_US),
                announced: false,
            }
        } else {
            Phase::Done
        };
    }

    /// Immediate stop: the slave holds where it is, outputs are released.
    fn stop_now(&mut self, devices: &mut Devices, hardware: &mut Hardware) {
        hardware.release_output(self.operands.pulse_output, self.owner);
        self.sync.release(devices);
        self.phase = Phase::Idle;
    }

    /// Rewrites the flag register: bits 0 and 1 keep what the program left
    /// (plus this tick's set/clear), the others show the current state.
    fn write_flags(&mut self, devices: &mut Devices) {
        let reg = self.operands.reg(offsets::FLAGS);
        let old = devices.word(reg).map_or(0, |w| w as u16);
        let mut value = old & flags::LATCHED;
        value |= self.set_latched;
        value &= !self.clear_latched;
        self.set_latched = 0;
        self.clear_latched = 0;
        match &self.error {
            // The running cam keeps its last good table and settings: an
            // immediate stop would be a velocity step (docs/plc.md, "Errors").
            Some(_) if self.run().is_some() => value |= flags::KEPT_LAST_GOOD,
            Some(e) => value |= e.flag_bits(),
            None => {}
        }
        if self.runtime_fault.is_some() {
            value |= flags::ERROR;
        }
        if self.run().is_some_and(|run| run.status().pulse_delayed) {
            value |= flags::PULSE_DELAYED;
        }
        match self.gate.active() {
            Some(CamMode::Cyclic) => value |= flags::CYCLIC,
            Some(CamMode::Noncyclic) => value |= flags::NONCYCLIC,
            None => {}
        }
        if self.cycle_done {
            value |= flags::CURRENT_CYCLE_COMPLETE;
        }
        if self.run().is_some_and(|run| run.in_sync(self.live)) {
            value |= flags::IN_SYNC_AREA;
        }
        if self.master.is_time_base() {
            value |= flags::TIME_BASE;
        }
        let _ = devices.set_word(reg, value as i16);
    }
}

/// Offsets 4 and 8–12, plus the one rule that needs the operands: the sync
/// terminal must not be the cam's own pulse (D1) or direction (D2) output,
/// whose level the sync signal would overwrite.
fn live_settings(block: &Block<'_>, operands: &DecamOperands) -> Result<LiveSettings, BlockError> {
    let live = block.live()?;
    if live.sync_enabled {
        let sync = crate::device::Device::Y(live.sync_output);
        if sync == crate::device::Device::Y(u16::from(operands.pulse_output))
            || sync == operands.direction
        {
            return Err(BlockError::Parameter {
                offset: offsets::SYNC_OUTPUT,
                reason: "sync output is the cam's own pulse (D1) or direction (D2) output: use another Y",
            });
        }
    }
    Ok(live)
}

fn engine_refusal(e: ecam_engine::EngineError) -> &'static str {
    match e {
        ecam_engine::EngineError::BadZoom => "zoom terms must be 1-65535",
        ecam_engine::EngineError::EmptyCycle => "the table's last master must exceed its first",
        _ => "the cam engine refused this configuration",
    }
}

impl core::fmt::Debug for Decam {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Decam")
            .field("operands", &self.operands)
            .field("enabled", &self.enabled)
            .field("mode", &self.gate.active())
            .field("phase", &self.phase)
            .field("error", &self.error)
            .finish_non_exhaustive()
    }
}
