//! One CSP cycle for 1, 8 and 64 axes: every cam axis ticks, its drive's
//! controlword and target are packed into the process image, and the
//! inputs are unpacked back into the drive status (`csp_cycle`, the work
//! the master does per cycle besides the bus). `csp_exchange_emulated`
//! adds one real ethercrab exchange through the in-process emulated
//! segment (frame build, the emulation answering, frame parse), which is
//! an upper bound for the master-side frame handling, not a wire time.
//! After Criterion a plain loop times every single cycle and prints the
//! mean and the worst.

#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use ecam_core::PointTable;
use ecam_core::generator::rotary_cut::{Params, generate};
use ecam_engine::drive::AxisDrive;
use ecam_engine::{AxisConfig, CamAxis, Coupling, SlaveAlign, TickInput};
use ecam_ethercat::Cia402Drive;
use ecam_ethercat::cia402::Request;
use ecam_ethercat::emulation::{DriveBehaviour, EmulatedSegment};
use ecam_ethercat::line::{CamDrive, CamLine, LineState, Master};
use ecam_ethercat::pdo::{CspInputs, INPUTS_LEN, OUTPUTS_LEN};
use ecam_ethercat::{Segment, SegmentConfig, Transport};

fn knife() -> CamAxis<PointTable> {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        slave_align: SlaveAlign::Relative,
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(generate(&Params::default()).unwrap().table, config).unwrap();
    axis.arm().unwrap();
    axis
}

/// N axes, N drives already reporting "operation enabled", and a process
/// image laid out as ethercrab lays it (inputs first, then outputs).
struct Cycle {
    axes: Vec<CamAxis<PointTable>>,
    drives: Vec<Cia402Drive>,
    image: Vec<u8>,
    master: i64,
    n: usize,
}

impl Cycle {
    fn new(n: usize) -> Self {
        let mut drives = vec![Cia402Drive::new(); n];
        let enabled = CspInputs {
            statusword: 0x1237,
            ..CspInputs::default()
        };
        for d in &mut drives {
            d.set_request(Request::Operate);
            d.update(Some(enabled));
        }
        let mut image = vec![0u8; n * (INPUTS_LEN + OUTPUTS_LEN)];
        for i in 0..n {
            enabled
                .pack(&mut image[i * INPUTS_LEN..(i + 1) * INPUTS_LEN])
                .unwrap();
        }
        Self {
            axes: (0..n).map(|_| knife()).collect(),
            drives,
            image,
            master: 0,
            n,
        }
    }

    fn run(&mut self) {
        self.master += 7;
        let input = TickInput::at(self.master, 1000);
        let outputs_at = self.n * INPUTS_LEN;
        for (i, (axis, drive)) in self.axes.iter_mut().zip(&mut self.drives).enumerate() {
            let out = axis.tick(black_box(&input));
            drive.command(out.slave, 1000);
            let at = outputs_at + i * OUTPUTS_LEN;
            drive
                .outputs()
                .pack(&mut self.image[at..at + OUTPUTS_LEN])
                .unwrap();
        }
        for (i, drive) in self.drives.iter_mut().enumerate() {
            let inputs =
                CspInputs::unpack(&self.image[i * INPUTS_LEN..(i + 1) * INPUTS_LEN]).unwrap();
            drive.update(Some(inputs));
            black_box(drive.status());
        }
    }
}

fn running_line(n: usize) -> CamLine<PointTable> {
    let emulation = Arc::new(Mutex::new(EmulatedSegment::new(
        n,
        DriveBehaviour::default(),
    )));
    let config = SegmentConfig {
        dc_static_sync_iterations: 10,
        ..SegmentConfig::default()
    };
    let segment = Segment::bring_up(Transport::Emulated(emulation), config).unwrap();
    let axes = (0..n)
        .map(|drive| CamDrive {
            axis: knife(),
            drive,
            master: Master::Virtual,
        })
        .collect();
    let mut line = CamLine::new(segment, axes, 100, Duration::ZERO).unwrap();
    line.virtual_speed = 7;
    line.start().unwrap();
    while line.state() != LineState::Running {
        line.cycle().unwrap();
    }
    line
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("csp_cycle");
    for n in [1usize, 8, 64] {
        let mut cycle = Cycle::new(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_function(BenchmarkId::from_parameter(n), |b| b.iter(|| cycle.run()));
    }
    group.finish();
    let mut group = c.benchmark_group("csp_exchange_emulated");
    for n in [1usize, 8, 64] {
        let mut line = running_line(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| black_box(line.cycle().unwrap()))
        });
    }
    group.finish();
}

/// Times every cycle and prints mean and worst per cycle.
fn worst_case() {
    const CYCLES: u32 = 50_000;
    for n in [1usize, 8, 64] {
        let mut cycle = Cycle::new(n);
        let mut worst = Duration::ZERO;
        let mut total = Duration::ZERO;
        for _ in 0..CYCLES {
            let start = Instant::now();
            cycle.run();
            let took = start.elapsed();
            total += took;
            worst = worst.max(took);
        }
        println!(
            "csp_cycle/{n}: mean {:.2} µs per cycle, worst {:.2} µs ({CYCLES} cycles)",
            total.as_secs_f64() * 1e6 / f64::from(CYCLES),
            worst.as_secs_f64() * 1e6
        );
    }
}

criterion_group!(benches, bench);

fn main() {
    benches();
    if std::env::args().any(|a| a == "--bench") {
        worst_case();
    }
    Criterion::default().configure_from_args().final_summary();
}
