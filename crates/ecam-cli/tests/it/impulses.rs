//! Every shipped plot draws the impulses the table has, and no others
//! (issue 28): for every example table and parameter file in
//! `examples/tables/`, the impulses the plot draws (`ecam table gen
//! --plot`, `ecam table plot`) are compared with the steps found by
//! scanning the table's own curve, independently of the steps rule: where
//! its velocity jumps (an acceleration impulse) or its acceleration jumps (a
//! jerk impulse), the seam included. `ecam table show --json` and the
//! designer's `/api/table/gen` report the same steps.

use std::path::{Path, PathBuf};

use ecam_core::generator::ExactCurve;
use ecam_core::io::{self, AnyTable, TableFile};
use ecam_core::{CamCurve, Cursor, Kinematics};
use ecam_plot::{Chart, Style, cam_table};

use crate::common::{ecam, ok};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/tables")
}

/// A step found by the scan or drawn: master, size, seam.
type Found = (f64, f64, bool);

/// The impulses a chart draws in panel `k` (2: acceleration, 3: jerk).
fn drawn(chart: &Chart, k: usize) -> Vec<Found> {
    chart.panels[k]
        .traces
        .iter()
        .filter(|t| t.style == Style::Impulses)
        .flat_map(|t| {
            t.x.iter()
                .zip(&t.y)
                .zip(&t.tags)
                .map(|((x, y), tag)| (*x, *y, tag.starts_with("seam")))
        })
        .collect()
}

/// Where `pick` of the curve `f` over `[lo, hi]` jumps: a fine scan, each
/// cell whose change the next derivative (`slope`) cannot explain narrowed
/// down by bisection; then the seam (start value − end value at `hi`).
fn scan(
    f: &dyn Fn(f64) -> Kinematics,
    (lo, hi): (f64, f64),
    pick: fn(&Kinematics) -> f64,
    slope: fn(&Kinematics) -> f64,
) -> Vec<Found> {
    let n = 40_000;
    let dx = (hi - lo) / n as f64;
    let at = |i: usize| lo + dx * i as f64;
    let scale = (0..=n)
        .map(|i| pick(&f(at(i))).abs())
        .fold(1e-300, f64::max);
    let noise = 1e-7 * scale;
    let mut found: Vec<Found> = Vec::new();
    for i in 0..n {
        let (mut a, mut b) = (at(i), at(i + 1));
        let (ka, kb) = (f(a), f(b));
        let explained = 4.0 * dx * slope(&ka).abs().max(slope(&kb).abs()) + noise;
        if (pick(&kb) - pick(&ka)).abs() <= explained {
            continue;
        }
        for _ in 0..80 {
            let mid = 0.5 * (a + b);
            let left = (pick(&f(mid)) - pick(&f(a))).abs();
            let right = (pick(&f(b)) - pick(&f(mid))).abs();
            if left >= right { b = mid } else { a = mid }
        }
        let size = pick(&f(b + 1e-9 * (hi - lo))) - pick(&f(a - 1e-9 * (hi - lo)));
        if size.abs() > noise && found.last().is_none_or(|p| (p.0 - b).abs() > 1e-6) {
            found.push((b, size, false));
        }
    }
    let seam = pick(&f(lo)) - pick(&f(hi));
    if seam.abs() > noise {
        found.push((hi, seam, true));
    }
    found
}

/// Asserts `drawn` and `expected` are the same steps: masters within
/// `near` (0: the same corner), sizes within a millionth of the largest.
fn same(what: &str, drawn: &[Found], expected: &[Found], near: impl Fn(f64) -> f64) {
    assert_eq!(
        drawn.len(),
        expected.len(),
        "{what}: drawn {drawn:?}, the table has {expected:?}"
    );
    let scale = expected.iter().fold(1e-300, |m, e| f64::max(m, e.1.abs()));
    for (d, e) in drawn.iter().zip(expected) {
        assert!(
            (d.0 - near(e.0)).abs() < 1e-6 * d.0.abs().max(1.0) && d.2 == e.2,
            "{what}: drawn at {} ({}), the table steps at {} ({})",
            d.0,
            d.2,
            e.0,
            e.2
        );
        assert!(
            (d.1 - e.1).abs() < 1e-6 * scale,
            "{what} at {}: drawn {}, the table's step {}",
            d.0,
            d.1,
            e.1
        );
    }
}

/// The exact curve's steps by scanning it: (velocity steps, acceleration steps).
fn exact_steps(exact: &ExactCurve, span: (f64, f64)) -> (Vec<Found>, Vec<Found>) {
    let f: Box<dyn Fn(f64) -> Kinematics> = match exact {
        ExactCurve::Design(d) => Box::new(|m| d.eval(m)),
        ExactCurve::Profile(p) => Box::new(|m| p.eval(m, &mut Cursor::new())),
        ExactCurve::Segments(s) => Box::new(|m| s.eval(m, &mut Cursor::new())),
    };
    (
        scan(&*f, span, |k| k.v, |k| k.a),
        scan(&*f, span, |k| k.a, |k| k.j),
    )
}

/// The shipped parameter files, the generator each is for, and the table
/// file made from it (`examples/tables/README.md`).
const GENERATED: [(&str, &str, &str); 5] = [
    ("rotary-cut-demo.toml", "rotary-cut", "rotary-cut.csv"),
    ("fly-saw.toml", "fly-saw", "fly-saw-cycle.csv"),
    ("keypoints.toml", "keypoints", "keypoints.csv"),
    ("s-curve.toml", "s-curve", "s-curve.csv"),
    ("sine.toml", "function", "sine.csv"),
];

/// The shipped segment-cam parameter files.
const SEGMENTS: [&str; 4] = [
    "segments-double-dwell.toml",
    "segments-flying-saw.toml",
    "segments-pick-and-place.toml",
    "segments-rotary-knife.toml",
];

fn generate(params: &str, generator: &str, extra: &str) -> ecam_design::Generated {
    let text = std::fs::read_to_string(examples().join(params)).unwrap();
    let table: toml::Table = toml::from_str(&format!("{text}\n{extra}")).unwrap();
    ecam_design::from_toml(generator, table).unwrap()
}

#[test]
fn every_generated_plot_draws_the_steps_of_its_exact_curve() {
    // The shipped parameter files, and the cases the issue names: the
    // uniform S-curve's acceleration steps, a rotary cut's seam.
    let mut cases: Vec<(&str, &str, &str)> =
        GENERATED.iter().map(|(p, g, _)| (*p, *g, "")).collect();
    cases.push(("s-curve.toml", "s-curve", "curve = \"uniform\""));
    cases.push(("rotary-cut-demo.toml", "rotary-cut", ""));
    // The segment cams (`ecam table gen segments`): steps where segments
    // meet, inside a rise law, and at the seam.
    for params in SEGMENTS {
        cases.push((params, "segments", ""));
    }
    for (params, generator, extra) in cases {
        let g = generate(params, generator, extra);
        let what = format!("{params} {extra}");
        let file = TableFile {
            table: g.table.clone(),
            sync: g.sync,
            generator: None,
            kinematics: g.kinematics.clone(),
            segments: None,
        };
        let chart = cam_table::chart(&file, g.exact.as_ref(), generator);
        let span = (g.table.master_first() as f64, g.table.master_last() as f64);
        let (velocity, acceleration) = match &g.exact {
            Some(exact) => exact_steps(exact, span),
            // A function's table: its columns are the function's own
            // derivatives (the sine has no corner, and meets at its seam).
            None => (Vec::new(), Vec::new()),
        };
        same(&what, &drawn(&chart, 2), &velocity, |m| m);
        same(&what, &drawn(&chart, 3), &acceleration, |m| m);
        // The designer draws the same steps.
        let json = ecam_design::generate_json(&serde_json::json!({
            "generator": generator,
            "params": serde_json::to_value(toml::from_str::<toml::Table>(&format!(
                "{}\n{extra}",
                std::fs::read_to_string(examples().join(params)).unwrap()
            )).unwrap()).unwrap(),
        }))
        .unwrap();
        let served = |key: &str| -> Vec<Found> {
            json["steps"][key]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| {
                    (
                        s["master"].as_f64().unwrap(),
                        s["size"].as_f64().unwrap(),
                        s["seam"].as_bool().unwrap(),
                    )
                })
                .collect()
        };
        same(
            &format!("designer {what}"),
            &served("velocity"),
            &velocity,
            |m| m,
        );
        same(
            &format!("designer {what}"),
            &served("acceleration"),
            &acceleration,
            |m| m,
        );
    }
}

#[test]
fn every_shipped_table_file_plots_and_shows_the_steps_it_has() {
    let mut checked = 0;
    for (params, generator, table) in GENERATED {
        let g = generate(params, generator, "");
        let path = examples().join(table);
        let AnyTable::Points(file) = io::read(&path).unwrap() else {
            panic!("{table}: a point table");
        };
        let masters: Vec<f64> = file
            .table
            .points()
            .iter()
            .map(|p| p.master as f64)
            .collect();
        // From its columns alone a step is placed at the point that ends
        // the section it lies in.
        let at_point = |m: f64| {
            masters
                .iter()
                .copied()
                .find(|&p| p >= m - 1e-6)
                .unwrap_or(m)
        };
        let span = (masters[0], masters[masters.len() - 1]);
        let (velocity, acceleration) = match &g.exact {
            Some(exact) => exact_steps(exact, span),
            None => (Vec::new(), Vec::new()),
        };
        let chart = cam_table::chart(&file, None, table);
        same(table, &drawn(&chart, 2), &velocity, at_point);
        same(table, &drawn(&chart, 3), &acceleration, at_point);
        // `ecam table show --json` reports what the plot draws.
        let shown: serde_json::Value = serde_json::from_str(&ok(ecam(&[
            "table",
            "show",
            "--json",
            path.to_str().unwrap(),
        ])))
        .unwrap();
        let listed = |key: &str| -> Vec<Found> {
            shown["steps"][key]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| {
                    (
                        s["master"].as_f64().unwrap(),
                        s["size"].as_f64().unwrap(),
                        s["seam"].as_bool().unwrap(),
                    )
                })
                .collect()
        };
        same(
            &format!("show {table}"),
            &listed("velocity"),
            &drawn(&chart, 2),
            |m| m,
        );
        same(
            &format!("show {table}"),
            &listed("acceleration"),
            &drawn(&chart, 3),
            |m| m,
        );
        checked += 1;
    }
    // The rotary cut's JSON (with its sync zone), document 001's plain
    // points and the evenly spaced table: straight sections, whose every
    // slope change is an acceleration impulse.
    for table in ["rotary-cut.json", "doc001.csv", "uniform.json"] {
        let path = examples().join(table);
        let any = io::read(&path).unwrap();
        let (chart, expected_v, expected_a) = match &any {
            AnyTable::Points(file) if file.kinematics.is_some() => {
                let g = generate("rotary-cut-demo.toml", "rotary-cut", "");
                let span = (
                    file.table.master_first() as f64,
                    file.table.master_last() as f64,
                );
                let (v, a) = exact_steps(g.exact.as_ref().unwrap(), span);
                (cam_table::chart(file, None, table), v, a)
            }
            AnyTable::Points(file) => {
                let t = &file.table;
                let f = |m: f64| t.eval(m, &mut Cursor::new());
                let span = (t.master_first() as f64, t.master_last() as f64);
                (
                    cam_table::chart(file, None, table),
                    straight(&f, span, &masters_of(t.points())),
                    Vec::new(),
                )
            }
            AnyTable::Uniform(u) => {
                let f = |m: f64| u.eval(m, &mut Cursor::new());
                let n = u.values().len();
                let xs: Vec<f64> = (0..n)
                    .map(|k| k as f64 * u.cam_counts() as f64 / (n - 1) as f64)
                    .collect();
                (
                    cam_table::uniform_chart(u, None, table),
                    straight(&f, (0.0, u.cam_counts() as f64), &xs),
                    Vec::new(),
                )
            }
            AnyTable::Profile(_) => panic!("no profile ships"),
        };
        let masters = chart.panels[0].traces[1].x.clone();
        let at_point = |m: f64| {
            masters
                .iter()
                .copied()
                .find(|&p| p >= m - 1e-6)
                .unwrap_or(m)
        };
        same(table, &drawn(&chart, 2), &expected_v, at_point);
        same(table, &drawn(&chart, 3), &expected_a, at_point);
        checked += 1;
    }
    assert_eq!(checked, 8);
}

fn masters_of(points: &[ecam_core::CamPoint]) -> Vec<f64> {
    points.iter().map(|p| p.master as f64).collect()
}

/// Straight sections' velocity steps: at each inner point, the slope after
/// it less the slope before (from the curve itself, a little either side),
/// and the seam's.
fn straight(f: &dyn Fn(f64) -> Kinematics, (lo, hi): (f64, f64), xs: &[f64]) -> Vec<Found> {
    let eps = 1e-6;
    let mut found: Vec<Found> = xs[1..xs.len() - 1]
        .iter()
        .map(|&x| (x, f(x + eps).v - f(x - eps).v, false))
        .filter(|s| s.1.abs() > 1e-12)
        .collect();
    let seam = f(lo + eps).v - f(hi - eps).v;
    if seam.abs() > 1e-12 {
        found.push((hi, seam, true));
    }
    found
}

#[test]
fn the_shipped_segment_cam_file_plots_and_shows_the_steps_of_its_segments() {
    // A table file that keeps its segment cam (`ecam table gen segments -o
    // x.json`) is plotted and shown from the cam, not from its points.
    let path = examples().join("segments-rotary-knife.json");
    let AnyTable::Points(file) = io::read(&path).unwrap() else {
        panic!("a point table");
    };
    let cam = file.segments.as_deref().expect("the file keeps its cam");
    let chart = cam_table::segment_cam_chart(cam, file.sync, "segments-rotary-knife");
    let span = (cam.master_first() as f64, cam.master_last() as f64);
    let (velocity, acceleration) = exact_steps(&ExactCurve::Segments(cam.clone()), span);
    same("segments json", &drawn(&chart, 2), &velocity, |m| m);
    same("segments json", &drawn(&chart, 3), &acceleration, |m| m);
    let shown: serde_json::Value = serde_json::from_str(&ok(ecam(&[
        "table",
        "show",
        "--json",
        path.to_str().unwrap(),
    ])))
    .unwrap();
    for (key, k) in [("velocity", 2), ("acceleration", 3)] {
        let listed: Vec<Found> = shown["steps"][key]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| {
                (
                    s["master"].as_f64().unwrap(),
                    s["size"].as_f64().unwrap(),
                    s["seam"].as_bool().unwrap(),
                )
            })
            .collect();
        same("show segments json", &listed, &drawn(&chart, k), |m| m);
    }
}
