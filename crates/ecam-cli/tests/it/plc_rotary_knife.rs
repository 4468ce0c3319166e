//! A rotary knife built from the manual's parts: the ECAMTBX K100 demo table
//! run by DECAM as the manual's cyclic cam, so the knife turns on by one
//! revolution per cut, never jumps back and its direction output never flips.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::process::Command;

const PROGRAM: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../examples/plc/rotary_knife.il"
);

/// Feed pulses per cut and knife pulses per revolution of the demo.
const CUT: i64 = 3183;
const REVOLUTION: i64 = 1000;

#[test]
fn the_knife_turns_forward_cut_after_cut_and_the_counter_follows() {
    let dir = std::env::temp_dir().join(format!("ecam-knife-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let trace = dir.join("trace.csv");
    let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["plc", "run", PROGRAM, "--wire", "Y1:X0", "--ms", "2000"])
        .args(["--dump", "D500", "--dump", "D2001", "--dump", "DD2019"])
        .arg("--trace")
        .arg(&trace)
        .args(["--trace-dev", "DD2019", "--trace-dev", "DD8140"])
        .args(["--trace-dev", "C231", "--trace-dev", "DD2027"])
        .args(["--trace-dev", "Y4", "--trace-dev", "D2001"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let dump: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(dump["D500"], 100, "ECAMTBX made the 100-point table");
    let flags = dump["D2001"].as_i64().unwrap();
    assert_eq!(flags & 0b1000, 0, "no error flag: {flags:#b}");

    let text = std::fs::read_to_string(&trace).unwrap();
    let rows: Vec<Vec<i64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert!(rows.len() > 1900, "one row per 1 ms scan");
    let mut previous = i64::MIN;
    let mut revolutions_seen = 0;
    let (mut cuts, mut last_in_cycle) = (0i64, 0i64);
    for row in &rows {
        let (slave, counter, master, in_cycle) = (row[1], row[2], row[3], row[4]);
        let (direction, flags) = (row[5], row[6]);
        if master > 0 {
            assert_eq!(flags & (1 << 6), 1 << 6, "cyclic mode at t={} us", row[0]);
        }
        if counter > 0 {
            assert_eq!(
                direction, 1,
                "direction output stays forward at t={} us",
                row[0]
            );
        }
        // Each seam passed adds exactly one revolution: within the cut the
        // knife stands between the revolutions done and the next one.
        if in_cycle < last_in_cycle {
            cuts += 1;
        }
        last_in_cycle = in_cycle;
        assert!(
            (cuts * REVOLUTION..=(cuts + 1) * REVOLUTION).contains(&counter),
            "counter {counter} after {cuts} cuts at t={} us",
            row[0]
        );
        assert_eq!(
            slave, counter,
            "D8140 equals the slave position at t={} us",
            row[0]
        );
        assert!(
            slave >= previous,
            "the knife never turns back at t={} us",
            row[0]
        );
        previous = slave;
        assert!((0..CUT).contains(&in_cycle), "master in cycle {in_cycle}");
        if master > 0 {
            revolutions_seen = revolutions_seen.max(slave / REVOLUTION);
        }
    }
    // About 2 s of feed at 10 kHz (the trace's last row is the last scan
    // before the end): six whole cuts, so six whole knife revolutions.
    let last = rows.last().unwrap();
    assert!((19_900..=20_000).contains(&last[3]), "master {}", last[3]);
    assert_eq!(revolutions_seen, 6);
    assert_eq!(cuts, 6);
    assert!((6 * REVOLUTION..7 * REVOLUTION).contains(&last[1]));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_knife_changes_cut_length_twice_without_stepping_or_turning_back() {
    let dir = std::env::temp_dir().join(format!("ecam-knife-switch-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let trace = dir.join("trace.csv");
    let program = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/plc/rotary_knife_switch.il"
    );
    let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["plc", "run", program, "--wire", "Y1:X0", "--wire", "Y1:X1"])
        .args(["--ms", "4000", "--dump", "DD8140", "--dump", "D2001"])
        .arg("--trace")
        .arg(&trace)
        .args([
            "--trace-dev",
            "DD8140",
            "--trace-dev",
            "C231",
            "--trace-dev",
            "Y4",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let dump: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        dump["D2001"].as_i64().unwrap() & 0b1_0011_1000,
        0,
        "no error"
    );
    // 4 cuts of 3183, 5 of 2500 (the first seam after the second table was
    // written at 10000 is 12732; after the third, at 25000, it is 25232),
    // then 3 of 4000 and 2768 pulses into the next: 12 revolutions and the
    // 4000 table's value at 2768 - the same as ecam simulate's
    // rotary-knife-switch scenario.
    assert_eq!(dump["DD8140"], 12668);
    let text = std::fs::read_to_string(&trace).unwrap();
    let mut previous: Option<i64> = None;
    for line in text.lines().skip(1) {
        let row: Vec<i64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        let (slave, feed, direction) = (row[1], row[2], row[3]);
        if let Some(p) = previous {
            // 1 ms scans at 10 feed pulses each: at most 50/3 × 10 knife pulses.
            assert!((0..=167).contains(&(slave - p)), "step at feed {feed}");
        }
        if slave > 0 {
            assert_eq!(direction, 1, "direction output forward at feed {feed}");
        }
        previous = Some(slave);
    }
    std::fs::remove_dir_all(&dir).ok();
}
