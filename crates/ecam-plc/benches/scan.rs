//! Speed of the PLC simulation: one second of simulated time (1000 scans,
//! 10 000 hardware ticks) of a loopback program, and one scan of a long
//! straight-line program.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use criterion::{Criterion, criterion_group, criterion_main};
use ecam_plc::Plc;
use ecam_plc::Program;
use ecam_plc::Wire;
use ecam_plc::sim::{RunLength, Timing, run};

const LOOPBACK: &str = "LD M8000\nOUT C231 K2147483647\nDPLSY K100000 K0 Y1\nLD C231\nOUT Y7\n";

fn one_simulated_second(c: &mut Criterion) {
    let program = Program::parse(LOOPBACK, "bench.il").unwrap();
    c.bench_function("plc loopback, 1 s simulated", |b| {
        b.iter(|| {
            let mut plc = Plc::new(program.clone()).unwrap();
            plc.hardware_mut().add_wire(Wire::parse("Y1:X0").unwrap());
            run(&mut plc, Timing::default(), RunLength::Millis(1000), |_| {}).unwrap();
            plc.devices().counter(231).unwrap()
        });
    });
}

fn one_long_scan(c: &mut Criterion) {
    let mut source = String::from("LD M8000\n");
    for i in 0..1000 {
        source.push_str(&format!("ADD D{i} K1 D{i}\nCMP D{i} K100 M{}\n", i * 3));
    }
    let mut plc = Plc::new(Program::parse(&source, "bench.il").unwrap()).unwrap();
    c.bench_function("plc scan, 2000 applied instructions", |b| {
        b.iter(|| plc.scan().len())
    });
}

criterion_group!(benches, one_simulated_second, one_long_scan);
criterion_main!(benches);
