//! Evaluation speed of a 512-section table: sequential (a master that moves
//! a little each tick, the engine's normal case) and random access (jumps,
//! which fall back to a binary search), and the batch API over a million
//! sorted masters.

// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use ecam_core::{
    CamCurve, CamPoint, CamTable, Cursor, MotionLaw, PointTable, Segment, SegmentProfile,
    UniformTable,
};
use std::hint::black_box;

const SECTIONS: i64 = 512;
const SPAN: i64 = 1_000_000;
const PROBES: usize = 10_000;

fn tables() -> Vec<(&'static str, CamTable)> {
    let profile = SegmentProfile::new(
        CamPoint::new(0, 0),
        (1..=SECTIONS)
            .map(|i| {
                let law = MotionLaw::ALL[(i as usize) % MotionLaw::ALL.len()];
                Segment::new(
                    i * SPAN / SECTIONS,
                    if i % 2 == 0 { 0 } else { 10_000 },
                    law,
                )
            })
            .collect(),
    )
    .map_err(|e| e.to_string());
    let Ok(profile) = profile else {
        return Vec::new();
    };
    let mut out = Vec::new();
    // 513 points = 512 sections, following the profile.
    let mut cursor = Cursor::new();
    let pairs: Vec<(i64, i64)> = (0..=SECTIONS)
        .map(|i| {
            let m = i * SPAN / SECTIONS;
            (m, profile.position(m as f64, &mut cursor).round() as i64)
        })
        .collect();
    if let Ok(points) = PointTable::from_pairs(&pairs) {
        out.push(("points", CamTable::Points(points)));
    }
    let values = (0..=SECTIONS).map(|i| (i * 37) % 1000).collect();
    if let Ok(uniform) = UniformTable::new(values, SPAN) {
        out.push(("uniform", CamTable::Uniform(uniform)));
    }
    out.push(("profile", CamTable::Profile(profile)));
    out
}

fn sequential(c: &mut Criterion) {
    let mut group = c.benchmark_group("sequential");
    group.throughput(Throughput::Elements(PROBES as u64));
    for (name, table) in tables() {
        let step = table.master_span() as f64 / PROBES as f64;
        group.bench_with_input(BenchmarkId::from_parameter(name), &table, |b, t| {
            b.iter(|| {
                let mut cursor = Cursor::new();
                let mut sum = 0.0;
                for i in 0..PROBES {
                    sum += t.eval(black_box(i as f64 * step), &mut cursor).s;
                }
                sum
            })
        });
    }
    group.finish();
}

fn random_access(c: &mut Criterion) {
    let mut group = c.benchmark_group("random_access");
    group.throughput(Throughput::Elements(PROBES as u64));
    for (name, table) in tables() {
        // A fixed pseudo-random sequence (xorshift) so runs compare.
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let span = table.master_span() as f64;
        let masters: Vec<f64> = (0..PROBES)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 53) as f64 * span
            })
            .collect();
        group.bench_with_input(BenchmarkId::from_parameter(name), &table, |b, t| {
            b.iter(|| {
                let mut cursor = Cursor::new();
                let mut sum = 0.0;
                for &m in &masters {
                    sum += t.eval(black_box(m), &mut cursor).s;
                }
                sum
            })
        });
    }
    group.finish();
}

fn batch(c: &mut Criterion) {
    const BATCH: usize = 1_000_000;
    let mut group = c.benchmark_group("batch_sorted");
    group.throughput(Throughput::Elements(BATCH as u64));
    for (name, table) in tables() {
        let step = table.master_span() as f64 / BATCH as f64;
        let masters: Vec<f64> = (0..BATCH).map(|i| (i as f64 + 0.25) * step).collect();
        let mut out = vec![0.0; BATCH];
        group.bench_with_input(BenchmarkId::from_parameter(name), &table, |b, t| {
            b.iter(|| t.positions_into(black_box(&masters), &mut out))
        });
    }
    group.finish();
}

criterion_group!(benches, sequential, random_access, batch);
criterion_main!(benches);
