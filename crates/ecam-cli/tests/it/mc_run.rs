//! `ecam mc run`: document 001's motion-controller face from the command line.

use std::path::Path;

use crate::common::{ecam, fails, ok, scratch_dir};

fn example(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/mc")
        .join(name)
        .display()
        .to_string()
}

fn values(stdout: &str) -> Vec<i64> {
    stdout
        .lines()
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            v["value"].as_i64().unwrap()
        })
        .collect()
}

#[test]
fn the_single_turn_start_example_begins_at_minus_2000() {
    // Document 001: start at master 20000 with the slave at -1500; the
    // equivalent nearest to -1500 of the table's 1000 is -2000.
    let out = ok(ecam(&["mc", "run", &example("single_turn_start.mc")]));
    assert_eq!(values(&out)[..4], [-2000, -1500, -1000, -500]);
}

#[test]
fn every_shipped_script_runs() {
    for entry in std::fs::read_dir(Path::new(&example(""))).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "mc") {
            let out = ok(ecam(&["mc", "run", path.to_str().unwrap()]));
            assert!(!out.is_empty(), "{}", path.display());
        }
    }
}

#[test]
fn a_bad_line_names_the_file_and_line_and_runs_nothing() {
    let dir = scratch_dir("mc-run-bad");
    let script = dir.join("bad.mc");
    std::fs::write(
        &script,
        "ECAMTable t 0 0, 100 100\nGetCommandPosition 1\nStartECAM 0 1 Sideways t\n",
    )
    .unwrap();
    let out = ecam(&["mc", "run", script.to_str().unwrap()]);
    assert!(out.stdout.is_empty(), "nothing ran");
    let err = fails(out);
    assert!(err.contains("bad.mc:3"), "{err}");
}
