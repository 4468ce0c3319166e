//! `ecam table gen` for the S-curve, rotary cut and flying saw writes the
//! design curve's derivatives, and plots it; a plain CSV is plotted with
//! derivatives estimated from its points, and says so.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::{ecam, ok};

use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    crate::common::scratch_dir(&format!("table-design-{name}"))
}

/// Rows of `master,slave,velocity,acceleration,jerk`.
fn rows(csv: &str) -> Vec<(i64, i64, f64, f64, f64)> {
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("master,slave,velocity,acceleration,jerk")
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (
                f[0].parse().unwrap(),
                f[1].parse().unwrap(),
                f[2].parse().unwrap(),
                f[3].parse().unwrap(),
                f[4].parse().unwrap(),
            )
        })
        .collect()
}

const DEMO: [&str; 10] = [
    "--master",
    "3183",
    "--slave",
    "1000",
    "--sync",
    "333",
    "--ratio",
    "5/3",
    "--max-ratio",
    "50/3",
];

#[test]
fn the_rotary_cut_demo_has_a_smooth_acceleration_column() {
    let mut args = vec!["table", "gen", "rotary-cut"];
    args.extend(DEMO);
    let rows = rows(&ok(ecam(&args)));
    // The sync zone (master 0..201) runs at 5/3 exactly, unaccelerated.
    assert_eq!(rows[0].2, 5.0 / 3.0);
    assert_eq!(rows[0].3, 0.0);
    // Inside a ramp the acceleration keeps its sign from row to row (the
    // finite differences of the rounded points alternated).
    let mut ramp_pairs = 0;
    for w in rows.windows(2) {
        let (a0, a1) = (w[0].3, w[1].3);
        if a0 != 0.0 && a1 != 0.0 {
            assert_eq!(
                a0.signum(),
                a1.signum(),
                "rows at {} and {}",
                w[0].0,
                w[1].0
            );
            ramp_pairs += 1;
        }
    }
    assert!(ramp_pairs > 50, "{ramp_pairs}");
    // The uniform curve: one constant deceleration, then one acceleration,
    // both (5/3)/(ramp length) in size.
    let decel: Vec<f64> = rows.iter().map(|r| r.3).filter(|a| *a < 0.0).collect();
    assert!(decel.windows(2).all(|w| w[0] == w[1]));
    assert!((decel[0] + 0.004177).abs() < 1e-5, "{}", decel[0]);
    // The master and slave columns are the table's, as `--minimal` writes them.
    let mut args = vec!["table", "gen", "rotary-cut", "--minimal"];
    args.extend(DEMO);
    let minimal = ok(ecam(&args));
    let pairs: Vec<String> = rows.iter().map(|r| format!("{},{}", r.0, r.1)).collect();
    assert_eq!(minimal, format!("master,slave\n{}\n", pairs.join("\n")));
}

#[test]
fn every_cutting_generator_writes_design_derivatives() {
    for (generator, extra) in [
        ("s-curve", vec![]),
        ("fly-saw", vec!["--cycle"]),
        (
            "rotary-cut",
            vec!["--accel", "b-type", "--placement", "mid-all"],
        ),
    ] {
        let mut args = vec!["table", "gen", generator];
        args.extend(extra);
        let rows = rows(&ok(ecam(&args)));
        // Velocity is continuous: neighbouring rows differ by no more than
        // the peak acceleration (seen at the rows; 10 % spare for a peak
        // between two rows) times their distance.
        let peak = rows.iter().map(|r| r.3.abs()).fold(0.0, f64::max);
        assert!(peak > 0.0, "{generator}");
        for w in rows.windows(2) {
            let dm = (w[1].0 - w[0].0) as f64;
            assert!(
                (w[1].2 - w[0].2).abs() <= peak * dm * 1.1,
                "{generator}: velocity jumps between {} and {}",
                w[0].0,
                w[1].0
            );
        }
    }
}

#[test]
fn plots_name_what_they_show() {
    let dir = scratch("plots");
    let (csv, svg) = (dir.join("cut.csv"), dir.join("cut.svg"));
    let mut args = vec!["table", "gen", "rotary-cut", "--minimal", "-o"];
    args.push(csv.to_str().unwrap());
    args.extend(["--plot", svg.to_str().unwrap()]);
    args.extend(DEMO);
    ok(ecam(&args));
    let text = std::fs::read_to_string(&svg).unwrap();
    if text.contains("<text") {
        assert!(text.contains("exact curve"), "title");
        assert!(text.contains("table points"), "legend");
    }
    // The design is drawn densely; the table's points as dots.
    assert!(text.matches("<circle").count() >= 90);
    // The plain CSV written alongside has no derivatives: estimated, and said so.
    let plain = dir.join("plain.svg");
    ok(ecam(&[
        "table",
        "plot",
        csv.to_str().unwrap(),
        "-o",
        plain.to_str().unwrap(),
    ]));
    let text = std::fs::read_to_string(&plain).unwrap();
    if text.contains("<text") {
        assert!(text.contains("estimated from the points"));
        assert!(text.contains("per section"));
    }
}
