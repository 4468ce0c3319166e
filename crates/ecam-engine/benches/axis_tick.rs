//! Nanoseconds per axis-tick for 1, 8 and 64 axes following a repeat cam
//! (513 points, both zooms, two sync windows) with a moving master: one
//! cycle of the engine each, pulse generator and sync windows included,
//! beside the minimal loop (`common/minimal.rs`), the same work written by
//! hand, which is the honest limit. Criterion reports the mean per
//! iteration (all N axes; its throughput line counts axes). In real time
//! the worst case matters too, so after Criterion a plain loop times every
//! single tick and prints the mean and the worst.
//! `scripts/bench-side-by-side` prints the same comparison as JSON lines.

#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use ecam_engine::TickInput;

fn bench_axis_tick(c: &mut Criterion) {
    let table = common::stroke_table().unwrap();
    let mut group = c.benchmark_group("axis_tick");
    for n in [1usize, 8, 64] {
        let mut all = common::axes(&table, n);
        let mut master = 0i64;
        group.throughput(Throughput::Elements(n as u64));
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| {
                // 13 counts per 100 µs tick: continuous motion, cursor hits.
                master += common::MASTER_PER_TICK;
                let input = TickInput::at(master, common::DT_US);
                for axis in all.iter_mut() {
                    black_box(axis.tick(black_box(&input)));
                }
            })
        });
    }
    group.finish();

    let mut minimal = c.benchmark_group("minimal_tick");
    for n in [1usize, 64] {
        let mut all = common::minimal_axes(&table, n);
        let mut master = 0i64;
        minimal.throughput(Throughput::Elements(n as u64));
        minimal.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| {
                master += common::MASTER_PER_TICK;
                for axis in all.iter_mut() {
                    black_box(axis.tick(black_box(master)));
                }
            })
        });
    }
    minimal.finish();

    let mut jumps = c.benchmark_group("axis_tick_jump");
    let mut all = common::axes(&table, 1);
    let mut master = 0i64;
    jumps.bench_function("1", |b| {
        b.iter(|| {
            // A large jump every tick: binary search in the table.
            master += 123_457;
            black_box(all[0].tick(black_box(&TickInput::at(master, common::DT_US))));
        })
    });
    jumps.finish();
}

/// Times each control cycle of N axes separately and prints mean and worst
/// per axis-tick (the worst includes whatever the OS did meanwhile).
fn worst_case() {
    const TICKS: u32 = 50_000;
    let table = common::stroke_table().unwrap();
    for n in [1usize, 8, 64] {
        let mut all = common::axes(&table, n);
        let mut master = 0i64;
        let mut worst = Duration::ZERO;
        let mut total = Duration::ZERO;
        for _ in 0..TICKS {
            master += common::MASTER_PER_TICK;
            let input = TickInput::at(master, common::DT_US);
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
