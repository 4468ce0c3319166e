//! `ecam simulate`: every shipped scenario of `examples/scenarios/` against
//! the numbers of its document, the trace and summary formats, and errors.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::ecam;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn scenario(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/scenarios")
        .join(name)
}

fn scratch(name: &str) -> PathBuf {
    crate::common::scratch_dir(&format!("simulate-{name}"))
}

/// A trace, column by name.
struct Trace {
    columns: HashMap<String, usize>,
    rows: Vec<Vec<String>>,
}

impl Trace {
    fn read(path: &Path) -> Self {
        let text = std::fs::read_to_string(path).unwrap();
        let mut lines = text.lines();
        let header = lines.next().unwrap();
        assert!(
            header.starts_with("t,master,slave,velocity,pulses"),
            "{header}"
        );
        let columns = header
            .split(',')
            .enumerate()
            .map(|(i, c)| (c.to_string(), i))
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect();
        Self { columns, rows }
    }

    fn int(&self, row: &[String], column: &str) -> i64 {
        row[self.columns[column]].parse().unwrap()
    }

    /// The commanded slave on the first row where the cam's master input is `master`.
    fn slave_at(&self, master: i64) -> i64 {
        let row = self
            .rows
            .iter()
            .find(|r| self.int(r, "master") == master)
            .unwrap_or_else(|| panic!("no trace row at master {master}"));
        self.int(row, "slave")
    }

    fn first(&self, column: &str) -> i64 {
        self.int(&self.rows[0], column)
    }
}

/// Runs a shipped scenario with a trace; returns the summary and the trace.
fn run(name: &str) -> (Value, Trace) {
    let dir = scratch(name);
    let trace = dir.join("trace.csv");
    let out = ecam(&[
        "simulate",
        scenario(name).to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(text.lines().count(), 1, "one JSON line: {text}");
    (serde_json::from_str(&text).unwrap(), Trace::read(&trace))
}

#[test]
fn doc001_repeat_keeps_the_slave_continuous_at_the_seam() {
    let (sum, trace) = run("001-repeat.toml");
    assert_eq!(sum["final_master"], 60000);
    assert_eq!(sum["final_slave"], 3500);
    assert_eq!(sum["cycles"], 2);
    assert_eq!(sum["max_backlog"], 0);
    assert_eq!(trace.slave_at(15000), 1250);
    assert_eq!(trace.slave_at(30000), 2000);
    assert_eq!(trace.slave_at(30060), 2006);
    assert_eq!(trace.slave_at(40002), 3000); // 1500 - 0.1 + 1500, rounded
    assert_eq!(trace.slave_at(45000), 2750);
}

#[test]
fn doc001_periodic_jumps_back_at_the_seam() {
    let (sum, trace) = run("001-periodic.toml");
    assert_eq!(sum["final_slave"], 1500);
    assert_eq!(trace.slave_at(15004), 1250); // 1249.8, rounded
    // Just past the seam the commanded slave restarts from 500.
    let after = trace.slave_at(30008);
    assert!((500..510).contains(&after), "{after}");
    // The 1500-pulse jump is output under the 200 kHz limit: a backlog, never lost.
    assert!(sum["max_backlog"].as_u64().unwrap() > 1000);
    assert_eq!(sum["final_emitted"], 1500);
    assert_eq!(sum["pulses"], 1000);
}

#[test]
fn doc001_single_turn_repeat_depends_on_the_wraps() {
    let (sum, trace) = run("001-single-turn-repeat.toml");
    assert_eq!(sum["final_master"], 90000);
    assert_eq!(sum["final_slave"], 500 + 3 * 1500);
    assert_eq!(sum["cycles"], 3);
    // The cam sees the wrapped turn position.
    let max_master = trace
        .rows
        .iter()
        .map(|r| trace.int(r, "master"))
        .max()
        .unwrap();
    assert!(max_master < 30000, "{max_master}");
}

#[test]
fn doc001_single_turn_start_takes_the_nearest_equivalent() {
    let (sum, trace) = run("001-single-turn-start.toml");
    // Master 20000, slave -1500: the commanded position starts at -2000.
    assert_eq!(trace.first("master"), 20000);
    assert_eq!(trace.first("slave"), -2000);
    assert_eq!(sum["final_master"], 35000);
    assert_eq!(sum["final_slave"], -500);
    assert_eq!(sum["final_emitted"], -500);
}

#[test]
fn doc001_incomplete_table_is_extended_over_the_turn() {
    let (sum, trace) = run("001-incomplete-turn.toml");
    assert_eq!(trace.slave_at(2500), 1000);
    assert_eq!(trace.slave_at(12500), 2500);
    assert_eq!(trace.slave_at(27500), 3000);
    // Second turn: the cam sees 2500 again, one stroke (2000) higher.
    let second_turn = trace
        .rows
        .iter()
        .filter(|r| trace.int(r, "master") == 2500)
        .map(|r| trace.int(r, "slave"))
        .collect::<Vec<_>>();
    assert_eq!(second_turn, [1000, 3000]);
    assert_eq!(sum["final_slave"], 5000);
}

#[test]
fn doc002_linear_table_gives_202_at_input_101() {
    let (sum, _) = run("002-linear-incremental.toml");
    assert_eq!(sum["final_master"], 101);
    assert_eq!(sum["final_slave"], 202);
    assert_eq!(sum["pulses"], 202);
}

#[test]
fn doc002_incremental_cam_wraps_both_ways() {
    let (sum, trace) = run("002-linear-both-ways.toml");
    assert_eq!(trace.slave_at(101), 202);
    assert_eq!(sum["final_master"], -101);
    assert_eq!(sum["final_slave"], -202);
    assert_eq!(sum["cycles"], -2);
}

#[test]
fn doc002_breakpoint_start_and_smooth_stop() {
    let (sum, trace) = run("002-breakpoints.toml");
    assert_eq!(sum["engaged_at_s"], 0.1);
    assert_eq!(trace.slave_at(1000), 0);
    assert_eq!(trace.slave_at(1500), 500);
    // The stop at 1600 waits for the end of the table at 1640.
    assert_eq!(trace.slave_at(1639), 639);
    assert_eq!(sum["final_slave"], 640);
    assert_eq!(sum["state"], "finished");
}

#[test]
fn doc003_cyclic_cam_drives_the_sync_output_between_20000_and_30000() {
    let (sum, trace) = run("003-cyclic-sync.toml");
    assert_eq!(sum["cycles"], 2);
    assert_eq!(sum["sync_ticks"], 2 * 1001);
    assert_eq!(sum["pulses"], 0);
    assert_eq!(sum["pulses_forward"], 5000);
    for r in &trace.rows {
        let m = trace.int(r, "master_in_cycle");
        let on = trace.int(r, "sync") & 1 == 1;
        assert_eq!(on, (20000..=30000).contains(&m), "master in cycle {m}");
    }
}

#[test]
fn doc003_noncyclic_cam_runs_three_cycles_after_the_trigger() {
    let (sum, _) = run("003-noncyclic.toml");
    assert_eq!(sum["state"], "finished");
    assert_eq!(sum["cycles"], 3);
    assert_eq!(sum["final_slave"], 3000);
    assert_eq!(sum["engaged_at_s"], 0.1);
}

#[test]
fn summary_and_trace_formats() {
    let dir = scratch("formats");
    let (trace, svg) = (dir.join("t.csv"), dir.join("t.svg"));
    let out = ecam(&[
        "simulate",
        scenario("003-cyclic-sync.toml").to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let sum: Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "final_master",
        "final_slave",
        "final_emitted",
        "pulses",
        "cycles",
        "max_backlog",
        "state",
        "sync_ticks",
        "ticks",
        "time_s",
    ] {
        assert!(sum.get(key).is_some(), "summary lacks {key}");
    }
    let text = std::fs::read_to_string(&trace).unwrap();
    assert_eq!(
        text.lines().next(),
        Some(
            "t,master,slave,velocity,pulses,emitted,backlog,master_in_cycle,cycle,state,sync,flags"
        )
    );
    // One row per tick, t = 0 included: 1 s at 100 us.
    assert_eq!(text.lines().count(), 1 + 10001);
    assert!(text.contains("\n0.2,20000,2500,"), "row at t = 0.2 s");
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(
        svg.contains("<svg") && svg.contains("FFDD78"),
        "sync time shaded"
    );
}

#[test]
fn stops_and_delayed_starts() {
    let dir = scratch("stops");
    let path = dir.join("s.toml");
    let base = r#"
tick_us = 100
[table]
points = [[0, 0], [1000, 1000]]
[cam]
kind = "repeat"
[master]
moves = [[1.0, 10000]]
"#;
    let summary = |extra: &str| -> Value {
        let text = if extra.starts_with("[cam]") {
            base.replace("[cam]\nkind = \"repeat\"\n", extra)
        } else {
            format!("{base}{extra}")
        };
        std::fs::write(&path, text).unwrap();
        let out = ecam(&["simulate", path.to_str().unwrap()]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    // The master moves one count per tick. An immediate stop requested at
    // 0.25 s (master 2500) holds the slave where the tick before left it.
    let s = summary("[stop]\nat_s = 0.25\nkind = \"immediate\"\n");
    assert_eq!(s["final_slave"], 2499);
    assert_eq!(s["state"], "idle");
    // End-of-cycle stop at 0.25 s: the cycle ends at master 3000.
    let s = summary("[stop]\nat_s = 0.25\nkind = \"end-of-cycle\"\n");
    assert_eq!(s["final_slave"], 3000);
    // Start after a delay of 500 master counts.
    let s = summary("[start]\nmode = \"after-delay\"\ndelay = 500\nslave_align = \"relative\"\n");
    assert_eq!(s["final_slave"], 9500);
    // Start when the master reaches 4000, from the table's start.
    let s = summary(
        "[start]\nmode = \"at-position\"\nposition = 4000\nmaster_align = \"start-at\"\nmaster_value = 0\n",
    );
    assert_eq!(s["final_slave"], 6000);
    // A slave zoom of 3/2, and a master zoom of 1/2.
    let s = summary("[cam]\nkind = \"repeat\"\nslave_zoom = [3, 2]\n");
    assert_eq!(s["final_slave"], 15000);
    let s = summary("[cam]\nkind = \"repeat\"\nmaster_zoom = [1, 2]\n");
    assert_eq!(s["final_slave"], 5000);
}

#[test]
fn bad_scenarios_are_refused_with_a_message() {
    let dir = scratch("bad");
    let path = dir.join("bad.toml");
    let check = |text: &str, expect: &str| {
        std::fs::write(&path, text).unwrap();
        let out = ecam(&["simulate", path.to_str().unwrap()]);
        assert!(!out.status.success(), "accepted: {text}");
        assert!(out.stdout.is_empty());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(expect), "{expect:?} not in {err}");
    };
    let master = "[master]\nmoves = [[1.0, 100]]\n";
    check(
        &format!("[table]\npoints = [[0, 0], [0, 1]]\n{master}"),
        "6782",
    );
    check(
        &format!("[table]\npoints = [[0, 0], [10, 1]]\nfile = \"x.csv\"\n{master}"),
        "only one",
    );
    check(
        &format!("[table]\npoints = [[0, 0], [10, 1]]\n[cam]\nknd = \"repeat\"\n{master}"),
        "knd",
    );
    check(
        &format!("[table]\npoints = [[0, 0], [10, 1]]\n[cam]\nkind = \"sometimes\"\n{master}"),
        "sometimes",
    );
    check(
        &format!("[table]\npoints = [[0, 0], [10, 1]]\n[cam]\nslave_zoom = [1, 0]\n{master}"),
        "slave_zoom",
    );
    check(
        &format!("[table]\nfile = \"missing.csv\"\n{master}"),
        "missing.csv",
    );
    check(
        "[table]\npoints = [[0, 0], [10, 1]]\n[master]\nmoves = []\n",
        "nothing to simulate",
    );
    check(
        &format!("[table]\npoints = [[0, 0], [10, 1]]\n[start]\nmode = \"breakpoint\"\n{master}"),
        "compare",
    );
    let out = ecam(&["simulate", dir.join("none.toml").to_str().unwrap()]);
    assert!(!out.status.success());
}

#[test]
fn tables_from_files_and_generators() {
    let dir = scratch("sources");
    std::fs::write(dir.join("line.csv"), "master,slave\n0,0\n100,200\n").unwrap();
    let path = dir.join("s.toml");
    std::fs::write(
        &path,
        "[table]\nfile = \"line.csv\"\n[cam]\nkind = \"repeat\"\n[master]\nmoves = [[0.1, 150]]\n",
    )
    .unwrap();
    let out = ecam(&["simulate", path.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(s["final_slave"], 300);
    std::fs::write(
        &path,
        "[table]\ngenerator = \"rotary-cut\"\nmaster = 3183\nslave = 1000\nsync = 333\nratio = \"5/3\"\n[cam]\nkind = \"repeat\"\n[master]\nmoves = [[1.0, 6366]]\n",
    )
    .unwrap();
    let out = ecam(&["simulate", path.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s: Value = serde_json::from_slice(&out.stdout).unwrap();
    // Two cuts: two knife revolutions.
    assert_eq!(s["final_slave"], 2000);
    assert_eq!(s["cycles"], 2);
}

#[test]
fn a_closed_stdout_ends_the_run_quietly() {
    use std::process::Stdio;
    // The reading end is closed before the child starts, so its first write
    // fails however the two processes are scheduled.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["simulate", scenario("001-repeat.toml").to_str().unwrap()])
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    // As Unix tools do: no panic, no message, status 0.
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.is_empty(), "{err}");
    assert!(out.status.success());
}

#[test]
fn keys_the_start_mode_never_reads_are_refused() {
    let dir = scratch("unused-keys");
    let path = dir.join("s.toml");
    // Without mode = "after-delay" the delay would silently be ignored.
    std::fs::write(
        &path,
        "[table]\npoints = [[0, 0], [10, 1]]\n[start]\ndelay = 500\n[master]\nmoves = [[1.0, 100]]\n",
    )
    .unwrap();
    let out = ecam(&["simulate", path.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(out.stdout.is_empty());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("delay only applies"), "{err}");
}

#[test]
fn a_table_outside_the_turn_names_both() {
    let dir = scratch("outside-turn");
    let path = dir.join("s.toml");
    std::fs::write(
        &path,
        "[table]\npoints = [[0, 0], [200, 5]]\n[cam]\nsingle_turn = 150\n[master]\nmoves = [[0.1, 100]]\n",
    )
    .unwrap();
    let out = ecam(&["simulate", path.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("6782"), "{err}");
    assert!(
        err.contains("table master 0 .. 200, single_turn = 150"),
        "{err}"
    );
}

#[test]
fn a_rotary_knife_changes_cut_length_twice_while_running() {
    let dir = scratch("switch");
    let trace_file = dir.join("trace.csv");
    let out = ecam(&[
        "simulate",
        scenario("rotary-knife-switch.toml").to_str().unwrap(),
        "--trace",
        trace_file.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(summary["table_switches"], 2);
    assert_eq!(
        summary["direction_changes"], 0,
        "the knife never turns back"
    );
    // 4 cuts of 3183, 5 of 2500 (the first seam after the request at master
    // 25000 is 25232), then 4000-pulse cuts: 3 whole ones by master 40000.
    assert_eq!(summary["cycles"], 12);
    assert_eq!(summary["input_offset"], -25232);
    assert_eq!(summary["max_backlog"], 0);
    let trace = Trace::read(&trace_file);
    // Continuous: between two traced rows (1 ms apart) the knife moves at
    // most the table's top speed (50/3 × 10 counts) and never back.
    let mut last = None;
    for row in &trace.rows {
        let slave = trace.int(row, "slave");
        if let Some(prev) = last {
            let step = slave - prev;
            assert!((0..=167).contains(&step), "step {step} at t={}", row[0]);
        }
        last = Some(slave);
    }
}

#[test]
fn a_switch_at_once_or_at_a_position_blends_onto_the_new_table() {
    let dir = scratch("switch-modes");
    for switch in [
        "mode = \"now\"\nblend = 500",
        "mode = \"position\"\nposition = 7000\nblend = 500",
    ] {
        let path = dir.join("s.toml");
        std::fs::write(
            &path,
            format!(
                "tick_us = 100\n[table]\npoints = [[0, 0], [1000, 1000]]\n[cam]\nkind = \"repeat\"\n\
                 [master]\nmoves = [[1.0, 10000]]\n\
                 [[switch]]\nat_s = 0.5\n{switch}\ntable = {{ points = [[0, 0], [1000, 3000]] }}\n"
            ),
        )
        .unwrap();
        let trace_file = dir.join("t.csv");
        let out = ecam(&[
            "simulate",
            path.to_str().unwrap(),
            "--trace",
            trace_file.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let summary: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(summary["table_switches"], 1, "{switch}");
        assert_eq!(summary["direction_changes"], 0);
        let trace = Trace::read(&trace_file);
        let slaves: Vec<i64> = trace.rows.iter().map(|r| trace.int(r, "slave")).collect();
        // 1 count per tick: the slave moves 1 pulse per tick before, 3
        // after, and in between never more than 3 nor backwards.
        for w in slaves.windows(2) {
            assert!(
                (0..=3).contains(&(w[1] - w[0])),
                "{switch}: step {}",
                w[1] - w[0]
            );
        }
        let n = slaves.len();
        assert_eq!(
            slaves[n - 1] - slaves[n - 2],
            3,
            "{switch}: on the new table"
        );
        assert_eq!(slaves[1] - slaves[0], 1);
    }
}

#[test]
fn coupling_scenarios_run_with_a_trace_a_plot_and_their_summary_keys() {
    // The couplings beyond the documents (docs/simulate.md): each shipped
    // scenario runs through the binary; ecam-sim's tests check their traces.
    for (name, key, value) in [
        ("modulo-knife.toml", "modulo_position", 0.0),
        ("phasing-shift.toml", "phase_shift", 1000.0),
        ("gear-cam-superimposed.toml", "superimposed", 6000.0),
        ("registration-print-marks.toml", "registration_missed", 1.0),
        ("direction-guard.toml", "guard_lost", 3000.0),
        ("cam-switch-glue.toml", "cam_switch_toggles", 19.0),
    ] {
        let dir = scratch(name);
        let png = dir.join("plot.png");
        let (sum, trace) = run(name);
        assert_eq!(sum[key].as_f64(), Some(value), "{name}: {key}");
        assert_eq!(sum["pulses_reverse"], 0, "{name}");
        assert!(trace.rows.iter().all(|r| trace.int(r, "pulses") >= 0));
        let out = ecam(&[
            "simulate",
            scenario(name).to_str().unwrap(),
            "--plot",
            png.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{name}");
        assert!(std::fs::metadata(&png).unwrap().len() > 10_000);
    }
    // A plain cam's summary has none of the coupling keys.
    let (sum, _) = run("001-repeat.toml");
    assert!(sum.get("gear_slave").is_none() && sum.get("modulo_position").is_none());
}
