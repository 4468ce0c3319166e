//! `ecam plc run`: the command-line contract (docs/architecture.md), driven through the real binary.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// Writes `source` to a program file named `name` in the test's scratch directory.
fn program(name: &str, source: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&path, source).unwrap();
    path
}

fn ecam(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(args)
        .output()
        .unwrap()
}

fn ok_stdout(args: &[&str]) -> String {
    let out = ecam(args);
    assert!(
        out.status.success(),
        "ecam {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn failure(args: &[&str]) -> String {
    let out = ecam(args);
    assert!(!out.status.success(), "ecam {args:?} should fail");
    assert!(out.stdout.is_empty(), "nothing on stdout on failure");
    String::from_utf8(out.stderr).unwrap()
}

#[test]
fn dump_formats_follow_the_contract() {
    let p = program(
        "dump_formats.il",
        "LD M8000\nMOV K5200 D2000\nMOV K-2 D2019\nMOV K1 D2020\nDMOV K-100000 D2030\nOUT Y7\nOUT C0 K5\n",
    );
    let p = p.to_str().unwrap();
    let out = ok_stdout(&[
        "plc", "run", p, "--scans", "3", "--dump", "D2000", "--dump", "D2019:2", "--dump",
        "DD2019", "--dump", "Y7", "--dump", "DD2030", "--dump", "Y6", "--dump", "C0", "--dump",
        "D2030",
    ]);
    assert_eq!(
        out,
        "{\"D2000\": 5200, \"D2019\": -2, \"D2020\": 1, \"DD2019\": 131070, \"Y7\": 1, \"DD2030\": -100000, \"Y6\": 0, \"C0\": 1, \"D2030\": 31072}\n"
    );
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(json["DD2030"], -100000);
}

#[test]
fn key_order_is_the_order_of_the_dump_arguments() {
    let p = program("order.il", "LD M8000\nMOV K1 D9\n");
    let out = ok_stdout(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--scans",
        "1",
        "--dump",
        "Y0",
        "--dump",
        "D9",
        "--dump",
        "M5",
        "--dump",
        "d9",
    ]);
    assert_eq!(out, "{\"Y0\": 0, \"D9\": 1, \"M5\": 0}\n");
}

#[test]
fn set_forms_apply_before_the_first_scan() {
    let p = program(
        "set_forms.il",
        "LD M8002\nAND X2\nOUT Y0\nLD M8002\nAND M0\nOUT Y1\nLD M8002\nDEMOV D106 D110\nDMOV D102 D120\n",
    );
    let out = ok_stdout(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--scans",
        "1",
        "--set",
        "D100=3183",
        "--set",
        "DD102=-3183",
        "--set",
        "DE106=1.6667",
        "--set",
        "M0=1",
        "--set",
        "X2=1",
        "--set",
        "D104=65535",
        "--dump",
        "D100",
        "--dump",
        "DD102",
        "--dump",
        "DE110",
        "--dump",
        "DD120",
        "--dump",
        "Y0:2",
        "--dump",
        "D104",
    ]);
    assert_eq!(
        out,
        "{\"D100\": 3183, \"DD102\": -3183, \"DE110\": 1.6667, \"DD120\": -3183, \"Y0\": 1, \"Y1\": 1, \"D104\": -1}\n"
    );
}

#[test]
fn wire_loops_pulses_into_the_counter() {
    let p = program(
        "wire.il",
        "LD M8000\nOUT C231 K2147483647\nDPLSY K10000 K0 Y1\n",
    );
    let p = p.to_str().unwrap();
    let wired = ok_stdout(&[
        "plc", "run", p, "--ms", "100", "--wire", "Y1:X0", "--dump", "C231", "--dump", "DD8142",
        "--dump", "X0",
    ]);
    assert_eq!(wired, "{\"C231\": 1000, \"DD8142\": 1000, \"X0\": 0}\n");
    let unwired = ok_stdout(&[
        "plc", "run", p, "--ms", "100", "--dump", "C231", "--dump", "DD8142",
    ]);
    assert_eq!(unwired, "{\"C231\": 0, \"DD8142\": 1000}\n");
}

#[test]
fn scan_period_sets_simulated_time() {
    let p = program("scan_period.il", "LD M8000\nADD D0 K1 D0\n");
    let p = p.to_str().unwrap();
    assert_eq!(
        ok_stdout(&["plc", "run", p, "--ms", "10", "--dump", "D0"]),
        "{\"D0\": 10}\n"
    );
    assert_eq!(
        ok_stdout(&[
            "plc",
            "run",
            p,
            "--ms",
            "10",
            "--scan-us",
            "2500",
            "--dump",
            "D0"
        ]),
        "{\"D0\": 4}\n"
    );
    assert_eq!(
        ok_stdout(&[
            "plc",
            "run",
            p,
            "--scans",
            "7",
            "--scan-us",
            "2500",
            "--dump",
            "D0"
        ]),
        "{\"D0\": 7}\n"
    );
}

#[test]
fn trace_writes_one_row_per_scan() {
    let p = program("trace.il", "LD M8000\nADD D0 K1 D0\nDPLSY K1000 K0 Y0\n");
    let csv = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("trace.csv");
    let _ = std::fs::remove_file(&csv);
    let out = ok_stdout(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--scans",
        "3",
        "--scan-us",
        "2000",
        "--trace",
        csv.to_str().unwrap(),
        "--trace-dev",
        "D0",
        "DD8140",
        "M8147",
    ]);
    assert_eq!(out, "{}\n");
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(
        text,
        "t_us,D0,DD8140,M8147\n0,1,0,0\n2000,2,2,1\n4000,3,4,1\n"
    );
}

#[test]
fn parse_errors_name_file_and_line() {
    let p = program("bad_line.il", "; comment\nLD X0\nMOV K1 Q7\n");
    let err = failure(&["plc", "run", p.to_str().unwrap(), "--scans", "1"]);
    assert!(
        err.contains("bad_line.il:3: MOV operand 2: unknown device `Q7`"),
        "{err}"
    );
    let p = program("bad_range.il", "LD X0\nOUT Y0\nLD X1\nMOV K1 D8512\n");
    let err = failure(&["plc", "run", p.to_str().unwrap(), "--scans", "1"]);
    assert!(
        err.contains("bad_range.il:4: ") && err.contains("out of range"),
        "{err}"
    );
}

#[test]
fn bad_arguments_are_errors() {
    let p = program("ok.il", "LD M8000\nOUT Y0\n");
    let p = p.to_str().unwrap();
    assert!(
        failure(&["plc", "run", p, "--scans", "1", "--dump", "Q1"]).contains("unknown device `Q1`")
    );
    assert!(
        failure(&["plc", "run", p, "--scans", "1", "--dump", "D9000"]).contains("out of range")
    );
    assert!(
        failure(&["plc", "run", p, "--scans", "1", "--dump", "D8511:2"]).contains("past the end")
    );
    assert!(failure(&["plc", "run", p, "--scans", "1", "--set", "D1"]).contains("DEV=VALUE"));
    assert!(
        failure(&["plc", "run", p, "--scans", "1", "--set", "D1=70000"]).contains("-32768..65535")
    );
    assert!(failure(&["plc", "run", p, "--scans", "1", "--set", "M1=2"]).contains("0 or 1"));
    assert!(
        failure(&["plc", "run", p, "--scans", "1", "--set", "X8=1"]).contains("unknown device")
    );
    assert!(failure(&["plc", "run", p, "--scans", "1", "--wire", "Y5:X0"]).contains("Y0-Y3"));
    assert!(
        failure(&["plc", "run", p, "--scans", "1", "--wire", "Y1:X7"])
            .contains("no high-speed counter")
    );
    assert!(failure(&["plc", "run", p, "--scans", "1", "--scan-us", "0"]).contains("scan period"));
    assert!(
        !failure(&["plc", "run", p]).is_empty(),
        "--scans or --ms is required"
    );
    assert!(
        !failure(&["plc", "run", p, "--scans", "1", "--ms", "1"]).is_empty(),
        "not both"
    );
    assert!(failure(&["plc", "run", "/nonexistent/x.il", "--scans", "1"]).contains("cannot read"));
}

#[test]
fn operation_errors_are_reported_through_d8067() {
    let p = program("op_error.il", "LD M8000\nPLSY K-5 K10 Y0\n");
    let out = ecam(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--scans",
        "2",
        "--dump",
        "D8067",
        "--dump",
        "M8067",
    ]);
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "{\"D8067\": 6705, \"M8067\": 1}\n"
    );
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(
        err.matches("op_error.il:2: operation error 6705").count(),
        1,
        "{err}"
    );
}

/// The commands written at the top of `examples/plc/basic_*.il` print what they promise.
#[test]
fn basic_examples_print_what_their_comments_say() {
    let examples = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/plc");
    let loopback = examples.join("basic_loopback.il");
    let out = ok_stdout(&[
        "plc",
        "run",
        loopback.to_str().unwrap(),
        "--wire",
        "Y1:X0",
        "--ms",
        "300",
        "--dump",
        "C231",
        "--dump",
        "DD8142",
        "--dump",
        "Y7",
        "--dump",
        "M8148",
    ]);
    assert_eq!(
        out,
        "{\"C231\": 5000, \"DD8142\": 5000, \"Y7\": 1, \"M8148\": 0}\n"
    );
    let arith = examples.join("basic_arith.il");
    let out = ok_stdout(&[
        "plc",
        "run",
        arith.to_str().unwrap(),
        "--scans",
        "10",
        "--set",
        "D10=5",
        "--set",
        "X2=1",
        "--dump",
        "D0:2",
        "--dump",
        "M10:3",
    ]);
    assert_eq!(
        out,
        "{\"D0\": 10, \"D1\": 1, \"M10\": 1, \"M11\": 0, \"M12\": 0}\n"
    );
}

#[test]
fn set_input_edge_counts_on_its_high_speed_counter() {
    let p = program(
        "edge.il",
        "LD M8000\nOUT C231 K1\nOUT C236 K1\nLD C231\nOUT Y7\n",
    );
    let out = ok_stdout(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--scans",
        "3",
        "--set",
        "X0=1",
        "--dump",
        "C231",
        "--dump",
        "C236",
        "--dump",
        "Y7",
    ]);
    assert_eq!(out, "{\"C231\": 1, \"C236\": 0, \"Y7\": 1}\n");
}

#[test]
fn stop_flag_set_from_outside_holds_the_output() {
    let p = program("stop.il", "LD M8000\nDPLSY K10000 K0 Y0\n");
    let out = ok_stdout(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--ms",
        "10",
        "--set",
        "M8145=1",
        "--dump",
        "DD8140",
        "--dump",
        "M8147",
    ]);
    assert_eq!(out, "{\"DD8140\": 0, \"M8147\": 0}\n");
}

#[test]
fn word_bits_and_timers_are_dump_and_set_names() {
    let p = program(
        "bits_timers.il",
        "LD M8000\nOUT T0 K5\nLD T0\nSET D100.3\nLD D200.F\nOUT Y7\n",
    );
    let out = ok_stdout(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--ms",
        "1000",
        "--set",
        "D200.F=1",
        "--dump",
        "T0",
        "--dump",
        "D100.3",
        "--dump",
        "D100",
        "--dump",
        "Y7",
    ]);
    // T0 counts 100 ms units up to its set value 5; then D100 bit 3 is set.
    assert_eq!(out.trim(), r#"{"T0": 5, "D100.3": 1, "D100": 8, "Y7": 1}"#);
    assert!(
        failure(&[
            "plc",
            "run",
            p.to_str().unwrap(),
            "--ms",
            "1",
            "--dump",
            "D100.G"
        ])
        .contains("hex digit")
    );
}

#[test]
fn load_writes_a_table_file_as_the_blocks_register_image() {
    let p = program(
        "load_table.il",
        "LD M8000\nMOV K1 D2005\nDECAM K1 D2000 X2 Y0 Y4\nEND\n",
    );
    let table = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/tables/rotary-cut.csv"
    );
    let load = format!("D2000={table}");
    let out = ok_stdout(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--ms",
        "100",
        "--load",
        &load,
        "--dump",
        "D2038",
        "--dump",
        "D2002",
        "--dump",
        "DD2044",
    ]);
    let dump: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(dump["D2038"], 100, "the table's point count");
    assert_eq!(dump["D2002"], 0, "a good block");
    assert_eq!(dump["DD2044"], 201, "point 1's master, as in the file");
    // A block whose table would run past D8511, and a non-D block.
    let err = failure(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--ms",
        "1",
        "--load",
        &format!("D8400={table}"),
    ]);
    assert!(err.contains("6783") && err.contains("D8512"), "{err}");
    let out = ecam(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--ms",
        "1",
        "--load",
        &format!("M0={table}"),
    ]);
    // A usage mistake, naming what M0 is.
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("M0 is an auxiliary relay"), "{err}");
}

#[test]
fn index_registers_are_dump_set_and_trace_names() {
    let p = program(
        "index_registers.il",
        "LD M8000\nMOV K123 D10Z0\nDMOV K70000 Z1\nMOV K-1 K2Y0Z2\n",
    );
    let trace = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("index_registers.csv");
    let out = ok_stdout(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--scans",
        "2",
        "--set",
        "Z0=5",
        "--set",
        "Z2=8",
        "--dump",
        "Z0",
        "--dump",
        "D15",
        "--dump",
        "V1",
        "--dump",
        "Z1",
        "--dump",
        "Y7:3",
        "--trace",
        trace.to_str().unwrap(),
        "--trace-dev",
        "Z1",
        "--trace-dev",
        "V1",
    ]);
    // D10Z0 = D15; 70000 = V1 1, Z1 4464; K2Y0Z2 = K2Y10 (Z2 = 8 = 10 octal).
    assert_eq!(
        out.trim(),
        r#"{"Z0": 5, "D15": 123, "V1": 1, "Z1": 4464, "Y7": 0, "Y10": 1, "Y11": 1}"#
    );
    let csv = std::fs::read_to_string(&trace).unwrap();
    assert!(csv.starts_with("t_us,Z1,V1\n"), "{csv}");
    assert!(csv.contains(",4464,1\n"), "{csv}");
    let err = failure(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--scans",
        "1",
        "--dump",
        "Z8",
    ]);
    assert!(err.contains("V0-V7, Z0-Z7"), "{err}");
    let err = failure(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--scans",
        "1",
        "--set",
        "V0=70000",
    ]);
    assert!(err.contains("-32768..65535"), "{err}");
}
