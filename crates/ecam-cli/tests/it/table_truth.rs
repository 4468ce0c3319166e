//! Plots and summaries that tell the truth (issue 13): derivative columns
//! drawn as what they are, steps drawn as impulses, the design's peaks and
//! the sampled table's each labelled, machine units on request.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use crate::common::{ecam, ok};

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The README's rotary-cut demo as a CSV with its derivative columns.
fn rotary_cut_csv(dir: &Path) -> PathBuf {
    let csv = dir.join("rc.csv");
    ok(ecam(&[
        "table",
        "gen",
        "rotary-cut",
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
        "-o",
        s(&csv),
    ]));
    csv
}

#[test]
fn a_csv_plot_holds_its_columns_and_marks_acceleration_steps_as_jerk_impulses() {
    let dir = crate::common::scratch_dir("truth-plot");
    let csv = rotary_cut_csv(&dir);
    let svg = dir.join("rc.svg");
    ok(ecam(&["table", "plot", s(&csv), "-o", s(&svg)]));
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.contains("derivative columns at its points"));
    // The jerk column is 0 throughout, yet the acceleration steps by about
    // ±0.0042 pulses/count² where the sync zone and the dwell begin and
    // end: labelled impulses, not a flat 0 alone.
    assert!(
        svg.contains("impulse: acceleration step"),
        "no impulse legend"
    );
    let negative = svg.matches("-0.0042").count();
    let all = svg.matches("0.0042").count();
    assert!(negative >= 1 && all > negative, "impulse labels missing");
}

#[test]
fn a_plain_point_plot_dots_its_estimates() {
    let dir = crate::common::scratch_dir("truth-plain");
    // A ramp, a long dwell, a ramp: no estimate may be joined across the dwell.
    let csv = dir.join("t.csv");
    std::fs::write(&csv, "master,slave\n0,0\n10,10\n20,30\n1000,30\n1010,40\n").unwrap();
    let svg = dir.join("t.svg");
    ok(ecam(&["table", "plot", s(&csv), "-o", s(&svg)]));
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.contains("estimated from the points"));
    assert!(svg.contains("<circle"), "estimates are dots");
}

#[test]
fn the_summary_labels_design_and_sampled_peaks_and_explains_the_ripple() {
    let dir = crate::common::scratch_dir("truth-show");
    let csv = rotary_cut_csv(&dir);
    let text = ok(ecam(&["table", "show", s(&csv)]));
    assert!(
        text.contains("peak acceleration: 0.004177 pulses/count² (design"),
        "{text}"
    );
    assert!(text.contains("pulses/count² (table as sampled"), "{text}");
    assert!(
        text.contains("note:") && text.contains("whole pulses"),
        "{text}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&ok(ecam(&["table", "show", s(&csv), "--json"]))).unwrap();
    let design = json["design"]["peak_acceleration"].as_f64().unwrap();
    let sampled = json["peak_acceleration"].as_f64().unwrap();
    assert!((design - 0.004177).abs() < 1e-6, "{design}");
    assert!(sampled > 5.0 * design, "{sampled}");
}

#[test]
fn machine_units_give_hz_and_mm_per_s() {
    let dir = crate::common::scratch_dir("truth-units");
    let csv = rotary_cut_csv(&dir);
    let text = ok(ecam(&[
        "table",
        "show",
        s(&csv),
        "--master-speed",
        "1000",
        "--units",
        "mm",
        "--unit-per-pulse",
        "0.01",
    ]));
    // 5/3 pulses/count at 1000 counts/s; 0.004177 pulses/count² · 1000².
    assert!(
        text.contains("slave speed:       1666.666667 Hz = 16.666667 mm/s (design"),
        "{text}"
    );
    assert!(text.contains("slave accel.:      4177.1"), "{text}");
    assert!(text.contains("mm/s² (design)"), "{text}");
    let json: serde_json::Value = serde_json::from_str(&ok(ecam(&[
        "table",
        "show",
        s(&csv),
        "--json",
        "--master-speed",
        "1000",
    ])))
    .unwrap();
    assert_eq!(json["at_speed"]["of"], "design");
    assert!((json["at_speed"]["slave_hz"].as_f64().unwrap() - 5000.0 / 3.0).abs() < 1e-6);
    // A unit without its size, or a speed of 0, is a usage error (exit 2).
    for bad in [
        vec!["--units", "mm"],
        vec!["--master-speed", "0"],
        vec![
            "--master-speed",
            "1000",
            "--units",
            "inch",
            "--unit-per-pulse",
            "1",
        ],
    ] {
        let mut args = vec!["table", "show", s(&csv)];
        args.extend(bad.iter().copied());
        let out = ecam(&args);
        assert_eq!(out.status.code(), Some(2), "{bad:?}");
    }
}

#[test]
fn a_plot_in_machine_units_scales_every_panel_and_impulse() {
    let dir = crate::common::scratch_dir("truth-plot-units");
    let csv = rotary_cut_csv(&dir);
    let svg = dir.join("mm.svg");
    ok(ecam(&[
        "table",
        "plot",
        s(&csv),
        "-o",
        s(&svg),
        "--master-speed",
        "1000",
        "--units",
        "mm",
        "--unit-per-pulse",
        "0.01",
    ]));
    let svg = std::fs::read_to_string(&svg).unwrap();
    for title in [
        "displacement (mm)",
        "slave speed (mm/s)",
        "acceleration (mm/s²)",
        "at master 1000 counts/s",
        "impulse: acceleration step (mm/s²)",
    ] {
        assert!(svg.contains(title), "{title}");
    }
    // 0.004177 pulses/count² · 1000² · 0.01 mm: the acceleration steps by 41.77 mm/s².
    assert!(svg.contains("Δa -41.77") && svg.contains("Δa 41.77"));
}
