//! Nanoseconds per axis-tick for 1, 8 and 64 axes following a repeat cam
//! with a moving master (one cycle of the engine each, including the pulse
//! generator and sync windows). Criterion reports the mean per iteration
//! (all N axes; its throughput line counts axes). In real time the worst
//! case matters too, so after Criterion a plain loop times every single
//! tick and prints the mean and the worst.

#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use ecam_core::PointTable;
use ecam_engine::{AxisConfig, CamAxis, Coupling, SlaveAlign, SyncWindow, TickInput, Zoom};

fn table() -> PointTable {
    // 361 points: a sine-like cam over 36000 master counts, stroke 10000.
    let pairs: Vec<(i64, i64)> = (0..=360)
        .map(|i| {
            let m = i * 100;
            let u = i as f64 / 360.0;
            let s = 10000.0 * u - 800.0 * (u * std::f64::consts::TAU).sin();
            (m, s.round() as i64)
        })
        .collect();
    PointTable::from_pairs(&pairs).unwrap()
}

fn axes(n: usize) -> Vec<CamAxis<PointTable>> {
    (0..n)
        .map(|i| {
            let config = AxisConfig {
                coupling: Coupling::Repeat { min_stroke: 1 },
                slave_align: SlaveAlign::Relative,
                master_zoom: Zoom::new(7, 3).unwrap(),
                slave_zoom: Zoom::new(5, 4).unwrap(),
                sync_windows: [
                    SyncWindow::new(1000, 2000),
                    SyncWindow::new(10_000 + i as i64, 20_000),
                    SyncWindow::OFF,
                    SyncWindow::OFF,
                ],
                ..AxisConfig::default()
            };
            let mut axis = CamAxis::new(table(), config).unwrap();
            axis.arm().unwrap();
            let _ = axis.tick(&TickInput::at(0, 100));
            axis
        })
        .collect()
}

fn bench_axis_tick(c: &mut Criterion) {
    let mut group = c.benchmark_group("axis_tick");
    for n in [1usize, 8, 64] {
        let mut all = axes(n);
        let mut master = 0i64;
        group.throughput(Throughput::Elements(n as u64));
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| {
                // 13 counts per 100 µs tick: continuous motion, cursor hits.
                master += 13;
                let input = TickInput::at(master, 100);
                for axis in all.iter_mut() {
                    black_box(axis.tick(black_box(&input)));
                }
            })
        });
    }
    group.finish();

    let mut jumps = c.benchmark_group("axis_tick_jump");
    let mut all = axes(1);
    let mut master = 0i64;
    jumps.bench_function("1", |b| {
        b.iter(|| {
            // A large jump every tick: binary search in the table.
            master += 123_457;
            black_box(all[0].tick(black_box(&TickInput::at(master, 100))));
        })
    });
    jumps.finish();
}

/// Times each control cycle of N axes separately and prints mean and worst
/// per axis-tick (the worst includes whatever the OS did meanwhile).
fn worst_case() {
    const TICKS: u32 = 50_000;
    for n in [1usize, 8, 64] {
        let mut all = axes(n);
        let mut master = 0i64;
        let mut worst = Duration::ZERO;
        let mut total = Duration::ZERO;
        for _ in 0..TICKS {
            master += 13;
            let input = TickInput::at(master, 100);
            let start = Instant::now();
            for axis in all.iter_mut() {
                black_box(axis.tick(black_box(&input)));
            }
            let took = start.elapsed();
            total += took;
            worst = worst.max(took);
        }
        let per_axis = |d: Duration| d.as_nanos() as f64 / n as f64;
        println!(
            "axis_tick/{n}: mean {:.1} ns per axis-tick, worst cycle {:.1} ns per axis-tick ({TICKS} cycles)",
            per_axis(total) / f64::from(TICKS),
            per_axis(worst)
        );
    }
}

criterion_group!(benches, bench_axis_tick);

fn main() {
    benches();
    // Only when benchmarking, not when `cargo test --benches` smoke-runs this.
    if std::env::args().any(|a| a == "--bench") {
        worst_case();
    }
    Criterion::default().configure_from_args().final_summary();
}
