//! Bounded work: requests for more than the shared limits
//! (`ecam_core::limits`) are refused at once with a clear error, whatever
//! the face.

use std::time::{Duration, Instant};

use crate::common::{ecam, fails, scratch_dir};

/// Refused, quickly, with a message naming the limit.
fn refused(args: &[&str], needle: &str) {
    let start = Instant::now();
    let err = fails(ecam(args));
    assert!(err.contains(needle), "{args:?}: {err}");
    assert!(
        start.elapsed() < Duration::from_secs(20),
        "{args:?} took too long"
    );
}

#[test]
fn huge_point_counts_are_refused() {
    refused(&["law", "cycloid", "--points", "100000000000"], "limit");
    refused(
        &[
            "table",
            "gen",
            "function",
            "--expr",
            "x",
            "--points",
            "100000000000",
        ],
        "limit",
    );
}

#[test]
fn huge_expressions_are_refused() {
    let long = vec!["x"; 5000].join("+");
    refused(
        &["table", "gen", "function", "--expr", &long],
        "limit is 4096",
    );
}

#[test]
fn huge_runs_are_refused() {
    let dir = scratch_dir("limits");
    let program = dir.join("p.il");
    std::fs::write(&program, "LD M8000\nOUT Y0\n").unwrap();
    refused(
        &[
            "plc",
            "run",
            program.to_str().unwrap(),
            "--ms",
            "18446744073709551615",
        ],
        "the limit is 100000000",
    );
    let script = dir.join("s.pmd");
    std::fs::write(&script, "Tick 9223372036854775807\n").unwrap();
    let out = ecam(&["pmd", "run", script.to_str().unwrap(), "--strict"]);
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("0 to 100000000"), "{text}");
    let mc = dir.join("s.mc");
    std::fs::write(&mc, "Tick 9223372036854775807\n").unwrap();
    refused(&["mc", "run", mc.to_str().unwrap()], "0 to 100000000");
    let scenario = dir.join("s.toml");
    std::fs::write(
        &scenario,
        "duration_s = 100000\n[table]\npoints = [[0, 0], [10, 10]]\n[master]\nmoves = []\n",
    )
    .unwrap();
    refused(
        &["simulate", scenario.to_str().unwrap()],
        "the limit is 100000000",
    );
}

#[test]
fn huge_table_files_are_refused_before_they_are_read() {
    let dir = scratch_dir("limits-file");
    let path = dir.join("huge.csv");
    let file = std::fs::File::create(&path).unwrap();
    // A sparse 65 MiB file: nothing is written, the size alone is refused.
    file.set_len(65 * 1024 * 1024).unwrap();
    refused(
        &["table", "show", path.to_str().unwrap()],
        "limited to 67108864 bytes",
    );
}

/// Runs `ecam ARGS` and waits at most `deadline` (killing it then, and
/// failing): the run is bounded however long it asks for.
fn finishes_within(args: &[&str], deadline: Duration) -> std::process::Output {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{args:?} still runs after {deadline:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

#[test]
fn one_work_budget_per_run_bounds_what_a_short_input_asks_for() {
    let dir = scratch_dir("limits-budget");
    // A 3-line loop: the watchdog stops it in its first scan; the rest of
    // the run is hardware ticks.
    let endless = dir.join("endless.il");
    std::fs::write(&endless, "P0\nLD M8000\nCJ P0\n").unwrap();
    let out = finishes_within(
        &[
            "plc",
            "run",
            endless.to_str().unwrap(),
            "--ms",
            "100000",
            "--dump",
            "D8061",
        ],
        Duration::from_secs(120),
    );
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        r#"{"D8061": 6105}"#
    );
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("endless.il:3: watchdog timer error 6105")
    );
    // A script's Ticks add up: refused before any runs.
    let mc = dir.join("ticks.mc");
    std::fs::write(&mc, "Tick 60000000\nTick 60000000\n").unwrap();
    refused(
        &["mc", "run", mc.to_str().unwrap()],
        "add up to more than the 100000000",
    );
    // A function table whose evaluations cannot fit: refused before any.
    let expr = vec!["sin(x/1000)"; 300].join("+");
    refused(
        &[
            "table",
            "gen",
            "function",
            "--expr",
            &expr,
            "--points",
            "1000000",
            "--to",
            "100000000",
        ],
        "more work than one run may do",
    );
    // A run whose ticks fill the budget has none left for its program.
    let small = dir.join("small.il");
    std::fs::write(&small, "LD M8000\nOUT Y0\n").unwrap();
    refused(
        &["plc", "run", small.to_str().unwrap(), "--ms", "10000000"],
        "more work than one run may do",
    );
}
