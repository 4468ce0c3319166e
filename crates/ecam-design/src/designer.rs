//! The designer page's JSON: motion laws sampled like `ecam law`, and cam
//! tables from the generators of `ecam table gen`, whose parameters (names,
//! labels, defaults: the documents' cases) come from
//! [`ecam_core::generator::schema`], as its flags and TOML files do.
//!
//! JSON in, JSON out, no sockets: `ecam serve`'s HTTP routes call these and
//! only turn the result into a response. They live here rather than in
//! `ecam-serve` because they are about designing cams (generators, laws,
//! key points), not about serving the PLC; `ecam-serve` stays free of the
//! generators and the expression language.

use ecam_core::budget::Budget;
use ecam_core::generator::key_points::KeyPoint;
use ecam_core::generator::schema;
use ecam_core::generator::{ExactCurve, Field, FieldKind};
use ecam_core::table::steps::Steps;
use ecam_core::table::{Summary, derivatives};
use ecam_core::{CamCurve, MotionLaw};
use serde::de::DeserializeSeed;
use serde_json::{Value, json};

use crate::generate;

/// Points of `GET /api/law/NAME` when none are asked for (as `ecam law`).
pub const DEFAULT_LAW_POINTS: usize = 1001;
/// Most points a law may be sampled at.
pub const MAX_LAW_POINTS: usize = 100_001;
/// Most points of a table one design request may ask for
/// ([`generate_json`]): with its derivatives, its answer stays under about
/// 30 MB while it is built, which bounds a server's memory by the number
/// of requests it computes at once. `ecam table gen` has no such cap.
pub const MAX_DESIGN_POINTS: usize = MAX_LAW_POINTS;

/// Every motion law with its characteristic values (∞ as `null`).
pub fn laws_json() -> Value {
    Value::Array(
        MotionLaw::ALL
            .iter()
            .map(|law| {
                let c = law.characteristics();
                json!({
                    "name": law.name(),
                    "cv": c.cv,
                    "ca": c.ca,
                    "cj": c.cj,
                    "zero_end_velocity": c.zero_end_velocity,
                    "zero_end_acceleration": c.zero_end_acceleration,
                })
            })
            .collect(),
    )
}

/// The normalised rise of law `name` at `points` values of u ∈ [0, 1],
/// ends included: `{"law", "u", "s", "v", "a", "j"}`.
///
/// # Errors
/// An unknown law, or fewer than 2 / more than [`MAX_LAW_POINTS`] points.
pub fn law_curves_json(name: &str, points: usize) -> Result<Value, String> {
    let law = MotionLaw::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = MotionLaw::ALL.iter().map(|l| l.name()).collect();
        format!("unknown motion law `{name}`; known: {}", names.join(", "))
    })?;
    if !(2..=MAX_LAW_POINTS).contains(&points) {
        return Err(format!("points must be 2..={MAX_LAW_POINTS}"));
    }
    let last = (points - 1) as f64;
    let u: Vec<f64> = (0..points).map(|k| k as f64 / last).collect();
    let k: Vec<_> = u.iter().map(|&u| law.eval(u)).collect();
    Ok(json!({
        "law": law.name(),
        "u": u,
        "s": k.iter().map(|k| k.s).collect::<Vec<_>>(),
        "v": k.iter().map(|k| k.v).collect::<Vec<_>>(),
        "a": k.iter().map(|k| k.a).collect::<Vec<_>>(),
        "j": k.iter().map(|k| k.j).collect::<Vec<_>>(),
    }))
}

/// The generators (name, title, one-line `about`) and their parameters, for the page's form, from
/// [`schema`]: each field's key, label, type (`int`, `number` — arithmetic
/// such as `5/3` allowed —, `text`, `bool`, `choice` with its `choices`, and
/// `keys`: key points, one `master slave curve [resolution]` per line, read
/// by `POST /api/keypoints` into the `key` array), default, unit (empty
/// for counts of points and plain numbers), help text, and for whole
/// numbers the accepted `min` and `max`.
pub fn generators_json() -> Value {
    Value::Array(
        schema::GENERATORS
            .iter()
            .map(|g| {
                let defaults = generate::default_values(g);
                let fields: Vec<Value> = g
                    .fields
                    .iter()
                    .map(|f| form_field(f, defaults.get(f.key)))
                    .collect();
                json!({"name": g.name, "title": g.title, "about": g.about, "fields": fields})
            })
            .collect(),
    )
}

fn form_field(field: &Field, default: Option<&Value>) -> Value {
    let default = match (field.shown_default, field.kind, default) {
        (Some(text), _, _) => json!(text),
        (None, FieldKind::Switch, _) => json!(false),
        (None, FieldKind::KeyPoints, Some(keys)) => {
            let keys: Vec<KeyPoint> = serde_json::from_value(keys.clone()).unwrap_or_default();
            let lines: Vec<String> = keys.iter().map(KeyPoint::to_string).collect();
            json!(lines.join("\n"))
        }
        (None, _, Some(value)) => value.clone(),
        (None, _, None) => json!(""),
    };
    let mut value = json!({
        "key": field.key,
        "label": field.label(),
        "type": field.kind.name(),
        "default": default,
        "unit": field.unit,
        "help": field.help,
    });
    match field.kind {
        FieldKind::Choice(names) => value["choices"] = json!(names),
        FieldKind::Integer { min, max, .. } => {
            value["min"] = json!(min);
            value["max"] = json!(max);
        }
        _ => {}
    }
    value
}

/// The key points typed in the page's box (`{"lines": "600 0 cycloid\n…"}`),
/// read as `ecam table gen keypoints --key` reads them: `{"key": [{"master",
/// "slave", "curve", "resolution"}, …]}`, what `POST /api/table/gen` takes.
///
/// # Errors
/// A body without `lines`, or the first bad line.
pub fn key_points_json(body: &Value) -> Result<Value, String> {
    let text = body
        .get("lines")
        .and_then(Value::as_str)
        .ok_or("the body needs \"lines\", e.g. {\"lines\": \"600 0 cycloid\\n2000 0\"}")?;
    let keys = generate::parse_key_lines(text)?;
    Ok(json!({ "key": keys }))
}

/// Samples of an exact curve the page draws, spread over its pieces: enough
/// for smooth ramps, and a step at a corner still shows as a vertical edge.
const DESIGN_SAMPLES: usize = 600;

fn design_samples(exact: &ExactCurve) -> Value {
    let samples = exact.samples(DESIGN_SAMPLES);
    json!({
        "master": samples.iter().map(|(m, _)| *m).collect::<Vec<_>>(),
        "s": samples.iter().map(|(_, k)| k.s).collect::<Vec<_>>(),
        "v": samples.iter().map(|(_, k)| k.v).collect::<Vec<_>>(),
        "a": samples.iter().map(|(_, k)| k.a).collect::<Vec<_>>(),
        "j": samples.iter().map(|(_, k)| k.j).collect::<Vec<_>>(),
    })
}

/// Runs a generator: `{"generator": "rotary-cut", "params": {...}}` →
/// the table's points, velocity, acceleration and jerk at each point
/// (`exact_kinematics`: from the exact curve, or else section slopes), the
/// sync zone, the generator's extra outputs and the table's summary.
///
/// # Errors
/// A body of the wrong shape, an unknown generator or parameter, or
/// parameters the generator refuses (with the PLC's error code).
pub fn generate_json(body: &Value) -> Result<Value, String> {
    generate_json_within(body, &mut Budget::per_run())
}

/// As [`generate_json`], taking the work from `budget` (a server gives each
/// request its own, stopped when the request is given up); at most
/// [`MAX_DESIGN_POINTS`] points.
///
/// # Errors
/// As [`generate_json`]; more points than a request may have; the budget
/// used up or the request given up.
pub fn generate_json_within(body: &Value, budget: &mut Budget) -> Result<Value, String> {
    let name = body.get("generator").and_then(Value::as_str).ok_or(
        "the body needs \"generator\", e.g. {\"generator\": \"rotary-cut\", \"params\": {}}",
    )?;
    let params = body.get("params").cloned().unwrap_or_else(|| json!({}));
    // Refused before anything is computed (a string is read as the
    // generator reads it; a bad one gets the generator's own message).
    let asked = params.get("points").and_then(|p| match p {
        Value::String(text) => text.trim().parse::<u64>().ok(),
        other => other.as_u64(),
    });
    if let Some(asked) = asked.filter(|&n| n > MAX_DESIGN_POINTS as u64) {
        return Err(format!(
            "points {asked} is above the limit of {MAX_DESIGN_POINTS} points per design request"
        ));
    }
    let g = generate::from_json_within(name, params, budget).map_err(|e| e.to_string())?;
    let points = g.table.points();
    if points.len() > MAX_DESIGN_POINTS {
        return Err(format!(
            "the table has {} points, above the limit of {MAX_DESIGN_POINTS} per design request",
            points.len()
        ));
    }
    let exact = g.kinematics.is_some();
    let kinematics = g
        .kinematics
        .clone()
        .unwrap_or_else(|| derivatives::of_points(points));
    let summary = Summary::of(&g.table);
    let design_peaks = g.exact.as_ref().map(design_peaks);
    // The one rule for impulses (`ecam_core::table::steps`): the exact
    // curve's corners, or, for a function's table, its columns.
    let steps = match &g.exact {
        Some(exact) => Steps::of(exact),
        None => Steps::of_columns(points, &kinematics),
    };
    // The note `ecam table show` prints when the table's acceleration is
    // mostly whole-pulse rounding.
    let shortest = points
        .windows(2)
        .filter_map(|w| match w {
            [a, b] => b.master.checked_sub(a.master),
            _ => None,
        })
        .min();
    let note = match (design_peaks, shortest) {
        (Some((_, design_a)), Some(shortest)) => {
            crate::report::ripple_note(summary.peak_acceleration, design_a, shortest)
        }
        _ => None,
    };
    let outputs: serde_json::Map<String, Value> = g
        .outputs
        .iter()
        .map(|(label, value)| ((*label).to_string(), Value::String(value.clone())))
        .collect();
    Ok(json!({
        "generator": g.name,
        "points": points.len(),
        "master": points.iter().map(|p| p.master).collect::<Vec<_>>(),
        "slave": points.iter().map(|p| p.slave).collect::<Vec<_>>(),
        "velocity": kinematics.iter().map(|k| k.v).collect::<Vec<_>>(),
        "acceleration": kinematics.iter().map(|k| k.a).collect::<Vec<_>>(),
        "jerk": kinematics.iter().map(|k| k.j).collect::<Vec<_>>(),
        // false: slopes of the table's straight sections, each holding
        // from its point to the next (see `ecam_core::table::derivatives`).
        "exact_kinematics": exact,
        // The exact curve the generator designed before rounding it into
        // the table, sampled densely: a long section of the table (a dwell)
        // would otherwise draw its end points' accelerations joined by a
        // slope the motion never has.
        "design": g.exact.as_ref().map(design_samples),
        // Where velocity steps (acceleration impulses) and acceleration
        // steps (jerk impulses), the seam's at the last master.
        "steps": steps,
        // A segment cam: its points with every boundary value it was
        // solved for, the continuity at each point and each segment's peaks.
        "segments": g.segments.as_ref().map(crate::segments_json),
        "sync": g.sync.map(|(lo, hi)| vec![lo, hi]),
        "outputs": outputs,
        "summary": {
            "sections": summary.sections,
            "master_span": g.table.master_span(),
            "stroke": summary.stroke,
            "slave_min": summary.slave_min,
            "slave_max": summary.slave_max,
            "peak_velocity": summary.peak_velocity,
            "peak_acceleration": summary.peak_acceleration,
            // What the design asks for, beside what the whole-pulse table
            // shows: on short sections the rounding ripple of the table's
            // acceleration is many times the design's.
            "design_peak_velocity": design_peaks.map(|(v, _)| v),
            "design_peak_acceleration": design_peaks.map(|(_, a)| a),
            "continuity": summary.continuity.to_string(),
            "seam": summary.seam.to_string(),
            // The design's smoothness by the steps rule, as `ecam table
            // show` prints it beside the table's: the plots draw the
            // design, whose corners are fewer than the straight sections'.
            "design_continuity": design_peaks.map(|_| {
                let (inside, seam) = steps.continuity();
                format!("{inside} (seam {seam})")
            }),
            "note": note,
        },
    }))
}

/// "Make continuous": `{"start": {...}, "segment": [...]}` → the same with
/// every free velocity, acceleration and jerk filled in from the
/// neighbouring segments ([`ecam_core::segments::make_continuous`]).
///
/// # Errors
/// A body of the wrong shape, or a cam that cannot be made continuous (the
/// message names the point).
pub fn segments_continuous_json(body: &Value) -> Result<Value, String> {
    let generator = schema::find("segments").ok_or("no segments generator")?;
    let mut params = serde_json::Map::new();
    for key in ["start", "segment"] {
        if let Some(v) = body.get(key) {
            params.insert(key.to_string(), v.clone());
        }
    }
    let values = crate::params::ValuesSeed::new(generator, true)
        .deserialize(Value::Object(params))
        .map_err(|e| ecam_core::io::plain_serde_message(&e.to_string()))?;
    let p: ecam_core::generator::segments::Params =
        crate::params::typed(values).map_err(|e| format!("{e:#}"))?;
    let (start, segment) =
        ecam_core::segments::make_continuous(p.start, p.segment).map_err(|e| e.to_string())?;
    Ok(json!({ "start": start, "segment": segment }))
}

/// The largest |velocity| and |acceleration| of the exact curve, from the
/// same dense samples the page draws.
fn design_peaks(exact: &ExactCurve) -> (f64, f64) {
    // A segment cam's peaks are exact (closed forms).
    if let ExactCurve::Segments(cam) = exact {
        return cam.peaks().iter().fold((0.0_f64, 0.0_f64), |(v, a), p| {
            (v.max(p.peak_velocity), a.max(p.peak_acceleration))
        });
    }
    exact
        .samples(DESIGN_SAMPLES)
        .iter()
        .fold((0.0_f64, 0.0_f64), |(v, a), (_, k)| {
            (v.max(k.v.abs()), a.max(k.a.abs()))
        })
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_gives_the_designs_peaks_beside_the_tables() {
        let out = generate_json(&json!({"generator": "rotary-cut", "params": {}})).unwrap();
        let summary = &out["summary"];
        let design_a = summary["design_peak_acceleration"].as_f64().unwrap();
        let table_a = summary["peak_acceleration"].as_f64().unwrap();
        let design_v = summary["design_peak_velocity"].as_f64().unwrap();
        // The sync ratio is the design's top speed; the table's sections
        // reach it too. Its acceleration is the rounding ripple, far above.
        assert!((design_v - summary["peak_velocity"].as_f64().unwrap()).abs() < 0.05);
        assert!(
            design_a > 0.0 && table_a > 2.0 * design_a,
            "{design_a} {table_a}"
        );
        // Its continuity too, as `ecam table show` gives both: the table's
        // straight sections step in velocity, the design only in
        // acceleration.
        assert_eq!(summary["continuity"], "C0");
        assert_eq!(summary["design_continuity"], "C1 (seam C1)");
    }

    #[test]
    fn a_law_rises_from_zero_to_one() {
        let v = law_curves_json("cycloid", 5).unwrap();
        assert_eq!(v["u"], json!([0.0, 0.25, 0.5, 0.75, 1.0]));
        assert_eq!(v["s"][0], json!(0.0));
        assert_eq!(v["s"][4], json!(1.0));
        assert_eq!(v["v"][2], json!(2.0)); // cycloid: Cv = 2 at u = 1/2
        assert!(law_curves_json("nope", 5).is_err());
        assert!(law_curves_json("cycloid", 1).is_err());
    }

    #[test]
    fn every_listed_generator_runs_with_its_defaults() {
        let Value::Array(list) = generators_json() else {
            panic!("an array");
        };
        for g in list {
            let name = g["name"].as_str().unwrap();
            // What the page sends for an untouched form.
            let mut params = serde_json::Map::new();
            for f in g["fields"].as_array().unwrap() {
                let key = f["key"].as_str().unwrap().to_string();
                let value = match (f["type"].as_str().unwrap(), &f["default"]) {
                    (_, Value::String(s)) if s.is_empty() => continue,
                    ("keys", Value::String(lines)) => {
                        key_points_json(&json!({ "lines": lines })).unwrap()["key"].clone()
                    }
                    (_, v) => v.clone(),
                };
                params.insert(key, value);
            }
            let out = generate_json(&json!({"generator": name, "params": params})).unwrap();
            let n = out["points"].as_u64().unwrap() as usize;
            assert!(n >= 2, "{name}");
            for key in ["master", "slave", "velocity", "acceleration", "jerk"] {
                assert_eq!(out[key].as_array().unwrap().len(), n, "{name} {key}");
            }
        }
    }

    #[test]
    fn a_generated_table_carries_its_dense_design_curve() {
        let v = generate_json(&json!({"generator": "rotary-cut", "params": {}})).unwrap();
        let design = &v["design"];
        let master: Vec<f64> = serde_json::from_value(design["master"].clone()).unwrap();
        let a: Vec<f64> = serde_json::from_value(design["a"].clone()).unwrap();
        assert!(master.len() >= 50, "{} samples", master.len());
        // The default cut dwells between master 600 and 2600: the design's
        // acceleration there is exactly zero, not a slope between points.
        for (m, a) in master.iter().zip(&a) {
            if (700.0..2500.0).contains(m) {
                assert_eq!(*a, 0.0, "acceleration at master {m}");
            }
        }
        // Key points are drawn from their laws, the constant-acceleration
        // turns included (their jerk impulses).
        let kp = generate_json(&json!({"generator": "keypoints", "params": {}})).unwrap();
        assert!(kp["design"]["master"].as_array().unwrap().len() > 100);
        let turns = kp["steps"]["acceleration"].as_array().unwrap();
        assert!(
            turns.iter().any(|s| s["master"] == json!(1800.0)),
            "{turns:?}"
        );
        assert!(kp["steps"]["velocity"].as_array().unwrap().is_empty());
    }

    #[test]
    fn form_fields_carry_unit_help_and_range_from_the_schema() {
        let list = generators_json();
        let cut = list
            .as_array()
            .unwrap()
            .iter()
            .find(|g| g["name"] == "keypoints")
            .unwrap();
        let resolution = cut["fields"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["key"] == "resolution")
            .unwrap();
        let field = schema::find("keypoints")
            .unwrap()
            .field("resolution")
            .unwrap();
        let FieldKind::Integer { min, max, .. } = field.kind else {
            panic!("an integer");
        };
        assert_eq!(resolution["min"], json!(min));
        assert_eq!(resolution["max"], json!(max));
        assert_eq!(resolution["help"], json!(field.help));
        let initial = cut["fields"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["key"] == "initial_slave")
            .unwrap();
        assert_eq!(initial["unit"], "pulses");
    }

    #[test]
    fn rotary_cut_defaults_span_the_cut() {
        let out =
            generate_json(&json!({"generator": "rotary-cut", "params": {"ratio": "5/3"}})).unwrap();
        assert_eq!(out["master"][0], json!(0));
        assert_eq!(out["master"].as_array().unwrap().last(), Some(&json!(3000)));
        assert_eq!(out["slave"].as_array().unwrap().last(), Some(&json!(1000)));
        assert!(out["sync"].is_array());
    }

    #[test]
    fn bad_parameters_say_what_is_wrong() {
        let err = generate_json(&json!({"generator": "s-curve", "params": {"resolution": 5}}))
            .unwrap_err();
        assert!(err.contains("6781") || err.contains("resolution"), "{err}");
        assert!(generate_json(&json!({"generator": "nope"})).is_err());
        assert!(generate_json(&json!({"params": {}})).is_err());
        assert!(generate_json(&json!({"generator": "s-curve", "params": {"bogus": 1}})).is_err());
    }

    #[test]
    fn key_point_lines_are_read_by_the_server() {
        let v = key_points_json(&json!({"lines": "600 0\n\n1500, 2000; cycloid 20"})).unwrap();
        assert_eq!(
            v["key"],
            json!([
                {"master": 600, "slave": 0, "curve": "constant-acceleration", "resolution": 0},
                {"master": 1500, "slave": 2000, "curve": "cycloid", "resolution": 20},
            ])
        );
        let err = key_points_json(&json!({"lines": "600 0\n700 x"})).unwrap_err();
        assert_eq!(err, "key point line 2: slave \"x\" is not an integer");
        assert!(key_points_json(&json!({})).is_err());
    }
}
