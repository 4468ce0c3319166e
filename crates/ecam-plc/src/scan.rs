//! The PLC: a loaded program, its device memory and hardware, and the scan
//! cycle that runs them.
//!
//! A scan sets the run flags (M8000 on, M8001 off, M8002 on and M8003 off in
//! the first scan only) and the clocks M8011–M8014, executes the program top
//! to bottom, and reports each operation error the FX way: its code in D8067
//! and M8067 on, as the instruction fails (a later rung of the same scan
//! sees it). Both stay until the PLC is restarted (a new [`Plc`]) or the
//! program resets them, so a program can test M8067 at any later scan.

use crate::decam::{Decam, DecamOperands, MasterOperand};
use crate::device::Device;
use crate::devices::Devices;
use crate::hardware::Hardware;
use crate::il::{Instruction, MasterSpec, ParseError, Program};
use crate::interpreter::{Interpreter, LineError, Machine};
use crate::special::{M_CLOCKS, M_FIRST_SCAN, M_NOT_FIRST_SCAN, M_NOT_RUNNING, M_RUNNING};

/// A PLC with a program loaded, in RUN.
pub struct Plc {
    program: Program,
    interpreter: Interpreter,
    devices: Devices,
    hardware: Hardware,
    decams: Vec<Decam>,
    now_us: u64,
    scans: u64,
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
        Ok(Self {
            interpreter: Interpreter::new(&program),
            program,
            devices: Devices::new(),
            hardware: Hardware::new(),
            decams,
            now_us: 0,
            scans: 0,
        })
    }

    /// True while a DECAM whose register block starts at `D{block}` is
    /// armed or following its cam (a table written there now takes over
    /// at the next seam, see docs/plc.md).
    pub fn cam_running(&self, block: u16) -> bool {
        self.decams
            .iter()
            .any(|d| d.operands().block == block && d.is_running())
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
    /// errors it raised (also written to D8067/M8067).
    pub fn scan(&mut self) -> Vec<LineError> {
        let first = self.scans == 0;
        for (m, on) in [
            (M_RUNNING, true),
            (M_NOT_RUNNING, false),
            (M_FIRST_SCAN, first),
            (M_NOT_FIRST_SCAN, !first),
        ] {
            // Special relays are inside M0-M8511 by construction.
            let _ = self.devices.set_bit(Device::M(m), on);
        }
        for (m, period_us) in M_CLOCKS {
            let _ = self
                .devices
                .set_bit(Device::M(m), self.now_us % period_us < period_us / 2);
        }
        let mut machine = Machine {
            devices: &mut self.devices,
            hardware: &mut self.hardware,
            decams: &mut self.decams,
            now_us: self.now_us,
        };
        // The interpreter writes D8067/M8067 as each instruction fails.
        let errors = self.interpreter.scan(&self.program, &mut machine);
        self.scans += 1;
        errors
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
