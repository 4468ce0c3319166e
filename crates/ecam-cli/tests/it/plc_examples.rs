//! The PLC manual's worked examples (document 003 sections 4.1.3, 4.2.3 and
//! the ECAMTBX demos), run through the real `ecam plc run`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::process::Command;

use serde_json::Value;

fn example(name: &str) -> String {
    format!("{}/../../examples/plc/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Runs `ecam plc run` and returns the dumped devices.
fn run(program: &str, args: &[&str], dumps: &[&str]) -> serde_json::Map<String, Value> {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_ecam"));
    cmd.arg("plc").arg("run").arg(example(program)).args(args);
    for d in dumps {
        cmd.arg("--dump").arg(d);
    }
    let out = cmd.output().expect("ecam runs");
    assert!(
        out.status.success(),
        "ecam plc run {program} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    json.as_object().expect("an object").clone()
}

fn int(map: &serde_json::Map<String, Value>, key: &str) -> i64 {
    map.get(key)
        .and_then(Value::as_i64)
        .unwrap_or_else(|| panic!("{key} missing in {map:?}"))
}

/// Linear interpolation in a point table, as the PLC does.
fn table_value(table: &[(i64, i64)], master: i64) -> f64 {
    let i = table.windows(2).position(|w| master <= w[1].0).unwrap();
    let ((m0, s0), (m1, s1)) = (table[i], table[i + 1]);
    s0 as f64 + (s1 - s0) as f64 * (master - m0) as f64 / (m1 - m0) as f64
}

const CYCLIC_TABLE: &[(i64, i64)] = &[
    (0, 0),
    (5000, 100),
    (10000, 400),
    (15000, 900),
    (20000, 1500),
    (25000, 2000),
    (30000, 2500),
    (35000, 2200),
    (40000, 1500),
    (45000, 600),
    (50000, 0),
];

#[test]
fn cyclic_example_section_4_1_3() {
    let dumps = [
        "D2000", "D2001", "D2002", "D2039", "DD2025", "DD2027", "DD2019", "Y7", "DD8140", "C231",
        "D8067", "M8147",
    ];
    // 25 kHz master: the window 20000-30000 is passed between 800 and 1200 ms
    // of each 2000 ms cycle.
    let mut inside_seen = 0;
    let mut outside_seen = 0;
    for ms in ["500", "810", "1000", "1190", "1500", "2900", "3300", "4200"] {
        let d = run("decam_cyclic.il", &["--wire", "Y1:X0", "--ms", ms], &dumps);
        assert_eq!(int(&d, "D2000"), 5200, "offset 0: version");
        assert_eq!(int(&d, "D2039"), 40);
        assert_eq!(int(&d, "D2002"), 0, "no error");
        assert_eq!(int(&d, "D8067"), 0);
        let flags = int(&d, "D2001");
        assert_ne!(flags & 1, 0, "bit 0: initialised");
        assert_ne!(flags & (1 << 6), 0, "bit 6: cyclic");
        assert_eq!(flags & (1 << 3), 0, "no error flag");
        let master = int(&d, "DD2025");
        let counted = int(&d, "C231");
        assert_eq!(
            master,
            counted.rem_euclid(50000),
            "master in cycle at {ms} ms"
        );
        assert_eq!(int(&d, "DD2027"), master, "no master zoom");
        let inside = (20000..=30000).contains(&master);
        assert_eq!(
            int(&d, "Y7") == 1,
            inside,
            "Y7 at master {master} ({ms} ms)"
        );
        assert_eq!(flags & (1 << 10) != 0, inside, "bit 10 at master {master}");
        if inside {
            inside_seen += 1;
        } else {
            outside_seen += 1;
        }
        let pulses = int(&d, "DD8140");
        assert_eq!(
            pulses,
            int(&d, "DD2019"),
            "D8140 = slave position at {ms} ms"
        );
        let expected = table_value(CYCLIC_TABLE, master);
        assert!(
            (pulses as f64 - expected).abs() <= 1.0,
            "slave {pulses}, table {expected} at master {master}"
        );
        assert_eq!(int(&d, "M8147"), 1, "Y0 busy while the cam runs");
        if counted >= 50000 {
            assert_ne!(flags & 2, 0, "bit 1: a cycle completed");
        }
    }
    assert!(inside_seen >= 3 && outside_seen >= 3);
}

#[test]
fn cyclic_example_sync_edges_are_inclusive() {
    // 25 counts per ms: master 20000 is reached at 800 ms, 30000 at 1200 ms.
    for (ms, master, on) in [
        ("799", 19975, false),
        ("800", 20000, true),
        ("1200", 30000, true),
        ("1201", 30025, false),
    ] {
        let d = run(
            "decam_cyclic.il",
            &["--wire", "Y1:X0", "--ms", ms],
            &["DD2025", "Y7"],
        );
        assert_eq!(int(&d, "DD2025"), master, "at {ms} ms");
        assert_eq!(int(&d, "Y7") == 1, on, "Y7 at master {master}");
    }
}

#[test]
fn noncyclic_example_section_4_2_3_runs_three_cycles() {
    let dumps = ["D1001", "DD8140", "DD1019", "M8147", "Y7", "C231", "D8067"];
    let args = |ms: &'static str| ["--wire", "Y1:X0", "--set", "X2=1", "--ms", ms];
    // Each cycle is 100000 counts = 2 s at 50 kHz. Mid-third cycle: running.
    let d = run("decam_noncyclic.il", &args("5000"), &dumps);
    assert_eq!(int(&d, "D8067"), 0);
    assert_eq!(int(&d, "M8147"), 1);
    let flags = int(&d, "D1001");
    assert_ne!(flags & (1 << 7), 0, "bit 7: noncyclic");
    assert_ne!(flags & 1, 0);
    assert_ne!(flags & 2, 0, "bit 1: cycles completed");
    assert!(int(&d, "DD8140") > 3000, "mid-cycle the slave is far out");
    assert_eq!(int(&d, "DD8140"), int(&d, "DD1019"));
    assert_eq!(int(&d, "Y7"), 1, "sync window 40000-60000 at mid-cycle");
    // Where a fourth cycle would be mid-way: stopped at the table's end.
    let d = run("decam_noncyclic.il", &args("7000"), &dumps);
    assert!(int(&d, "C231") > 340_000, "the master keeps running");
    assert_eq!(int(&d, "DD8140"), 0, "the slave stopped after three cycles");
    assert_eq!(int(&d, "DD1019"), 0);
    assert_eq!(int(&d, "M8147"), 0, "Y0 no longer busy");
    assert_eq!(int(&d, "Y7"), 0);
    let flags = int(&d, "D1001");
    assert_ne!(
        flags & (1 << 9),
        0,
        "bit 9: stopped at the end of its cycles"
    );
    assert_ne!(flags & 1, 0, "re-armed for the next X2 edge after 5 ms");
}

#[test]
fn noncyclic_example_waits_for_x2() {
    let d = run(
        "decam_noncyclic.il",
        &["--wire", "Y1:X0", "--ms", "1000"],
        &["D1001", "DD8140", "M8147", "C231"],
    );
    assert!(int(&d, "C231") > 40_000, "the master runs");
    assert_eq!(int(&d, "DD8140"), 0, "no start signal, no slave motion");
    assert_ne!(int(&d, "D1001") & 1, 0, "initialised and waiting");
}

#[test]
fn rotary_cut_demo() {
    let d = run(
        "ecamtbx_rotary_cut.il",
        &["--scans", "1"],
        &["D500", "D2038", "D2039", "D8067"],
    );
    let points = int(&d, "D500");
    assert!(points >= 10, "{d:?}");
    assert_eq!(int(&d, "D2038"), points);
    assert_eq!(int(&d, "D2039"), 40);
    assert_eq!(int(&d, "D8067"), 0);
    let last = format!("DD{}", 2040 + 4 * (points - 1));
    let d = run(
        "ecamtbx_rotary_cut.il",
        &["--scans", "1"],
        &["DD2040", last.as_str()],
    );
    assert_eq!(int(&d, "DD2040"), 0);
    assert_eq!(int(&d, &last), 3183, "the table spans the cut length");
}

#[test]
fn flying_saw_demo_forward_and_return() {
    let d = run(
        "ecamtbx_flying_saw.il",
        &["--scans", "1"],
        &["D500", "D501", "D8067"],
    );
    assert_eq!(int(&d, "D8067"), 0);
    for (result, base, stroke) in [("D500", 2000, 2000), ("D501", 3000, -2000)] {
        let points = int(&d, result);
        assert!(points >= 10, "{d:?}");
        let last = base + 40 + 4 * (points - 1);
        let (m, s) = (format!("DD{last}"), format!("DD{}", last + 2));
        let t = run(
            "ecamtbx_flying_saw.il",
            &["--scans", "1"],
            &[m.as_str(), s.as_str()],
        );
        assert_eq!(int(&t, &m), 1750);
        assert_eq!(int(&t, &s), stroke);
    }
}

#[test]
fn s_curve_demo() {
    let d = run(
        "ecamtbx_s_curve.il",
        &["--scans", "1"],
        &[
            "D500", "D2038", "DD110", "DD114", "DD116", "D119", "DD2836", "DD2838",
        ],
    );
    assert_eq!(int(&d, "D500"), 200, "resolution 200");
    assert_eq!(int(&d, "D2038"), 200);
    assert_eq!(int(&d, "D119"), 200, "P13 result");
    assert_eq!(int(&d, "DD110"), 100, "P8: 100 ms of deceleration");
    assert_eq!(int(&d, "DD114"), 100, "P10: 100 ms at top speed");
    assert_eq!(int(&d, "DD116"), 50000, "P11: 50 kHz reached");
    // Last point (199) at D2040 + 4*199 = D2836: 300 ms, 10000 pulses.
    assert_eq!(int(&d, "DD2836"), 300);
    assert_eq!(int(&d, "DD2838"), 10000);
}

#[test]
fn key_point_case_runs_as_a_cam() {
    let d = run(
        "ecamtbx_key_points.il",
        &["--ms", "150"],
        &[
            "D100", "D101", "D500", "D2038", "DD2436", "DD2438", "DD2027", "DD8140", "D8067",
        ],
    );
    assert_eq!(int(&d, "D500"), 100);
    assert_eq!(int(&d, "D100"), 100, "S0: result");
    assert_eq!(int(&d, "D101"), 0, "S0+1: no error");
    assert_eq!(int(&d, "DD2436"), 2000, "last point master");
    assert_eq!(int(&d, "DD2438"), 0, "last point slave");
    // K1 time base: it reads 0 when the cam starts, on the first 100 µs
    // hardware tick; 150 ms later it reads 1499 counts, inside the dwell
    // at key point 2 (slave 2000).
    assert_eq!(int(&d, "DD2027"), 1499);
    assert_eq!(int(&d, "DD8140"), 2000);
}

#[test]
fn bad_table_sets_6782_and_clears_when_corrected() {
    // A copy of the cyclic example with point 3's master below point 2's.
    let dir = std::env::temp_dir().join(format!("ecam-plc-ecam-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let source = std::fs::read_to_string(example("decam_cyclic.il")).unwrap();
    let bad = source.replace("DMOV K15000 D2052", "DMOV K9000 D2052");
    let path = dir.join("bad_table.il");
    std::fs::write(&path, bad).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["plc", "run"])
        .arg(&path)
        .args(["--wire", "Y1:X0", "--ms", "200"])
        .args([
            "--dump", "D8067", "--dump", "M8067", "--dump", "D2002", "--dump", "D2001",
        ])
        .args(["--dump", "DD8140", "--dump", "M8147"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let d: Value = serde_json::from_slice(&out.stdout).unwrap();
    let d = d.as_object().unwrap();
    assert_eq!(int(d, "D8067"), 6782);
    assert_eq!(int(d, "M8067"), 1);
    assert_eq!(int(d, "D2002"), 3, "error register: the section number");
    let flags = int(d, "D2001");
    assert_ne!(flags & (1 << 3), 0);
    assert_ne!(flags & (1 << 5), 0);
    assert_eq!(flags & 1, 0, "not initialised");
    assert_eq!(int(d, "DD8140"), 0, "the cam did not start");
    // Corrected by `--set` before the run: the same program runs clean.
    let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["plc", "run"])
        .arg(example("decam_cyclic.il"))
        .args([
            "--wire", "Y1:X0", "--ms", "200", "--dump", "D8067", "--dump", "D2002",
        ])
        .output()
        .unwrap();
    let d: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(d["D8067"], 0);
    assert_eq!(d["D2002"], 0);
    std::fs::remove_dir_all(&dir).ok();
}

/// `decam_flow.il`: the manual's flow charts as a program. Cycles of 200 ms
/// (5000 counts at 25 kHz); three cuts a run, then a 500 ms dwell (T0), then
/// the next run. Times are chosen away from the cycle seams. Each cut logs
/// the master position C231 through index register Z0 (DD300, DD302,
/// DD304): the seams are at whole multiples of 5000 counts, and the dwell
/// stops the master, so run r's cuts are at 15000·(r−1) + 5000·k. The cut
/// count shows on the word group K1Y20.
#[test]
fn decam_flow_counts_cuts_stops_after_n_and_dwells() {
    let dumps = [
        "D2001", "D2002", "D8067", "D100", "D101", "D102", "M0", "M1", "Y10", "DD300", "DD302",
        "DD304", "Z0", "V0", "Y20", "Y21", "Y22", "Y23",
    ];
    // (ms, cuts in this run D101, runs completed D102, running M0, the cut log)
    for (ms, cuts, runs, running, log) in [
        ("100", 0, 0, true, [0, 0, 0]),
        ("300", 1, 0, true, [5000, 0, 0]),
        ("500", 2, 0, true, [5000, 10000, 0]),
        ("700", 3, 1, false, [5000, 10000, 15000]),
        ("1000", 3, 1, false, [5000, 10000, 15000]),
        ("1400", 1, 1, true, [20000, 10000, 15000]),
        ("2000", 3, 2, false, [20000, 25000, 30000]),
        ("2500", 1, 2, true, [35000, 25000, 30000]),
        ("3000", 3, 3, false, [35000, 40000, 45000]),
    ] {
        let d = run("decam_flow.il", &["--wire", "Y1:X0", "--ms", ms], &dumps);
        assert_eq!(int(&d, "D2002"), 0, "no block error at {ms} ms");
        assert_eq!(int(&d, "D8067"), 0, "no operation error at {ms} ms");
        assert_eq!(int(&d, "D100"), 3);
        assert_eq!(int(&d, "D101"), cuts, "cuts at {ms} ms");
        assert_eq!(int(&d, "D102"), runs, "runs at {ms} ms");
        assert_eq!(int(&d, "M0") == 1, running, "M0 at {ms} ms");
        assert_eq!(int(&d, "M1") == 1, !running, "dwell M1 at {ms} ms");
        let flags = int(&d, "D2001");
        assert_eq!(flags & 1 != 0, running, "flag bit 0 at {ms} ms");
        assert_eq!(flags & 2, 0, "flag bit 1 is reset once counted ({ms} ms)");
        assert_eq!(int(&d, "Y10") == 1, running, "Y10 follows bit 0 ({ms} ms)");
        let logged = [int(&d, "DD300"), int(&d, "DD302"), int(&d, "DD304")];
        assert_eq!(logged, log, "cut log at {ms} ms");
        assert_eq!(int(&d, "Z0"), 2 * cuts, "Z0 steps 2 words a cut ({ms} ms)");
        assert_eq!(int(&d, "V0"), 0);
        let lamps = (0..4).fold(0, |v, i| v | int(&d, &format!("Y2{i}")) << i);
        assert_eq!(lamps, cuts, "K1Y20 shows the cut count ({ms} ms)");
    }
}
