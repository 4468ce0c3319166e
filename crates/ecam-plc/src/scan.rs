//! The PLC: a loaded program, its device memory and hardware, and the scan
//! cycle that runs them.
//!
//! A scan sets the run flags (M8000 on, M8001 off, M8002 on and M8003 off in
//! the first scan only) and the clocks M8011–M8014, executes the program top
//! to bottom, and reports each operation error the FX way: its code in D8067
//! and M8067 on, as the instruction fails (a later rung of the same scan
//! sees it). Both stay until the PLC is restarted (a new [`Plc`]) or the
//! program resets them, so a program can test M8067 at any later scan.
//!
//! Each scan is timed against the watchdog time D8000 ([`crate::watchdog`]):
//! D8010–D8012 give the scan times, and a scan over D8000 stops the
//! program (the PLC is then [`Plc::fault`]ed until it is started again).

use crate::decam::{Decam, DecamOperands, MasterOperand};
use crate::device::Device;
use crate::devices::Devices;
use crate::hardware::Hardware;
use crate::hardware::{OutputOwner, PULSE_OUTPUTS};
use crate::il::{Instruction, MasterSpec, ParseError, Program};
use crate::interpreter::{Interpreter, LineError, Machine};
use crate::special::{
    D_ERROR, D_HARDWARE_ERROR, D_SCAN_TIME, D_WATCHDOG, M_CLOCKS, M_ERROR, M_FIRST_SCAN,
    M_HARDWARE_ERROR, M_NOT_FIRST_SCAN, M_NOT_RUNNING, M_RUNNING,
};
use crate::watchdog::{self, DEFAULT_WATCHDOG_MS, Fault, ModeledScanTime, ScanTimer};

/// A PLC with a program loaded: in RUN until a fault stops it.
pub struct Plc {
    program: Program,
    interpreter: Interpreter,
    devices: Devices,
    hardware: Hardware,
    decams: Vec<Decam>,
    now_us: u64,
    scans: u64,
    /// Times each scan for the watchdog and D8010–D8012.
    timer: Box<dyn ScanTimer>,
    /// Instructions the last scan executed.
    last_steps: u64,
    /// Shortest and longest scan so far, µs.
    scan_range_us: Option<(u64, u64)>,
    /// What stopped the program, if anything did.
    fault: Option<Fault>,
}

impl Plc {
    /// Loads `program` with zeroed device memory and idle hardware, and
    /// creates one E-cam instance per DECAM instruction.
    ///
    /// # Errors
    /// A DECAM whose operands the E-cam face refuses, with its line.
    ///
    /// ```
    /// let program = ecam_plc::Program::parse("LD M8000\nMOV K7 D0\n", "demo.il").unwrap();
    /// let mut plc = ecam_plc::Plc::new(program).unwrap();
    /// plc.scan();
    /// assert_eq!(plc.devices().word(0), Ok(7));
    /// ```
    pub fn new(program: Program) -> Result<Self, ParseError> {
        let mut decams = Vec::new();
        for statement in &program.statements {
            if let Instruction::Decam {
                master,
                block,
                start,
                pulse_output,
                direction,
            } = statement.instruction
            {
                let master = match master {
                    MasterSpec::Counter(n) => MasterOperand::Counter(n),
                    MasterSpec::Register(n) => MasterOperand::Register(n),
                    MasterSpec::TimeBase(k) => MasterOperand::TimeBase(k),
                };
                let operands = DecamOperands::new(master, block, start, pulse_output, direction)
                    .map_err(|err| ParseError {
                        file: program.file.clone(),
                        line: statement.line,
                        problem: crate::il::ParseProblem::Decam(err),
                    })?;
                decams.push(Decam::new(operands));
            }
        }
        let mut devices = Devices::new();
        // Set at power-on, as the FX's system does.
        let _ = devices.set_word(D_WATCHDOG, DEFAULT_WATCHDOG_MS as i16);
        Ok(Self {
            interpreter: Interpreter::new(&program),
            program,
            devices,
            hardware: Hardware::new(),
            decams,
            now_us: 0,
            scans: 0,
            timer: Box::new(ModeledScanTime),
            last_steps: 0,
            scan_range_us: None,
            fault: None,
        })
    }

    /// Times scans with `timer` from now on (the default,
    /// [`ModeledScanTime`], counts instructions; a real-time server
    /// measures the CPU time the scan takes).
    pub fn set_scan_timer(&mut self, timer: Box<dyn ScanTimer>) {
        self.timer = timer;
    }

    /// What stopped the program (the watchdog), if anything did: the
    /// program no longer runs, every output is off, and M8061/D8061 say
    /// why, until the PLC is started again.
    pub fn fault(&self) -> Option<&Fault> {
        self.fault.as_ref()
    }

    /// Instructions the last scan executed (a run's work, see
    /// `ecam_core::budget`).
    pub fn last_scan_steps(&self) -> u64 {
        self.last_steps
    }

    /// True while a DECAM whose register block starts at `D{block}` is
    /// armed or following its cam (a table written there now takes over
    /// at the next seam, see docs/plc.md).
    pub fn cam_running(&self, block: u16) -> bool {
        self.decams
            .iter()
            .any(|d| d.operands().block == block && d.is_running())
    }

    /// The register blocks (`D{block}`) of the DECAMs armed or following
    /// their cam now.
    pub fn running_cams(&self) -> impl Iterator<Item = u16> + '_ {
        self.decams
            .iter()
            .filter(|d| d.is_running())
            .map(|d| d.operands().block)
    }

    /// The master span of the table the cam at `D{block}` follows while it
    /// runs: its cycle length in table counts, which a table written into
    /// the block changes only at the next seam. `None` while no cam runs
    /// there.
    pub fn cam_table_span(&self, block: u16) -> Option<i64> {
        self.decams
            .iter()
            .filter(|d| d.operands().block == block)
            .find_map(Decam::running_table_span)
    }

    /// The program's DECAM instances, in program order.
    pub(crate) fn decams(&self) -> &[Decam] {
        &self.decams
    }

    /// Device memory.
    pub fn devices(&self) -> &Devices {
        &self.devices
    }

    /// Device memory, to set inputs and registers from outside.
    pub fn devices_mut(&mut self) -> &mut Devices {
        &mut self.devices
    }

    /// Pulse outputs, counters and wires.
    pub fn hardware(&self) -> &Hardware {
        &self.hardware
    }

    /// Mutable hardware (to add wires).
    pub fn hardware_mut(&mut self) -> &mut Hardware {
        &mut self.hardware
    }

    /// The loaded program.
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// Simulated time in µs.
    pub fn now_us(&self) -> u64 {
        self.now_us
    }

    /// Number of scans run so far.
    pub fn scans(&self) -> u64 {
        self.scans
    }

    /// Runs one program scan at the current time and returns the operation
    /// errors it raised (also written to D8067/M8067). A scan that runs
    /// past the watchdog time stops the program ([`Plc::fault`]); once
    /// stopped, a scan runs nothing (the clocks M8011–M8014 go on).
    pub fn scan(&mut self) -> Vec<LineError> {
        let first = self.scans == 0;
        let running = self.fault.is_none();
        for (m, on) in [
            (M_RUNNING, running),
            (M_NOT_RUNNING, !running),
            (M_FIRST_SCAN, first && running),
            (M_NOT_FIRST_SCAN, !first && running),
        ] {
            // Special relays are inside M0-M8511 by construction.
            let _ = self.devices.set_bit(Device::M(m), on);
        }
        for (m, period_us) in M_CLOCKS {
            let _ = self
                .devices
                .set_bit(Device::M(m), self.now_us % period_us < period_us / 2);
        }
        if !running {
            self.last_steps = 0;
            return Vec::new();
        }
        let limit_us = watchdog::limit_us(self.devices.word(D_WATCHDOG).unwrap_or(0));
        let mut machine = Machine {
            devices: &mut self.devices,
            hardware: &mut self.hardware,
            decams: &mut self.decams,
            now_us: self.now_us,
        };
        let timer = &mut self.timer;
        timer.start();
        // The interpreter writes D8067/M8067 as each instruction fails.
        let outcome = self
            .interpreter
            .scan(&self.program, &mut machine, &mut |steps| {
                timer.elapsed_us(steps) > limit_us
            });
        let scan_us = self.timer.elapsed_us(outcome.steps);
        self.last_steps = outcome.steps;
        self.scans += 1;
        self.show_scan_time(scan_us);
        if let Some(line) = outcome.overrun_at {
            self.stop(Fault::Watchdog {
                line,
                scan_us,
                limit_ms: limit_us / 1000,
            });
        }
        outcome.errors
    }

    /// D8010–D8012: this scan's time, the shortest and the longest, 0.1 ms.
    fn show_scan_time(&mut self, scan_us: u64) {
        let (low, high) = self.scan_range_us.map_or((scan_us, scan_us), |(l, h)| {
            (l.min(scan_us), h.max(scan_us))
        });
        self.scan_range_us = Some((low, high));
        for (register, us) in D_SCAN_TIME.into_iter().zip([scan_us, low, high]) {
            let tenths = i16::try_from(us / 100).unwrap_or(i16::MAX);
            let _ = self.devices.set_word(register, tenths);
        }
    }

    /// Stops the program the FX way after an error: every output off, the
    /// pulse outputs and cams stopped, the error's flag and code set.
    fn stop(&mut self, fault: Fault) {
        for y in 0..crate::device::XY_COUNT {
            let _ = self.devices.set_bit(Device::Y(y), false);
        }
        for output in 0..PULSE_OUTPUTS as u8 {
            if let Some(owner @ OutputOwner::PulseTrain(_)) = self.hardware.owner(output) {
                self.hardware.release_output(output, owner);
            }
        }
        for decam in &mut self.decams {
            // Its power flow off: the next hardware tick stops the cam.
            let _ = decam.execute(false, &mut self.devices, self.now_us);
        }
        for (m, on) in [
            (M_RUNNING, false),
            (M_NOT_RUNNING, true),
            (M_HARDWARE_ERROR, true),
            (M_ERROR, true),
        ] {
            let _ = self.devices.set_bit(Device::M(m), on);
        }
        let _ = self.devices.set_word(D_HARDWARE_ERROR, fault.code() as i16);
        let _ = self.devices.set_word(D_ERROR, M_HARDWARE_ERROR as i16);
        self.fault = Some(fault);
    }

    /// One hardware tick of `dt_us`: pulse trains emit, every E-cam instance
    /// ticks (program order), counters sample their inputs and the busy flags
    /// settle; then the clock advances.
    pub fn hardware_tick(&mut self, dt_us: u32) {
        self.hardware.tick_pulse_trains(&mut self.devices, dt_us);
        for decam in &mut self.decams {
            decam.hardware_tick(&mut self.devices, &mut self.hardware, self.now_us, dt_us);
        }
        self.hardware.end_tick(&mut self.devices);
        self.now_us = self.now_us.saturating_add(u64::from(dt_us));
    }
}
