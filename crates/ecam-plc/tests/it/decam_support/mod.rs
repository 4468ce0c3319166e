//! A test rig around one DECAM instruction: device memory, hardware, a
//! master in D10/D11 the test moves, block at D2000, output Y0, direction Y4,
//! start signal M100, scans every 1 ms and hardware ticks of 100 µs.
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Hardware;
use ecam_plc::OperationError;
use ecam_plc::decam::{Decam, DecamOperands, MasterOperand};
use ecam_plc::{Device, Devices};

pub const BLOCK: u16 = 2000;
pub const MASTER: u16 = 10;
pub const START: Device = Device::M(100);

pub struct Rig {
    pub dev: Devices,
    pub hw: Hardware,
    pub cam: Decam,
    pub now: u64,
    pub tick_us: u32,
    pub master: i64,
    pub enabled: bool,
    /// Errors returned by `execute`, in order.
    pub errors: Vec<OperationError>,
}

impl Rig {
    /// A rig whose block holds `table`, cam not started.
    pub fn new(table: &[(i32, i32)]) -> Self {
        Self::with_master(table, MasterOperand::Register(MASTER))
    }

    pub fn with_master(table: &[(i32, i32)], master: MasterOperand) -> Self {
        let ops = DecamOperands::new(master, BLOCK, START, 0, Device::Y(4)).unwrap();
        let mut rig = Self {
            dev: Devices::new(),
            hw: Hardware::new(),
            cam: Decam::new(ops),
            now: 0,
            tick_us: 100,
            master: 0,
            enabled: true,
            errors: Vec::new(),
        };
        rig.set_table(table);
        rig
    }

    pub fn set_table(&mut self, table: &[(i32, i32)]) {
        self.set(38, table.len() as i16);
        for (i, &(m, s)) in table.iter().enumerate() {
            let at = 40 + 4 * i as u16;
            self.set_d(at, m);
            self.set_d(at + 2, s);
        }
    }

    pub fn set(&mut self, offset: u16, value: i16) {
        self.dev.set_word(BLOCK + offset, value).unwrap();
    }

    pub fn set_d(&mut self, offset: u16, value: i32) {
        self.dev.set_dword(BLOCK + offset, value).unwrap();
    }

    pub fn reg(&self, offset: u16) -> i16 {
        self.dev.word(BLOCK + offset).unwrap()
    }

    pub fn reg_d(&self, offset: u16) -> i32 {
        self.dev.dword(BLOCK + offset).unwrap()
    }

    pub fn flags(&self) -> u16 {
        self.reg(1) as u16
    }

    pub fn flag(&self, bit: u16) -> bool {
        self.flags() & (1 << bit) != 0
    }

    /// Y0's pulse counter D8140/D8141.
    pub fn pulses(&self) -> i32 {
        self.dev.dword(8140).unwrap()
    }

    pub fn y(&self, n: u16) -> bool {
        self.dev.bit(Device::Y(n)).unwrap()
    }

    pub fn set_bit(&mut self, device: Device, on: bool) {
        self.dev.set_bit(device, on).unwrap();
    }

    /// One program scan (the DECAM instruction's execution).
    pub fn scan(&mut self) {
        if let Err(e) = self.cam.execute(self.enabled, &mut self.dev, self.now) {
            self.errors.push(e);
        }
    }

    /// One hardware tick with the master moved by `step` counts first.
    pub fn tick(&mut self, step: i64) {
        self.master += step;
        self.dev.set_dword(MASTER, self.master as i32).unwrap();
        self.now += u64::from(self.tick_us);
        let (now, dt) = (self.now, self.tick_us);
        self.cam.hardware_tick(&mut self.dev, &mut self.hw, now, dt);
        self.hw.end_tick(&mut self.dev);
    }

    /// `ticks` hardware ticks, a scan before every tenth (1 ms scan).
    pub fn run(&mut self, ticks: u32, step: i64) {
        for i in 0..ticks {
            if i % 10 == 0 {
                self.scan();
            }
            self.tick(step);
        }
    }

    /// Moves the master to `target` in steps of at most `step` (> 0), one tick each.
    pub fn run_to(&mut self, target: i64, step: i64) {
        let mut ticks = 0u32;
        while self.master != target {
            if ticks.is_multiple_of(10) {
                self.scan();
            }
            ticks += 1;
            let d = (target - self.master).clamp(-step, step);
            self.tick(d);
        }
    }

    /// Writes the start register and runs one scan and one tick.
    pub fn start(&mut self, mode: i16) {
        self.set(5, mode);
        self.scan();
        self.tick(0);
    }
}
