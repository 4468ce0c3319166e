//! `ecam ethercat run`: the shipped rotary-knife configuration on emulated
//! drives, the summary line, and configuration errors.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::{ecam, fails, ok};

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/ethercat/rotary-knife.toml")
}

#[test]
fn rotary_knife_runs_on_emulated_drives() {
    let config = example();
    let out = ok(ecam(&[
        "ethercat",
        "run",
        config.to_str().unwrap(),
        "--emulated",
        "2",
        "--cycles",
        "400",
        "--status-ms",
        "0",
    ]));
    assert!(
        out.contains("segment: 2 drives in OP, SYNC0 every 1000 µs"),
        "{out}"
    );
    let summary: Value = serde_json::from_str(out.lines().last().unwrap()).unwrap();
    assert_eq!(summary["drives"], 2);
    assert_eq!(summary["cycles"], 400);
    assert_eq!(summary["faults"].as_array().unwrap().len(), 0);
    // A loaded host may delay a reply past the cycle's deadline: counted
    // as a lost cycle, never as a fault.
    assert_eq!(summary["working_counter_errors"], summary["lost_cycles"]);
    assert!(summary["lost_cycles"].as_u64().unwrap() < 20, "{summary}");
    let master = summary["virtual_master"].as_i64().unwrap();
    // 400 cycles at 7 counts, then the stop's 500 ms ramp (7 · 500 / 2).
    assert!(master > 7 * 380 && master <= 7 * 400 + 1750, "{master}");
    // The shaft trails the master by the drive lag; the knife turned.
    let actual = summary["actual"].as_array().unwrap();
    assert!(actual[0].as_i64().unwrap() > master - 100);
    assert!(actual[1].as_i64().unwrap() > 0);
    let histogram = summary["lateness"]["histogram_us"].as_array().unwrap();
    let wakeups: u64 = histogram.iter().map(|b| b[1].as_u64().unwrap()).sum();
    assert_eq!(wakeups, 400);
}

#[test]
fn configuration_errors_are_clear() {
    let dir = crate::common::scratch_dir("ethercat-config");
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "cycle_us = 5\n[[axis]]\ndrive = 0\n[axis.table]\npoints = [[0, 0], [10, 10]]\n",
    )
    .unwrap();
    let err = fails(ecam(&[
        "ethercat",
        "run",
        bad.to_str().unwrap(),
        "--emulated",
        "1",
    ]));
    assert!(err.contains("cycle_us = 5 is out of range"), "{err}");
    let no_iface = dir.join("no-iface.toml");
    std::fs::write(
        &no_iface,
        "cycle_us = 1000\n[[axis]]\ndrive = 0\n[axis.table]\npoints = [[0, 0], [10, 10]]\n",
    )
    .unwrap();
    let err = fails(ecam(&["ethercat", "run", no_iface.to_str().unwrap()]));
    assert!(err.contains("no interface"), "{err}");
    // A drive the segment does not have.
    let err = fails(ecam(&[
        "ethercat",
        "run",
        example().to_str().unwrap(),
        "--emulated",
        "1",
        "--cycles",
        "1",
    ]));
    assert!(
        err.contains("drive 1 does not exist (the segment has 1)"),
        "{err}"
    );
    // [[drive]]: an identity the drive does not have, a start-up SDO
    // value outside its type.
    let text = std::fs::read_to_string(example()).unwrap();
    let wrong = dir.join("wrong-drive.toml");
    std::fs::write(
        &wrong,
        format!("{text}\n[[drive]]\ndrive = 1\nproduct_code = 0x1234\n"),
    )
    .unwrap();
    let err = fails(ecam(&[
        "ethercat",
        "run",
        wrong.to_str().unwrap(),
        "--emulated",
        "2",
    ]));
    assert!(
        err.contains("drive 1 (ecam emulated CSP drive) reports product_code 0x4543414d"),
        "{err}"
    );
    std::fs::write(
        &wrong,
        format!(
            "{text}\n[[drive]]\ndrive = 0\nsdo = [{{ index = 0x6065, type = \"u8\", value = 300 }}]\n"
        ),
    )
    .unwrap();
    let err = fails(ecam(&[
        "ethercat",
        "run",
        wrong.to_str().unwrap(),
        "--emulated",
        "2",
    ]));
    assert!(err.contains("value 300 does not fit type \"u8\""), "{err}");
}

#[cfg(unix)]
#[test]
fn sigterm_ends_a_run_with_the_drives_disabled_and_the_summary() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};

    let config = example();
    let mut child = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["ethercat", "run", config.to_str().unwrap()])
        .args(["--emulated", "2", "--status-ms", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let stdout = child.stdout.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    let reader = std::thread::spawn(move || {
        let mut lines = Vec::new();
        for line in std::io::BufRead::lines(std::io::BufReader::new(stdout)) {
            let Ok(line) = line else { break };
            let _ = tx.send(line.clone());
            lines.push(line);
        }
        lines
    });
    // The `cycle:` line comes once the drives are being enabled (and the
    // signal is watched); then let it run a little.
    loop {
        let line = rx.recv_timeout(Duration::from_secs(20)).unwrap();
        if line.starts_with("cycle:") {
            break;
        }
    }
    std::thread::sleep(Duration::from_millis(300));
    let pid = child.id().to_string();
    assert!(
        Command::new("kill")
            .args(["-TERM", &pid])
            .status()
            .unwrap()
            .success()
    );
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        assert!(start.elapsed() < Duration::from_secs(20), "did not stop");
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(status.success(), "{status}");
    let out = reader.join().unwrap();
    let summary: Value = serde_json::from_str(out.last().unwrap()).unwrap();
    assert_eq!(summary["state"], "stopped");
    assert!(summary["cycles"].as_u64().unwrap() > 0);
}
