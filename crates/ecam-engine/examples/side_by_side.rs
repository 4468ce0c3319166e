//! The ecam half of `scripts/bench-side-by-side`: times table lookups and
//! axis-ticks on the benchmark scenario and prints one JSON object per
//! line (`case`, `ecam_ns`, and for the tick cases the reference measured
//! here: the minimal loop, or the mean for the worst case); `--lookups` or
//! `--ticks` runs only those cases. With
//! `--data DIR` it first writes the table, the queries and its own lookup
//! results there (little-endian f64), so the script can time numpy on the
//! very same data and check that both agree. `--quick` takes fewer
//! repetitions. Build with `--release`; see docs/engine.md, "Benchmarks".

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use ecam_core::{CamCurve, Cursor, PointTable};
use ecam_engine::TickInput;
use ecam_engine::plcopen::{CamIn, McCamAxis};
use ecam_engine::plcopen_blocks::CamInBlock;

#[path = "../benches/common/mod.rs"]
mod common;

/// Queries of the single-lookup cases.
const QUERIES: usize = 10_000;
/// Queries of the batch case.
const BATCH: usize = 1_000_000;
/// Ticks timed one by one for the worst case.
const WORST_TICKS: usize = 1_000_000;

struct Options {
    quick: bool,
    data: Option<PathBuf>,
    /// Only the lookup cases, or only the tick cases (both when neither).
    lookups: bool,
    ticks: bool,
}

fn main() -> Result<(), String> {
    let mut options = Options {
        quick: false,
        data: None,
        lookups: false,
        ticks: false,
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--quick" => options.quick = true,
            "--lookups" => options.lookups = true,
            "--ticks" => options.ticks = true,
            "--data" => options.data = Some(args.next().ok_or("--data needs a directory")?.into()),
            other => {
                return Err(format!(
                    "unknown argument {other:?} (use --quick, --data DIR, --lookups, --ticks)"
                ));
            }
        }
    }
    let table = common::stroke_table().ok_or("benchmark table")?;
    let span = table.master_span() as f64;
    let sequential: Vec<f64> = (0..QUERIES)
        .map(|i| (i as f64 + 0.5) * span / QUERIES as f64)
        .collect();
    let random = pseudo_random(QUERIES, span);
    let batch: Vec<f64> = (0..BATCH)
        .map(|i| (i as f64 + 0.25) * span / BATCH as f64)
        .collect();
    if let Some(dir) = &options.data {
        dump(
            dir,
            &table,
            &[
                ("sequential", &sequential),
                ("random", &random),
                ("batch", &batch),
            ],
        )?;
    }
    let both = !options.lookups && !options.ticks;
    if options.lookups || both {
        let reps = if options.quick { 40 } else { 300 };
        lookup_case("lookup-sequential", reps, &sequential, |q, out| {
            single(&table, q, out)
        });
        lookup_case("lookup-random", reps, &random, |q, out| {
            single(&table, q, out)
        });
        lookup_case(
            "lookup-batch-1M",
            if options.quick { 5 } else { 21 },
            &batch,
            |q, out| table.positions_into(q, out),
        );
    }
    if !(options.ticks || both) {
        return Ok(());
    }
    let blocks = if options.quick { 300 } else { 2000 };
    for n in [1usize, 64] {
        let (engine, minimal) = ticks_side_by_side(&table, n, blocks);
        line(
            &format!("tick-{n}"),
            engine,
            Some(("minimal loop (benches/common/minimal.rs)", minimal)),
        );
    }
    let (mean, worst) = worst_case(&table);
    line(
        "tick-worst",
        worst,
        Some(("mean of the same 1e6 ticks", mean)),
    );
    line("tick-peer", time_peer_case(blocks)?, None);
    Ok(())
}

/// The peer driver's `cam513` (scripts/plcopen-peer/driver.cpp): 512 steps
/// of 100 master counts, a 2000-count stroke plus a 300-count sine.
fn peer_table() -> Result<PointTable, String> {
    let pairs: Vec<(i64, i64)> = (0..=512i64)
        .map(|i| {
            let u = i as f64 / 512.0;
            let s = 2000.0 * u + 300.0 * (std::f64::consts::TAU * u).sin();
            (100 * i, s.round() as i64)
        })
        .collect();
    PointTable::from_pairs(&pairs).map_err(|e| format!("peer table: {e}"))
}

/// Median ns per cycle of what the peer's bench times: a periodic,
/// absolute `MC_CamIn` on `cam513`, one facade tick and one `MC_CamIn`
/// block call per cycle, the master advancing 7.3 thousandths of the
/// table's span each cycle (374 counts; the peer's master is a float).
fn time_peer_case(blocks: usize) -> Result<f64, String> {
    let mut axis = McCamAxis::new(peer_table()?).map_err(|e| format!("peer axis: {e}"))?;
    // The new axis' selection is the peer's: periodic, master and slave
    // absolute.
    let params = CamIn::default();
    let mut block = CamInBlock::default();
    let mut status = axis.tick(0, common::DT_US);
    block.call(&mut axis, true, &params, &status);
    let mut master = 0i64;
    let mut times = Vec::with_capacity(blocks);
    for _ in 0..blocks.max(3) {
        let start = Instant::now();
        for _ in 0..TICKS_PER_BLOCK {
            master += 374;
            status = axis.tick(black_box(master), common::DT_US);
            black_box(block.call(&mut axis, true, &params, &status));
        }
        times.push(start.elapsed().as_nanos() as f64 / TICKS_PER_BLOCK as f64);
    }
    // Not `in_sync`: with an absolute slave the table's 2000-count jump
    // back at every seam is paid out by the pulse limiter over the
    // following cycles (the float peer jumps at once), so ecam may be
    // owing pulses at any given cycle.
    if !block.call(&mut axis, true, &params, &status).active {
        return Err("tick-peer: the cam is not active".to_string());
    }
    Ok(median(&mut times))
}

/// One lookup per query through the cursor, as the engine does.
fn single(table: &PointTable, queries: &[f64], out: &mut [f64]) {
    let mut cursor = Cursor::new();
    for (q, o) in queries.iter().zip(out.iter_mut()) {
        *o = table.position(black_box(*q), &mut cursor);
    }
}

fn lookup_case(case: &str, reps: usize, queries: &[f64], run: impl Fn(&[f64], &mut [f64])) {
    let mut out = vec![0.0; queries.len()];
    let mut times = Vec::with_capacity(reps);
    for _ in 0..reps {
        let start = Instant::now();
        run(black_box(queries), &mut out);
        black_box(&out);
        times.push(start.elapsed().as_nanos() as f64 / queries.len() as f64);
    }
    line(case, median(&mut times), None);
}

/// Axis-ticks per timed block: short, so that a block the OS interrupts
/// is one outlier among many rather than a shift of the whole figure.
const TICKS_PER_BLOCK: usize = 2048;

/// Median ns per axis-tick of the engine and of the minimal loop, `n` axes
/// each, timed in alternating blocks so that both see the same machine.
fn ticks_side_by_side(table: &PointTable, n: usize, blocks: usize) -> (f64, f64) {
    let mut engine = common::axes(table, n);
    let mut minimal = common::minimal_axes(table, n);
    let cycles = (TICKS_PER_BLOCK / n).max(1);
    let (mut master_e, mut master_m) = (0i64, 0i64);
    let mut times_e = Vec::with_capacity(blocks);
    let mut times_m = Vec::with_capacity(blocks);
    for _ in 0..blocks {
        let start = Instant::now();
        for _ in 0..cycles {
            master_e += common::MASTER_PER_TICK;
            let input = TickInput::at(master_e, common::DT_US);
            for axis in engine.iter_mut() {
                black_box(axis.tick_in_place(black_box(&input)));
            }
        }
        times_e.push(start.elapsed().as_nanos() as f64 / (cycles * n) as f64);
        let start = Instant::now();
        for _ in 0..cycles {
            master_m += common::MASTER_PER_TICK;
            for axis in minimal.iter_mut() {
                black_box(axis.tick(black_box(master_m)));
            }
        }
        times_m.push(start.elapsed().as_nanos() as f64 / (cycles * n) as f64);
    }
    (median(&mut times_e), median(&mut times_m))
}

/// Mean and worst of 10^6 single ticks of one axis, each timed alone
/// (the clock reading, ~20 ns, is inside every figure).
fn worst_case(table: &PointTable) -> (f64, f64) {
    let mut axes = common::axes(table, 1);
    let Some(axis) = axes.first_mut() else {
        return (f64::NAN, f64::NAN);
    };
    let mut master = 0i64;
    let mut total = 0u128;
    let mut worst = 0u128;
    for _ in 0..WORST_TICKS {
        master += common::MASTER_PER_TICK;
        let input = TickInput::at(master, common::DT_US);
        let start = Instant::now();
        black_box(axis.tick_in_place(black_box(&input)));
        let took = start.elapsed().as_nanos();
        total += took;
        worst = worst.max(took);
    }
    (total as f64 / WORST_TICKS as f64, worst as f64)
}

fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    times.get(times.len() / 2).copied().unwrap_or(f64::NAN)
}

fn line(case: &str, ecam_ns: f64, reference: Option<(&str, f64)>) {
    match reference {
        Some((name, ns)) => println!(
            "{{\"case\": \"{case}\", \"ecam_ns\": {ecam_ns:.2}, \"reference\": \"{name}\", \"reference_ns\": {ns:.2}, \"ratio\": {:.3}}}",
            ecam_ns / ns
        ),
        None => println!("{{\"case\": \"{case}\", \"ecam_ns\": {ecam_ns:.2}}}"),
    }
}

/// `n` uniform masters in `[0, span)` from a fixed xorshift sequence.
fn pseudo_random(n: usize, span: f64) -> Vec<f64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * span
        })
        .collect()
}

/// Writes the table (`table.csv`), each query set (`NAME.f64`) and ecam's
/// results for it (`NAME.ecam.f64`).
fn dump(dir: &Path, table: &PointTable, sets: &[(&str, &[f64])]) -> Result<(), String> {
    let io = |e: std::io::Error| format!("{}: {e}", dir.display());
    std::fs::create_dir_all(dir).map_err(io)?;
    let csv: String = table
        .points()
        .iter()
        .map(|p| format!("{},{}\n", p.master, p.slave))
        .collect();
    std::fs::write(dir.join("table.csv"), csv).map_err(io)?;
    for (name, queries) in sets {
        let mut out = vec![0.0; queries.len()];
        single(table, queries, &mut out);
        std::fs::write(dir.join(format!("{name}.f64")), bytes(queries)).map_err(io)?;
        std::fs::write(dir.join(format!("{name}.ecam.f64")), bytes(&out)).map_err(io)?;
    }
    Ok(())
}

fn bytes(values: &[f64]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}
