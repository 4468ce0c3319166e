//! Safe motion through the command line, as a user meets it: commands a
//! drive can follow from `ecam plc run` and `ecam simulate`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use crate::common::{ecam, ok, scratch_dir};
use serde_json::Value;

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs `ecam plc run PROGRAM ARGS --trace` with one traced device per
/// column; returns the dump and the trace rows (time first).
fn plc_run(
    dir: &Path,
    program: &str,
    args: &[&str],
    dump: &[&str],
    trace: &[&str],
) -> (Value, Vec<Vec<i64>>) {
    let path = write(dir, "program.il", program);
    let trace_file = dir.join("trace.csv");
    let mut all: Vec<String> = vec!["plc".into(), "run".into(), path.display().to_string()];
    all.extend(args.iter().map(|a| a.to_string()));
    for d in dump {
        all.push("--dump".into());
        all.push(d.to_string());
    }
    all.push("--trace".into());
    all.push(trace_file.display().to_string());
    for d in trace {
        all.push("--trace-dev".into());
        all.push(d.to_string());
    }
    let all: Vec<&str> = all.iter().map(String::as_str).collect();
    let stdout = ok(ecam(&all));
    let text = std::fs::read_to_string(&trace_file).unwrap();
    let rows = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (serde_json::from_str(&stdout).unwrap(), rows)
}

/// A straight cam at D2000: master 0..1000, slave 0..`stroke`, started as
/// mode `mode` by the first scan; `master` is S1.
fn line_cam(master: &str, stroke: i32, mode: i32, extra: &str) -> String {
    format!(
        "LD M8002\nMOV K2 D2038\nDMOV K0 D2040\nDMOV K0 D2042\nDMOV K1000 D2044\n\
         DMOV K{stroke} D2046\n{extra}\nLD M8000\nMOV K{mode} D2005\n\
         DECAM {master} D2000 X2 Y0 Y4\nEND\n"
    )
}

/// Pulses per 100 µs tick from a trace of D8140 taken every 100 µs scan.
fn per_tick(rows: &[Vec<i64>]) -> Vec<i64> {
    rows.windows(2).map(|w| w[1][1] - w[0][1]).collect()
}

#[test]
fn a_k10_time_base_cruises_at_50_khz_without_bursts() {
    let dir = scratch_dir("safe-k10");
    // One master count per ms, 50 slave pulses per count: 50 kHz, which is
    // 5 pulses in every 100 µs tick.
    let (_, rows) = plc_run(
        &dir,
        &line_cam("K10", 50_000, 1, ""),
        &["--scan-us", "100", "--ms", "100"],
        &["D2001"],
        &["DD8140"],
    );
    let pulses = per_tick(&rows);
    assert!(pulses.len() > 900);
    for (i, p) in pulses.iter().enumerate().skip(2) {
        assert!((4..=6).contains(p), "tick {i}: {p} pulses");
    }
}

#[test]
fn a_counter_fed_at_1_khz_cruises_without_bursts() {
    let dir = scratch_dir("safe-hsc");
    // DPLSY sends 1 kHz into X0, counted by C235: one count per 10 ticks.
    let extra = "RST C235\nLD M8000\nOUT C235 K2147483647\nDPLSY K1000 K0 Y1";
    let (_, rows) = plc_run(
        &dir,
        &line_cam("C235", 50_000, 1, extra),
        &["--wire", "Y1:X0", "--scan-us", "100", "--ms", "200"],
        &["D2001"],
        &["DD8140", "C235"],
    );
    let pulses = per_tick(&rows);
    // After the tracker has seen a few counts, every tick carries 4-6.
    let settled: Vec<_> = pulses.iter().skip(100).collect();
    assert!(settled.len() > 1800);
    for (i, p) in settled.iter().enumerate() {
        assert!((4..=6).contains(*p), "tick {}: {p} pulses", i + 100);
    }
}

#[test]
fn a_start_at_master_0_on_a_time_base_fires() {
    let dir = scratch_dir("safe-start0");
    // Noncyclic (2), function bit 1: start at master position 0 (D2017).
    // K1: one count per 100 µs tick, so a time base that read 1 on its
    // first tick would already have passed 0.
    let extra = "MOV K2 D2003\nDMOV K0 D2017";
    let (dump, _) = plc_run(
        &dir,
        &line_cam("K1", 1000, 2, extra),
        &["--ms", "50"],
        &["DD8140", "D2013", "D2001"],
        &["DD8140"],
    );
    assert_eq!(dump["D2013"], 0, "no counts left to wait");
    let slave = dump["DD8140"].as_i64().unwrap();
    assert!((498..=500).contains(&slave), "engaged at 0: slave {slave}");
}

#[test]
fn a_noncyclic_time_base_cam_engages_at_master_0() {
    let dir = scratch_dir("safe-engage0");
    let (dump, _) = plc_run(
        &dir,
        &line_cam("K10", 1000, 2, ""),
        &["--ms", "50"],
        &["DD2027", "DD8140"],
        &["DD8140"],
    );
    // Started on the first 100 µs tick: 49.9 ms later, 49 whole counts and
    // nine tenths of the next; the slave (1 per count) stands at 49.9.
    assert_eq!(dump["DD2027"], 49);
    assert_eq!(dump["DD8140"], 50);
}

#[test]
fn a_mid_cam_end_table_stops_the_cam_when_it_completes() {
    let dir = scratch_dir("safe-midcamend");
    // The manual's rotary-cut demo with P6 high word 3 (midCAMend), run as
    // the cyclic cam from a K1 time base.
    let program = "LD M8002\nDMOV K3183 D100\nDMOV K1000 D102\nDMOV K333 D104\n\
        DEMOV E1.6666666 D106\nDEMOV E16.666666 D108\nMOV K0 D110\nMOV K3 D111\n\
        MOV K100 D112\nECAMTBX D100 K100 D2000 D500\n\
        LD M8000\nMOV K1 D2005\nDECAM K1 D2000 X2 Y0 Y4\nEND\n";
    let (dump, rows) = plc_run(
        &dir,
        program,
        &["--ms", "1000"],
        &["D500", "D2031", "D2001", "DD8140", "M8147"],
        &["DD8140"],
    );
    assert_eq!(dump["D500"], 100);
    assert_eq!(dump["D2031"], 1, "ECAMTBX marked the table single-pass");
    let flags = dump["D2001"].as_i64().unwrap();
    assert_ne!(flags & (1 << 9), 0, "current cycle complete: {flags:#b}");
    assert_eq!(dump["M8147"], 0, "the output is no longer busy");
    // 3183 counts of K1 take 318.3 ms; from then on the knife stands still.
    let at_end = rows.iter().find(|r| r[0] >= 400_000).unwrap()[1];
    assert_eq!(rows.last().unwrap()[1], at_end);
    assert_eq!(dump["DD8140"], at_end);
}

/// A cam on C235 (10 kHz from DPLSY on Y1): when the master passes 2500 the
/// program writes new table words while the cam runs.
fn edited_while_running(edit: &str) -> String {
    let extra = format!("RST C235\nLD M8000\nOUT C235 K2500\nDPLSY K10000 K0 Y1\nLD C235\n{edit}");
    line_cam("C235", 1000, 1, &extra)
}

#[test]
fn a_table_edited_while_running_takes_over_at_the_seam_without_a_step() {
    let dir = scratch_dir("safe-edit");
    // Slave end 1000 → 3000 at master 2500: the old table runs to the seam
    // at 3000, the new one from there (3 pulses per count).
    let (dump, rows) = plc_run(
        &dir,
        &edited_while_running("DMOV K3000 D2046"),
        &["--wire", "Y1:X0", "--ms", "400"],
        &["DD8140", "C235", "D2001"],
        &["DD8140", "C235"],
    );
    for w in rows.windows(2) {
        let step = w[1][1] - w[0][1];
        // 10 counts per ms: at most 30 pulses per scan, never backwards.
        assert!((0..=31).contains(&step), "t={} us: step {step}", w[1][0]);
    }
    let master = dump["C235"].as_i64().unwrap();
    assert!((3500..=4000).contains(&master));
    let expected = 3000 + 3 * (master - 3000);
    let slave = dump["DD8140"].as_i64().unwrap();
    assert!(
        (slave - expected).abs() <= 30,
        "slave {slave}, expected {expected}"
    );
    let at_2900 = rows.iter().find(|r| r[2] >= 2900).unwrap();
    assert!(
        (at_2900[1] - at_2900[2]).abs() <= 10,
        "old table up to the seam"
    );
}

#[test]
fn a_bad_table_write_keeps_the_cam_running_and_the_flags_say_so() {
    let dir = scratch_dir("safe-bad-edit");
    // Point 1's master written as 0: error 6782 at point 1.
    let (dump, _) = plc_run(
        &dir,
        &edited_while_running("DMOV K0 D2044"),
        &["--wire", "Y1:X0", "--ms", "400"],
        &["DD8140", "C235", "D2001", "D2002"],
        &["DD8140"],
    );
    let flags = dump["D2001"].as_i64().unwrap();
    assert_eq!(dump["D2002"], 1, "error register: the bad point");
    assert_ne!(flags & (1 << 8), 0, "bit 8: running on the last good table");
    assert_eq!(flags & 0b11_1000, 0, "bits 3-5 off: the cam did not stop");
    let master = dump["C235"].as_i64().unwrap();
    let slave = dump["DD8140"].as_i64().unwrap();
    assert!(
        (slave - master).abs() <= 10,
        "still following the 1:1 table"
    );
}

fn simulate(dir: &Path, scenario: &str) -> Value {
    let path = write(dir, "scenario.toml", scenario);
    serde_json::from_str(&ok(ecam(&["simulate", path.to_str().unwrap()]))).unwrap()
}

#[test]
fn a_normal_cam_on_a_single_turn_master_follows_every_turn() {
    let dir = scratch_dir("safe-normal-turn");
    let summary = simulate(
        &dir,
        "tick_us = 100\n[table]\npoints = [[0, 0], [1000, 500]]\n\
         [cam]\nkind = \"normal\"\nsingle_turn = 1000\n\
         [master]\nmoves = [[0.5, 2250]]\n",
    );
    // Document 001: with the table covering the turn, Normal behaves as
    // Periodic: at 2250 (250 into the third turn) the slave is 125.
    assert_eq!(summary["final_master"], 2250);
    assert_eq!(summary["final_slave"], 125);
}

#[test]
fn a_coarse_master_in_a_scenario_is_interpolated() {
    let dir = scratch_dir("safe-coarse-scenario");
    let scenario = |filter: &str| {
        format!(
            "tick_us = 100\nduration_s = 1.1\n[table]\npoints = [[0, 0], [1000, 50000]]\n\
             [cam]\nkind = \"repeat\"\n{filter}\n\
             [master]\nmoves = [[1.0, 1000]]\nupdate_us = 1000\n"
        )
    };
    let raw = simulate(&dir, &scenario(""));
    let smooth = simulate(&dir, &scenario("master_filter = \"interpolate\""));
    assert_eq!(raw["max_pulses_per_tick"], 20, "bursts at the ceiling");
    assert!(smooth["max_pulses_per_tick"].as_i64().unwrap() <= 6);
    assert_eq!(smooth["final_slave"], 50_000);
    assert_eq!(smooth["direction_changes"], 0);
}

#[test]
fn a_periodic_jump_is_flagged_and_spread_under_the_ceiling() {
    let summary = simulate(
        &scratch_dir("safe-periodic"),
        "tick_us = 100\n[table]\npoints = [[0, 500], [10000, 1500], [20000, 1000], [30000, 2000]]\n\
         [cam]\nkind = \"periodic\"\nmax_frequency_hz = 100000\n\
         [start]\nslave = 500\n[master]\nmoves = [[1.0, 55000]]\n",
    );
    assert_eq!(summary["seam_jumps"], 1);
    assert!(summary["max_pulses_per_tick"].as_i64().unwrap() <= 10);
    assert_eq!(summary["final_emitted"], 1500);
}
