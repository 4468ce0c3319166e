//! Starting a repeating cam with the machine away from its origin, through
//! `ecam plc run` (docs/plc.md, "The start rule"): the cycle count starts
//! in the cycle the master is in, and a cam with a stroke engages at the
//! equivalent position ahead of where the slave stands, less than one
//! stroke on, never with a reverse pulse.

use std::path::{Path, PathBuf};

use crate::common::{ecam, ok, scratch_dir};

const KNIFE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../examples/plc/rotary_knife.il"
);

/// Knife pulses per revolution and feed pulses per cut of the demo.
const REVOLUTION: i64 = 1000;

fn dump(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&ok(ecam(args))).unwrap()
}

fn program(dir: &Path, name: &str, source: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, source).unwrap();
    path
}

/// A cyclic cam on the two-point table `first`..`last` (master, slave), the
/// master a register (D10) standing at `master`, D8140 cleared.
fn two_point_cam(first: (i32, i32), last: (i32, i32), master: i32) -> String {
    format!(
        "LD M8002\nDMOV K0 D8140\nMOV K2 D2038\nDMOV K{} D2040\nDMOV K{} D2042\n\
         DMOV K{} D2044\nDMOV K{} D2046\nDMOV K{master} D10\n\
         LD M8000\nMOV K1 D2005\nDECAM D10 D2000 X2 Y0 Y4\n",
        first.0, first.1, last.0, last.1
    )
}

/// The first case: the manual's rotary knife started as the
/// cyclic cam with the feed standing at 10000 (in its fourth cut) and
/// D8140 cleared. Counting cuts from feed 0 drove the knife to 3621 pulses
/// at the 200 kHz ceiling, three revolutions with the feed at rest; it
/// goes to the table value of its place in the cut, 621.
#[test]
fn a_knife_started_mid_line_goes_to_the_table_value_not_three_revolutions() {
    let d = dump(&[
        "plc",
        "run",
        KNIFE,
        "--set",
        "C231=10000",
        "--ms",
        "50",
        "--dump",
        "DD8140",
        "--dump",
        "DD2019",
        "--dump",
        "DD2021",
        "--dump",
        "DD2027",
        "--dump",
        "Y4",
        "--dump",
        "D2001",
    ]);
    assert_eq!(d["DD2027"], 10000 - 3 * 3183, "the feed's place in its cut");
    assert_eq!(d["DD8140"], 621, "{d}");
    assert_eq!(d["DD2019"], 621);
    assert_eq!(d["DD2021"], 621, "no strokes of earlier cuts");
    assert_eq!(d["Y4"], 1, "forward pulses only");
    assert_eq!(d["D2001"].as_i64().unwrap() & 0b1_0011_1100, 0, "{d}");
}

/// The second case: a table (0,0)-(1000,100) started with the
/// master at 2500 goes to 50 (the table value half-way through the cycle),
/// not 250.
#[test]
fn a_table_started_in_its_third_cycle_takes_that_cycles_value() {
    let dir = scratch_dir("plc-starts-third-cycle");
    let p = program(&dir, "p.il", &two_point_cam((0, 0), (1000, 100), 2500));
    let d = dump(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--ms",
        "20",
        "--dump",
        "DD8140",
        "--dump",
        "DD2019",
    ]);
    assert_eq!(
        (d["DD8140"].as_i64(), d["DD2019"].as_i64()),
        (Some(50), Some(50))
    );
}

/// The third case: a rising table (1000,0)-(2000,100) started with
/// the master at 0 (the cycle before its origin) sent 100 reverse pulses
/// first; it sends none, and follows forward as the master moves.
#[test]
fn a_rising_table_started_before_its_origin_sends_no_reverse_pulse() {
    let dir = scratch_dir("plc-starts-before-origin");
    let source = two_point_cam((1000, 0), (2000, 100), 0)
        .replace("LD M8000\n", "LD M8000\nDADD D10 K1 D10\n");
    let p = program(&dir, "p.il", &source);
    let trace = dir.join("trace.csv");
    let d = dump(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--ms",
        "1500",
        "--dump",
        "DD8140",
        "--dump",
        "DD10",
        "--trace",
        trace.to_str().unwrap(),
        "--trace-dev",
        "DD8140",
    ]);
    let counters: Vec<i64> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    assert!(
        counters.windows(2).all(|w| w[1] >= w[0]) && counters.iter().all(|&c| c >= 0),
        "a reverse pulse: {counters:?}"
    );
    // One master count per scan: 100 pulses per 1000 counts from 0 (the
    // register master is followed a count behind, and rounds).
    let master = d["DD10"].as_i64().unwrap();
    assert!(master > 1400, "{d}");
    assert!(
        (d["DD8140"].as_i64().unwrap() - master / 10).abs() <= 1,
        "{d}"
    );
}

/// Runs the rotary-knife example with the feed counter at `feed` and the
/// feed running: the knife reaches the cam less than one revolution from
/// where it stood, then turns one revolution per cut; its pulse counter
/// never goes back and its direction output never changes.
fn knife_from(feed: i64) {
    let dir = scratch_dir(&format!("plc-starts-knife-{feed}"));
    let trace = dir.join("trace.csv");
    let out = ecam(&[
        "plc",
        "run",
        KNIFE,
        "--set",
        &format!("C231={feed}"),
        "--wire",
        "Y1:X0",
        "--ms",
        "2000",
        "--dump",
        "D2001",
        "--trace",
        trace.to_str().unwrap(),
        "--trace-dev",
        "DD8140",
        "--trace-dev",
        "DD2019",
        "--trace-dev",
        "DD2027",
        "--trace-dev",
        "Y4",
        "--trace-dev",
        "D2001",
        "--trace-dev",
        "C231",
    ]);
    let d: serde_json::Value = serde_json::from_str(&ok(out)).unwrap();
    assert_eq!(d["D2001"].as_i64().unwrap() & 0b1_0011_1000, 0, "{d}");
    let rows: Vec<Vec<i64>> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let (mut previous, mut forward, mut caught_up) = (0i64, false, None);
    let (mut cuts, mut last_in_cut) = (0i64, None);
    for row in &rows {
        let (t, counter, slave, in_cut, direction, flags) =
            (row[0], row[1], row[2], row[3], row[4], row[5]);
        assert!(
            counter >= previous,
            "the knife went back at t={t}: {previous} -> {counter}"
        );
        previous = counter;
        forward |= direction == 1;
        assert!(
            !forward || direction == 1,
            "the direction output changed at t={t}"
        );
        if flags & (1 << 6) == 0 {
            continue; // not started yet
        }
        if caught_up.is_none() && flags & (1 << 2) == 0 {
            // No pulse owed: the knife follows the cam from here.
            caught_up = Some(counter);
            assert_eq!(counter, slave);
        }
        if last_in_cut.is_some_and(|last| in_cut < last) {
            cuts += 1;
        }
        last_in_cut = Some(in_cut);
        // The cuts count from the one the feed started in.
        assert!(
            (cuts * REVOLUTION..=(cuts + 1) * REVOLUTION).contains(&slave),
            "feed {feed}: slave {slave} after {cuts} cuts at t={t}"
        );
    }
    let caught_up = caught_up.expect("the knife caught up with its cam");
    assert!(
        (0..REVOLUTION).contains(&caught_up),
        "feed {feed}: {caught_up} pulses before following"
    );
    assert!(forward, "the knife moved");
    assert!(
        cuts >= 6,
        "about 20000 feed pulses: six cuts or more, {cuts}"
    );
    let last = rows.last().unwrap();
    assert!(last[6] >= feed + 19_900, "the feed ran: {}", last[6]);
}

#[test]
fn the_knife_starts_safely_with_the_feed_at_10000() {
    knife_from(10_000);
}

#[test]
fn the_knife_starts_safely_with_the_feed_at_12345() {
    knife_from(12_345);
}

#[test]
fn the_knife_starts_safely_with_the_feed_at_999999() {
    knife_from(999_999);
}

/// Repeat count HFFFF (the noncyclic cam that runs for ever) starts its
/// table at its first point where the feed stands, the slave where it is:
/// the cycle begins at the start, and the knife does not move before the
/// feed does.
#[test]
fn a_noncyclic_knife_repeating_for_ever_starts_where_it_stands() {
    let dir = scratch_dir("plc-starts-hffff");
    let source = std::fs::read_to_string(KNIFE)
        .unwrap()
        .replace("MOV K1 D2005", "MOV K2 D2005\nMOV HFFFF D2014");
    assert!(source.contains("HFFFF D2014"));
    let p = program(&dir, "knife.il", &source);
    let d = dump(&[
        "plc",
        "run",
        p.to_str().unwrap(),
        "--set",
        "C231=10000",
        "--ms",
        "50",
        "--dump",
        "DD8140",
        "--dump",
        "D2001",
    ]);
    assert_eq!(d["DD8140"], 0, "{d}");
    assert_eq!(
        d["D2001"].as_i64().unwrap() & (1 << 7),
        1 << 7,
        "noncyclic: {d}"
    );
}
