//! The CPU an EtherCAT cycle costs the master without the network, for
//! `scripts/bench-side-by-side` (`ethercat-cycle-N`): for 1, 8 and 64
//! drives, what `CamLine::cycle` does around the exchange, built from the
//! crate's public cycle pieces: every cam axis ticks against the virtual
//! master, its drive takes the command and packs its outputs into a process
//! image laid out as ethercrab lays it (inputs first, then outputs), the
//! inputs are unpacked into every drive's state machine, and the line's
//! supervisor looks at the drives. The inputs stand still (every drive
//! reports "operation enabled"); the frame itself, its trip and the
//! emulated drives' answers are not timed (`benches/csp_cycle.rs`
//! `csp_exchange_emulated` times an emulated exchange).
//!
//! Time is the thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`), so the time
//! this thread waits while others use the core is left out; it is read
//! around blocks of cycles, and the median block gives ns per cycle. One
//! JSON line per drive count, with the 250 µs cycle as the reference and
//! the ratio the fraction of it the work takes. Build with `--release`.

use std::hint::black_box;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use ecam_core::PointTable;
use ecam_core::generator::rotary_cut::{Params, generate};
use ecam_engine::drive::AxisDrive;
use ecam_engine::{AxisConfig, CamAxis, Coupling, SlaveAlign, TickInput, TickOutput};
use ecam_ethercat::emulation::{DriveBehaviour, EmulatedSegment};
use ecam_ethercat::line::LineState;
use ecam_ethercat::pdo::{CspInputs, INPUTS_LEN, OUTPUTS_LEN};
use ecam_ethercat::supervisor::{Supervisor, default_max_lost_cycles};
use ecam_ethercat::{CycleReport, Segment, SegmentConfig, Transport};
use nix::time::{ClockId, clock_gettime};

/// The cycle the figures are compared with.
const CYCLE: Duration = Duration::from_micros(250);
/// Virtual master counts per cycle.
const MASTER_PER_CYCLE: i64 = 7;

/// A rotary knife on a repeat cam, as the line examples run it.
fn knife() -> Result<CamAxis<PointTable>, String> {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        slave_align: SlaveAlign::Relative,
        ..AxisConfig::default()
    };
    let table = generate(&Params::default())
        .map_err(|e| format!("knife table: {e}"))?
        .table;
    CamAxis::new(table, config).map_err(|e| format!("knife axis: {e}"))
}

/// One line of `n` drives, its supervisor and a process image.
struct Line {
    segment: Segment,
    supervisor: Supervisor,
    axes: Vec<CamAxis<PointTable>>,
    outputs: Vec<TickOutput>,
    image: Vec<u8>,
    master: i64,
    dt_us: u32,
}

impl Line {
    fn new(n: usize) -> Result<Self, String> {
        let emulation = Arc::new(Mutex::new(EmulatedSegment::new(
            n,
            DriveBehaviour::default(),
        )));
        let config = SegmentConfig {
            cycle: CYCLE,
            dc_static_sync_iterations: 10,
            ..SegmentConfig::default()
        };
        let mut segment = Segment::bring_up(Transport::Emulated(emulation), config)
            .map_err(|e| format!("segment: {e}"))?;
        let mut supervisor =
            Supervisor::new((0..n).collect(), n, CYCLE, default_max_lost_cycles(CYCLE));
        supervisor
            .start(&mut segment)
            .map_err(|state| format!("start: line {state:?}"))?;
        let mut image = vec![0u8; n * (INPUTS_LEN + OUTPUTS_LEN)];
        let enabled = CspInputs {
            statusword: 0x1237,
            ..CspInputs::default()
        };
        for slot in image[..n * INPUTS_LEN].chunks_exact_mut(INPUTS_LEN) {
            enabled.pack(slot).map_err(|e| format!("image: {e}"))?;
        }
        let mut line = Self {
            segment,
            supervisor,
            axes: (0..n).map(|_| knife()).collect::<Result<_, _>>()?,
            outputs: Vec::with_capacity(n),
            image,
            master: 0,
            dt_us: u32::try_from(CYCLE.as_micros()).unwrap_or(u32::MAX),
        };
        // Until the line runs and every cam is engaged.
        for _ in 0..3 {
            line.cycle()?;
        }
        if line.supervisor.state() != LineState::Running {
            return Err(format!("line {:?}, not running", line.supervisor.state()));
        }
        Ok(line)
    }

    /// One cycle: master, cams, commands and outputs packed, inputs
    /// unpacked, supervision (with the exchange left out).
    fn cycle(&mut self) -> Result<(), String> {
        let running = self.supervisor.state() == LineState::Running;
        if running {
            self.master = self.master.saturating_add(MASTER_PER_CYCLE);
        }
        let n = self.axes.len();
        let (inputs, outputs) = self.image.split_at_mut(n * INPUTS_LEN);
        self.outputs.clear();
        let drives = self.segment.drives_mut();
        for ((axis, drive), slot) in self
            .axes
            .iter_mut()
            .zip(drives.iter_mut())
            .zip(outputs.chunks_exact_mut(OUTPUTS_LEN))
        {
            let out = axis.tick(&TickInput {
                master: black_box(self.master),
                dt_us: self.dt_us,
                output_enabled: running && drive.status().enabled,
                ..TickInput::default()
            });
            drive.command(out.slave, self.dt_us);
            drive
                .outputs()
                .pack(slot)
                .map_err(|e| format!("pack: {e}"))?;
            self.outputs.push(out);
        }
        for (drive, slot) in drives.iter_mut().zip(inputs.chunks_exact(INPUTS_LEN)) {
            let inputs = CspInputs::unpack(slot).map_err(|e| format!("unpack: {e}"))?;
            drive.update(Some(inputs));
        }
        let expected = u16::try_from(3 * n).unwrap_or(u16::MAX);
        let bus = CycleReport {
            working_counter: expected,
            expected_working_counter: expected,
            ..CycleReport::default()
        };
        let seen = self.supervisor.after_exchange(&mut self.segment, &bus);
        if seen.new_faults != 0 {
            return Err(format!("fault: {:?}", self.supervisor.new_faults()));
        }
        if seen.now_running {
            for (axis, drive) in self.axes.iter_mut().zip(self.segment.drives()) {
                axis.set_slave_position(drive.actual())
                    .map_err(|e| format!("slave: {e}"))?;
                axis.arm().map_err(|e| format!("arm: {e}"))?;
            }
        }
        black_box(&self.outputs);
        black_box(&self.image);
        Ok(())
    }
}

fn cpu_ns() -> Result<i64, String> {
    let t = clock_gettime(ClockId::CLOCK_THREAD_CPUTIME_ID).map_err(|e| format!("clock: {e}"))?;
    Ok(t.tv_sec() * 1_000_000_000 + t.tv_nsec())
}

/// Median CPU ns per cycle over `blocks` blocks of `per_block` cycles.
fn time(line: &mut Line, blocks: usize, per_block: usize) -> Result<f64, String> {
    let mut times = Vec::with_capacity(blocks);
    for _ in 0..blocks {
        let start = cpu_ns()?;
        for _ in 0..per_block {
            line.cycle()?;
        }
        times.push((cpu_ns()? - start) as f64 / per_block as f64);
    }
    times.sort_by(f64::total_cmp);
    Ok(times.get(times.len() / 2).copied().unwrap_or(f64::NAN))
}

fn main() -> Result<(), String> {
    let quick = std::env::args().any(|a| a == "--quick");
    let blocks = if quick { 51 } else { 301 };
    let budget = CYCLE.as_nanos() as f64;
    for n in [1usize, 8, 64] {
        let mut line = Line::new(n)?;
        // About a millisecond of work per block.
        let per_block = (1024 / n).max(8);
        let ns = time(&mut line, blocks, per_block)?;
        let engaged = line.axes.iter().all(|a| a.state().is_engaged());
        if !engaged {
            return Err(format!("{n} drives: a cam is not engaged"));
        }
        println!(
            "{{\"case\": \"ethercat-cycle-{n}\", \"ecam_ns\": {ns:.1}, \"reference\": \"the 250 us cycle\", \"reference_ns\": {budget:.1}, \"ratio\": {:.4}}}",
            ns / budget
        );
    }
    Ok(())
}
