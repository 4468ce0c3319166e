//! `ecam table gen | show | plot`: file formats, the documents' generator
//! examples, plots, and errors.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::{ecam, fails, ok};

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh scratch folder per test.
fn scratch(name: &str) -> PathBuf {
    crate::common::scratch_dir(&format!("table-{name}"))
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `(master, slave)` of every row of a table CSV, header checked.
fn csv_points(text: &str, header: &str) -> Vec<(i64, i64)> {
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(header));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[0].parse().unwrap(), f[1].parse().unwrap())
        })
        .collect()
}

const FULL: &str = "master,slave,velocity,acceleration,jerk";

#[test]
fn the_rotary_cut_demo_writes_csv_and_svg() {
    let dir = scratch("rotary");
    let (csv, svg) = (dir.join("rotary-cut.csv"), dir.join("rotary-cut.svg"));
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
        "--plot",
        s(&svg),
    ]));
    let points = csv_points(&std::fs::read_to_string(&csv).unwrap(), FULL);
    assert_eq!(points.first(), Some(&(0, 0)));
    assert_eq!(points.last(), Some(&(3183, 1000)));
    assert!(points.len() <= 512);
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.contains("<svg"));
    // Four panels, four polylines.
    assert!(svg.matches("<polyline").count() >= 4, "{}", &svg[..200]);
}

#[test]
fn stdout_gets_csv_when_no_file_is_named() {
    let text = ok(ecam(&["table", "gen", "rotary-cut"]));
    let points = csv_points(&text, FULL);
    // The register table's defaults: 3000 master, 1000 slave.
    assert_eq!(points.last(), Some(&(3000, 1000)));
    let text = ok(ecam(&["table", "gen", "rotary-cut", "--minimal"]));
    assert!(text.starts_with("master,slave\n0,0\n"));
}

#[test]
fn json_output_keeps_the_sync_zone() {
    let dir = scratch("json");
    let json = dir.join("cut.json");
    ok(ecam(&[
        "table",
        "gen",
        "rotary-cut",
        "--master",
        "3183",
        "--sync",
        "333",
        "-o",
        s(&json),
    ]));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["generator"], "rotary-cut");
    let (lo, hi) = (
        v["sync"]["low"].as_i64().unwrap(),
        v["sync"]["high"].as_i64().unwrap(),
    );
    assert!(lo < hi);
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.last().unwrap()["master"], 3183);
    assert!(points[0]["velocity"].as_f64().is_some());
    // `show` reads it back, sync zone included.
    let shown: serde_json::Value =
        serde_json::from_str(&ok(ecam(&["table", "show", s(&json), "--json"]))).unwrap();
    assert_eq!(shown["sync"][0].as_i64(), Some(lo));
    assert_eq!(shown["stroke"], 1000);
    assert_eq!(shown["sections"].as_u64().unwrap() + 1, points.len() as u64);
}

#[test]
fn the_manuals_sine_function() {
    let text = ok(ecam(&[
        "table",
        "gen",
        "function",
        "--expr",
        "1000*sin(2*pi*x/36000)",
        "--from",
        "0",
        "--to",
        "36000",
        "--points",
        "361",
    ]));
    let points = csv_points(&text, FULL);
    assert_eq!(points.len(), 361);
    assert_eq!(points[90], (9000, 1000));
    assert_eq!(points[180].1, 0);
    assert_eq!(points[270], (27000, -1000));
    assert_eq!(points[360], (36000, 0));
}

#[test]
fn the_key_point_application_case_is_the_default() {
    let points = csv_points(&ok(ecam(&["table", "gen", "keypoints"])), FULL);
    assert_eq!(points.len(), 100);
    assert_eq!(points.first(), Some(&(0, 0)));
    assert_eq!(points.last(), Some(&(2000, 0)));
    // Dwell at 0 until 600, at 2000 between 1500 and 1700.
    for &(m, sl) in &points {
        if m <= 600 {
            assert_eq!(sl, 0, "master {m}");
        }
        if (1500..=1700).contains(&m) {
            assert_eq!(sl, 2000, "master {m}");
        }
    }
    // The same case spelled out with flags.
    let flags = csv_points(
        &ok(ecam(&[
            "table",
            "gen",
            "keypoints",
            "--resolution",
            "100",
            "--key",
            "600:0",
            "--key",
            "1500:2000",
            "--key",
            "1700:2000",
            "--key",
            "1900:600",
            "--key",
            "2000:0",
        ])),
        FULL,
    );
    assert_eq!(flags, points);
}

#[test]
fn the_s_curve_calculation_case() {
    let points = csv_points(&ok(ecam(&["table", "gen", "s-curve"])), FULL);
    // 10000 pulses: 100 ms up, 100 ms at 50 kHz, 100 ms down (1 count = 1 ms).
    assert_eq!(points.last(), Some(&(300, 10000)));
    let out = ecam(&["table", "gen", "s-curve"]);
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("P10 uniform time: 100"), "{err}");
}

#[test]
fn the_flying_saw_demo() {
    let forward = csv_points(
        &ok(ecam(&[
            "table",
            "gen",
            "fly-saw",
            "--master",
            "1750",
            "--slave",
            "2000",
            "--sync",
            "667",
            "--ratio",
            "3*pi",
            "--max-ratio",
            "10",
        ])),
        FULL,
    );
    assert_eq!(forward.last(), Some(&(1750, 2000)));
    let back = csv_points(
        &ok(ecam(&[
            "table",
            "gen",
            "fly-saw",
            "--master",
            "1750",
            "--slave",
            "-2000",
            "--sync",
            "667",
            "--ratio",
            "3*pi",
            "--max-ratio",
            "10",
        ])),
        FULL,
    );
    assert_eq!(back.last(), Some(&(1750, -2000)));
    let cycle = csv_points(
        &ok(ecam(&[
            "table",
            "gen",
            "fly-saw",
            "--master",
            "1750",
            "--slave",
            "2000",
            "--sync",
            "667",
            "--ratio",
            "3*pi",
            "--max-ratio",
            "10",
            "--cycle",
        ])),
        FULL,
    );
    assert_eq!(cycle.last(), Some(&(3500, 0)));
}

#[test]
fn a_params_file_sets_defaults_that_flags_override() {
    let dir = scratch("params");
    let params = dir.join("cut.toml");
    std::fs::write(
        &params,
        "master = 3183\nslave = 1000\nsync = 333\nratio = \"5/3\"\nmax_ratio = \"50/3\"\n",
    )
    .unwrap();
    let points = csv_points(
        &ok(ecam(&[
            "table",
            "gen",
            "rotary-cut",
            "--params",
            s(&params),
        ])),
        FULL,
    );
    assert_eq!(points.last(), Some(&(3183, 1000)));
    let points = csv_points(
        &ok(ecam(&[
            "table",
            "gen",
            "rotary-cut",
            "--params",
            s(&params),
            "--master",
            "4000",
        ])),
        FULL,
    );
    assert_eq!(points.last(), Some(&(4000, 1000)));
    std::fs::write(&params, "mastre = 3183\n").unwrap();
    let err = fails(ecam(&[
        "table",
        "gen",
        "rotary-cut",
        "--params",
        s(&params),
    ]));
    assert!(err.contains("mastre"), "{err}");
}

#[test]
fn show_summarises_a_csv() {
    let dir = scratch("show");
    let csv = dir.join("t.csv");
    std::fs::write(
        &csv,
        "master,slave\n0,500\n10000,1500\n20000,1000\n30000,2000\n",
    )
    .unwrap();
    let text = ok(ecam(&["table", "show", s(&csv)]));
    assert!(text.contains("sections:          3"), "{text}");
    assert!(text.contains("stroke 1500"), "{text}");
    assert!(text.contains("peak velocity:     0.1 "), "{text}");
    assert!(text.contains("continuity:        C0"), "{text}");
}

/// `ecam_core`'s JSON of a profile: a cycloid rise of 1000 over 100 counts,
/// a dwell of 100, then a constant-velocity rise of 1000 over 100.
fn profile_json() -> String {
    use ecam_core::{CamPoint, CamTable, MotionLaw, Segment, SegmentProfile};
    let profile = SegmentProfile::new(
        CamPoint::new(0, 0),
        vec![
            Segment::new(100, 1000, MotionLaw::Cycloid),
            Segment::new(200, 1000, MotionLaw::Cycloid),
            Segment::new(300, 2000, MotionLaw::ConstantVelocity),
        ],
    )
    .unwrap();
    ecam_core::io::to_json(&CamTable::Profile(profile))
}

#[test]
fn show_summarises_uniform_tables_and_profiles_exactly() {
    let dir = scratch("show-any");
    // Document 002's example: a straight line, 2 pulses per count.
    let uniform = dir.join("uniform.json");
    std::fs::write(
        &uniform,
        r#"{"kind":"uniform","values":[0,100,200],"cam_counts":100}"#,
    )
    .unwrap();
    let text = ok(ecam(&["table", "show", s(&uniform)]));
    assert!(text.contains("kind:              uniform"), "{text}");
    assert!(text.contains("points:            3"), "{text}");
    assert!(text.contains("sections:          2"), "{text}");
    assert!(
        text.contains("master:            0 .. 100 (span 100)"),
        "{text}"
    );
    assert!(
        text.contains("0 .. 200 (stroke 200, range 0 .. 200)"),
        "{text}"
    );
    assert!(text.contains("peak velocity:     2 "), "{text}");
    assert!(text.contains("peak acceleration: 0 "), "{text}");
    assert!(text.contains("continuity:        C2"), "{text}");

    // 4 values over 10 counts, a value every 3⅓ counts: slopes 3, 6, 9,
    // each joint 3 pulses/count more over 10/3 counts: 0.9 pulses/count².
    let fractional = dir.join("fractional.json");
    std::fs::write(
        &fractional,
        r#"{"kind":"uniform","values":[0,10,30,60],"cam_counts":10}"#,
    )
    .unwrap();
    let text = ok(ecam(&["table", "show", s(&fractional)]));
    assert!(text.contains("a value every 3.333333 counts"), "{text}");
    assert!(text.contains("sections:          3"), "{text}");
    assert!(text.contains("(stroke 60, range 0 .. 60)"), "{text}");
    assert!(text.contains("peak velocity:     9 "), "{text}");
    assert!(text.contains("peak acceleration: 0.9 "), "{text}");
    assert!(text.contains("continuity:        C0"), "{text}");

    // The profile's own laws, not a sampled table: cycloid peak velocity
    // 2·h/β = 20 and acceleration 2π·h/β² = 0.2π; the velocity steps from
    // 0 to 10 where the constant-velocity segment starts.
    let profile = dir.join("profile.json");
    std::fs::write(&profile, profile_json()).unwrap();
    let text = ok(ecam(&["table", "show", s(&profile)]));
    assert!(text.contains("kind:              profile"), "{text}");
    assert!(text.contains("points:            4"), "{text}");
    assert!(text.contains("sections:          3"), "{text}");
    assert!(
        text.contains("0 .. 2000 (stroke 2000, range 0 .. 2000)"),
        "{text}"
    );
    assert!(text.contains("peak velocity:     20 "), "{text}");
    assert!(text.contains("peak acceleration: 0.628319 "), "{text}");
    assert!(text.contains("continuity:        C0"), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&ok(ecam(&["table", "show", s(&profile), "--json"]))).unwrap();
    assert_eq!(json["kind"], "profile");
    assert_eq!(json["points"], 4);
    assert_eq!(json["stroke"], 2000);
    assert_eq!(json["master_last"], 300);
    let peak = json["peak_acceleration"].as_f64().unwrap();
    assert!((peak - 0.2 * std::f64::consts::PI).abs() < 1e-9, "{peak}");
    assert!((json["peak_velocity"].as_f64().unwrap() - 20.0).abs() < 1e-9);
    // Point tables keep their output: no `kind`.
    let csv = dir.join("t.csv");
    std::fs::write(&csv, "master,slave\n0,0\n10,5\n").unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&ok(ecam(&["table", "show", s(&csv), "--json"]))).unwrap();
    assert!(json.get("kind").is_none(), "{json}");
}

#[test]
fn plot_draws_uniform_tables_and_profiles() {
    let dir = scratch("plot-any");
    let inputs = [
        (
            "uniform",
            r#"{"kind":"uniform","values":[0,100,200],"cam_counts":100}"#.to_string(),
        ),
        (
            "fractional",
            r#"{"kind":"uniform","values":[0,10,30,60],"cam_counts":10}"#.to_string(),
        ),
        ("profile", profile_json()),
    ];
    for (name, text) in inputs {
        let json = dir.join(format!("{name}.json"));
        std::fs::write(&json, text).unwrap();
        let png = dir.join(format!("{name}.png"));
        ok(ecam(&["table", "plot", s(&json), "-o", s(&png)]));
        let bytes = std::fs::read(&png).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{name}");
        let svg = dir.join(format!("{name}.svg"));
        ok(ecam(&[
            "table",
            "plot",
            s(&json),
            "-o",
            s(&svg),
            "--sync",
            "0:5",
        ]));
        let svg = std::fs::read_to_string(&svg).unwrap();
        assert!(svg.matches("<polyline").count() >= 4, "{name}");
        assert_eq!(svg.matches("fill=\"#FFDD78\"").count(), 4, "{name}");
    }
}

#[test]
fn plot_writes_png_and_svg_with_the_sync_zone() {
    let dir = scratch("plot");
    let json = dir.join("cut.json");
    ok(ecam(&["table", "gen", "rotary-cut", "-o", s(&json)]));
    let png = dir.join("cut.png");
    ok(ecam(&["table", "plot", s(&json), "-o", s(&png)]));
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let svg = dir.join("cut.svg");
    ok(ecam(&[
        "table",
        "plot",
        s(&json),
        "-o",
        s(&svg),
        "--sync",
        "0:200",
    ]));
    let text = std::fs::read_to_string(&svg).unwrap();
    // The shaded zone is a filled rectangle in every panel.
    assert_eq!(text.matches("fill=\"#FFDD78\"").count(), 4);
    // A CSV has no sync zone: nothing shaded.
    let csv = dir.join("cut.csv");
    ok(ecam(&["table", "gen", "rotary-cut", "-o", s(&csv)]));
    ok(ecam(&["table", "plot", s(&csv), "-o", s(&svg)]));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(text.matches("fill=\"#FFDD78\"").count(), 0);
}

#[test]
fn errors_name_the_problem_and_exit_non_zero() {
    let dir = scratch("errors");
    // Sync ratio above the maximum: parameter error 6781.
    let err = fails(ecam(&[
        "table",
        "gen",
        "rotary-cut",
        "--ratio",
        "5",
        "--max-ratio",
        "2",
    ]));
    assert!(err.contains("6781"), "{err}");
    // Not a number.
    fails(ecam(&["table", "gen", "rotary-cut", "--ratio", "5/"]));
    // Unknown generator.
    fails(ecam(&["table", "gen", "laser"]));
    // Bad output extensions are refused before anything is written.
    let err = fails(ecam(&[
        "table",
        "gen",
        "rotary-cut",
        "-o",
        s(&dir.join("t.xlsx")),
    ]));
    assert!(err.contains(".csv or .json"), "{err}");
    let err = fails(ecam(&[
        "table",
        "gen",
        "rotary-cut",
        "--plot",
        s(&dir.join("t.pdf")),
    ]));
    assert!(err.contains(".svg or .png"), "{err}");
    // A table whose master does not increase: 6782 with the section.
    let csv = dir.join("bad.csv");
    std::fs::write(&csv, "master,slave\n0,0\n10,1\n10,2\n").unwrap();
    let err = fails(ecam(&["table", "show", s(&csv)]));
    assert!(err.contains("6782") && err.contains("section 2"), "{err}");
    // Missing file.
    fails(ecam(&["table", "show", s(&dir.join("none.csv"))]));
    // A function that cannot be evaluated everywhere.
    let err = fails(ecam(&[
        "table", "gen", "function", "--expr", "1/(x-50)", "--to", "100", "--points", "11",
    ]));
    assert!(err.contains("x = 50"), "{err}");
    let err = fails(ecam(&["table", "gen", "function", "--expr", "y*2"]));
    assert!(err.contains("\"y\""), "{err}");
    // Too many key points' resolution: a flag outside the core's range is
    // a usage error (exit 2) naming the range.
    let out = ecam(&["table", "gen", "keypoints", "--resolution", "600"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("10..=512"), "{err}");
}

#[test]
fn shipped_example_tables_match_their_parameter_files() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/tables");
    for (generator, params, table) in [
        ("rotary-cut", "rotary-cut-demo.toml", "rotary-cut.csv"),
        ("fly-saw", "fly-saw.toml", "fly-saw-cycle.csv"),
        ("keypoints", "keypoints.toml", "keypoints.csv"),
        ("function", "sine.toml", "sine.csv"),
        ("s-curve", "s-curve.toml", "s-curve.csv"),
    ] {
        let made = ok(ecam(&[
            "table",
            "gen",
            generator,
            "--params",
            s(&dir.join(params)),
        ]));
        let shipped = std::fs::read_to_string(dir.join(table)).unwrap();
        assert!(
            made == shipped,
            "examples/tables/{table} is stale: regenerate it (see examples/tables/README.md)"
        );
    }
    // The doc-001 table reads back as the document's four points.
    let text = ok(ecam(&[
        "table",
        "show",
        s(&dir.join("doc001.csv")),
        "--json",
    ]));
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(
        (v["sections"].as_u64(), v["stroke"].as_i64()),
        (Some(3), Some(1500))
    );
}

#[test]
fn plots_have_text_from_the_embedded_font_whatever_the_environment() {
    let dir = scratch("font");
    for name in ["t.png", "t.svg"] {
        let out = Command::new(env!("CARGO_BIN_EXE_ecam"))
            .args([
                "table",
                "gen",
                "keypoints",
                "-o",
                s(&dir.join("t.csv")),
                "--plot",
                s(&dir.join(name)),
            ])
            // Neither a font variable nor system font paths matter.
            .env("ECAM_FONT", "none")
            .env("XDG_DATA_DIRS", s(&dir))
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(!String::from_utf8_lossy(&out.stderr).contains("without text"));
        assert!(std::fs::metadata(dir.join(name)).unwrap().len() > 1000);
    }
    let svg = std::fs::read_to_string(dir.join("t.svg")).unwrap();
    assert!(svg.contains("<text") && svg.contains("master (counts)"));
}

#[test]
fn review_findings_stay_fixed() {
    let dir = scratch("review");
    // A one-point table: the message says what is needed, not "allowed 2 to 2^64 − 1".
    let one = dir.join("one.csv");
    std::fs::write(&one, "master,slave\n0,0\n").unwrap();
    let err = fails(ecam(&["table", "show", s(&one)]));
    assert!(err.contains("at least 2"), "{err}");
    assert!(!err.contains("18446744073709551615"), "{err}");
    // ecam_core's JSON with a bad table gets the core's error, not "missing field points".
    let bad = dir.join("bad.json");
    std::fs::write(
        &bad,
        r#"{"kind": "uniform", "values": [0, 1], "cam_counts": 1}"#,
    )
    .unwrap();
    let err = fails(ecam(&["table", "show", s(&bad)]));
    assert!(err.contains("6781") && err.contains("CamCounts"), "{err}");
    // Scientific notation is a number.
    let out = ok(ecam(&[
        "table",
        "gen",
        "function",
        "--expr",
        "1.5e3*x/36000",
        "--points",
        "3",
    ]));
    assert_eq!(
        csv_points(&out, "master,slave,velocity,acceleration,jerk"),
        [(0, 0), (18000, 750), (36000, 1500)]
    );
    // A reversed function range names both ends.
    let err = fails(ecam(&[
        "table", "gen", "function", "--expr", "x", "--from", "10", "--to", "10",
    ]));
    assert!(err.contains("must be greater than the first (10)"), "{err}");
    // The rotary-cut demo has the 100 points its resolution asks for.
    let out = ok(ecam(&[
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
    ]));
    assert_eq!(
        csv_points(&out, "master,slave,velocity,acceleration,jerk").len(),
        100
    );
}

/// Runs ecam, failing (not hanging) if it takes longer than a minute.
fn ecam_within_a_minute(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    for _ in 0..600 {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    child.kill().unwrap();
    panic!("ecam {args:?} did not finish within a minute");
}

#[test]
fn extreme_values_plot_without_hanging_or_panicking() {
    let dir = scratch("extreme-plot");
    let huge = dir.join("huge.csv");
    // Derivatives near f64::MAX once made the axis span infinite (an endless
    // tick search); values far off the axes overflowed the pixel mapping.
    std::fs::write(
        &huge,
        "master,slave,velocity,acceleration,jerk\n0,0,1e308,-1e308,1e308\n10,5,-1e308,1e308,0\n",
    )
    .unwrap();
    let wide = dir.join("wide.csv");
    std::fs::write(
        &wide,
        "master,slave\n0,-9223372036854775808\n1,9223372036854775807\n2,-9223372036854775808\n",
    )
    .unwrap();
    let sync = dir.join("sync.json");
    std::fs::write(
        &sync,
        r#"{"sync": {"low": -9223372036854775808, "high": 9223372036854775807},
            "points": [{"master": 0, "slave": 0}, {"master": 100, "slave": 5}]}"#,
    )
    .unwrap();
    for (input, out) in [
        (&huge, "huge.svg"),
        (&huge, "huge.png"),
        (&wide, "wide.png"),
        (&sync, "sync.svg"),
    ] {
        let out = dir.join(out);
        let result = ecam_within_a_minute(&["table", "plot", s(input), "-o", s(&out)]);
        let err = String::from_utf8_lossy(&result.stderr);
        assert!(result.status.success(), "{}: {err}", input.display());
        assert!(std::fs::metadata(&out).unwrap().len() > 0);
    }
}
