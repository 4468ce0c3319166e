//! `ecam pmd run`: document 002's examples through the real binary.
#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/pmd")
}

/// Runs `ecam pmd run FILE ARGS…`; gives the parsed output lines.
fn run_file(file: &Path, args: &[&str]) -> Vec<Value> {
    let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["pmd", "run"])
        .arg(file)
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("not JSON: {l}: {e}")))
        .collect()
}

/// Writes `script` to a fresh temporary file and runs it.
fn run_text(name: &str, script: &str, args: &[&str]) -> Vec<Value> {
    let dir = std::env::temp_dir().join(format!("ecam-pmd-run-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.pmd"));
    std::fs::write(&file, script).unwrap();
    run_file(&file, args)
}

fn values(lines: &[Value]) -> Vec<i64> {
    lines.iter().map(|l| l["value"].as_i64().unwrap()).collect()
}

#[test]
fn three_entry_table_input_100_to_101_gives_200_to_202() {
    let lines = run_file(&examples().join("three_entry.pmd"), &[]);
    assert_eq!(values(&lines), [200, 202, 200, -2]);
    assert_eq!(
        lines[2],
        serde_json::json!({"cmd":"GetCam","axis":0,"param":"CamOutputOffset","value":200})
    );
}

#[test]
fn bumpless_start_offsets() {
    let lines = run_file(&examples().join("bumpless.pmd"), &[]);
    assert_eq!(lines[0]["param"], "CamOutputOffset");
    assert_eq!(values(&lines), [450, -975, 500, 520]);
}

#[test]
fn typical_command_sequence_with_real_numbers() {
    let lines = run_file(&examples().join("doc002_typical.pmd"), &[]);
    let v = values(&lines);
    // master 999: waiting; 1000: active (profile segment bits 15:13 = 1,
    // in motion bit 10), no jump, input offset -1000.
    assert_eq!(v[..2], [0, 0]);
    assert_eq!(v[2], 0x2400);
    assert_eq!(v[3..6], [0, 0, -1000]);
    // Half a table (cycloid at half rise), one table, stop pending at 1600,
    // stopped at the table end 1640 after two full tables, holding at 2000.
    assert_eq!(v[6..8], [500, 1000]);
    assert_eq!(v[8], 0x2400);
    assert_eq!(v[9..12], [2000, 0, 2000]);
    // Motion complete, breakpoint 1 and breakpoint 2 events.
    assert_eq!(v[12], 0x4005);
}

#[test]
fn typical_command_sequence_runs_unchanged() {
    // The document's listing, byte for byte (typographic quotes, the `…`
    // line), plus simulation commands after it. It never sets CamBufferID,
    // so the StartCam breakpoint raises a MotionError instead of starting.
    let listing = std::fs::read_to_string(examples().join("doc002_typical_verbatim.pmd")).unwrap();
    let script = format!(
        "{listing}\nMoveTo 1 2000 2000\nTick 2000\nGetActivityStatus\nGetEventStatus\nGetCam CamCounts\nGetCam CamSource\n"
    );
    let lines = run_text(
        "verbatim",
        &script,
        &["--define", "cam_table_0=0", "--define", "cam_table_1=10"],
    );
    assert_eq!(values(&lines), [0, 0x4014, 320, 1]);
}

#[test]
fn symbolic_values_must_be_defined() {
    let listing = std::fs::read_to_string(examples().join("doc002_typical_verbatim.pmd")).unwrap();
    let lines = run_text("undefined", &listing, &[]);
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[0]["cmd"], "WriteBuffer");
    assert_eq!(lines[0]["line"], 6);
    assert!(lines[0]["error"].as_str().unwrap().contains("cam_table_0"));
}

#[test]
fn refused_and_bad_commands_report_and_change_nothing() {
    let lines = run_text(
        "bad",
        "SetBufferLength 2 3
SetProfileMode 8
Update
SetCam CamCounts 300
Frobnicate 1
SetCam CamCounts 1
SetCam CamCounts
SetBufferWriteIndex 2 3
SetCam CamInputOffset 0
GetCam CamCounts
",
        &[],
    );
    assert_eq!(lines.len(), 6);
    for (line, cmd) in [
        (5, "Frobnicate"),
        (6, "SetCam"),
        (7, "SetCam"),
        (8, "SetBufferWriteIndex"),
        (9, "SetCam"),
    ] {
        let l = lines.iter().find(|l| l["line"] == line).unwrap();
        assert_eq!(l["cmd"], cmd);
        assert!(!l["error"].as_str().unwrap().is_empty());
    }
    assert_eq!(
        lines[5],
        serde_json::json!({"cmd":"GetCam","axis":0,"param":"CamCounts","value":300})
    );
}

#[test]
fn strict_mode_stops_with_an_error() {
    let dir = std::env::temp_dir().join(format!("ecam-pmd-strict-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("strict.pmd");
    std::fs::write(
        &file,
        "GetActualPosition\nSetCam CamCounts 5\nGetActualPosition\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["pmd", "run", "--strict"])
        .arg(&file)
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert_eq!(String::from_utf8(out.stdout).unwrap().lines().count(), 2);
    assert!(String::from_utf8_lossy(&out.stderr).contains(":2:"));
}

#[test]
fn missing_script_is_an_error() {
    let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["pmd", "run", "/nonexistent/script.pmd"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read script"));
}

#[test]
fn abrupt_and_smooth_stops() {
    let lines = run_file(&examples().join("stops.pmd"), &[]);
    // Smooth: held at the table end (input 200, output 400), cam inactive.
    // Abrupt at master 280: 400 + 2·(280 − 250) = 460.
    // Backwards smooth stop at master 190: 460 − 200 = 260. Motion complete.
    assert_eq!(values(&lines), [400, 0, 460, 260, 1]);
}

#[test]
fn smooth_stops_on_a_table_end_stop_there_at_once() {
    let lines = run_file(&examples().join("boundary_stops.pmd"), &[]);
    // Forwards onto the table end: inactive at once, held at 200 while the
    // master goes on (no second table, which would end at 400).
    // Backwards onto the table start, master resting: inactive at once,
    // held at 200, motion complete, and SetCam accepted again.
    assert!(lines.iter().all(|l| l.get("error").is_none()), "{lines:?}");
    assert_eq!(values(&lines), [0, 200, 0, 200, 1, 50]);
}

#[test]
fn stops_hold_a_simulated_move_and_the_cam_on_it() {
    let lines = run_file(&examples().join("master_stops.pmd"), &[]);
    assert!(lines.iter().all(|l| l.get("error").is_none()), "{lines:?}");
    // Abrupt stop of the master at 30: it rests (activity 0), the cam on
    // it stays active (0x2400) holding 60. Smooth stop at 115: held, cam
    // 230. Breakpoint abrupt stop at 150 (breakpoint 0 event only): cam 300.
    assert_eq!(values(&lines), [30, 0, 60, 0x2400, 115, 230, 150, 4, 300]);
}

#[test]
fn a_table_edited_while_running_takes_over_at_the_seam() {
    let lines = run_file(&examples().join("table_edit.pmd"), &[]);
    assert!(lines.iter().all(|l| l.get("error").is_none()), "{lines:?}");
    // The old copy to the table end (no step at the write), then the new
    // values continuing from 200.
    assert_eq!(values(&lines), [150, 200, 300, 500]);
}
