//! Running a table generator by name: the generators of `ecam table gen`,
//! with their parameters as key/value pairs from flags, a TOML file, a
//! scenario's `[table]` or the designer's JSON.
//!
//! Every parameter starts at the document's default (the `Default` of the
//! generator's `Params` in `ecam_core::generator`); the values given
//! override what they set. Numeric ratios accept arithmetic (`5/3`, `3*pi`).

use ecam_core::budget::Budget;
use ecam_core::excerpt::excerpt;
use ecam_core::generator::key_points::{self, CurveType, KeyPoint, LineError};
use ecam_core::generator::schema;
use ecam_core::generator::{
    CutParams, DesignCurve, ExactCurve, Generator as Schema, flying_saw, function, rotary_cut,
    s_curve, segments,
};
use ecam_core::segments::SegmentCam;
use ecam_core::{CamCurve, CamPoint, Cursor, Kinematics, PointTable};
use serde::de::DeserializeSeed;
use serde_json::Value;

use crate::error::GenerateError;
use crate::expr::MasterFunction;
use crate::params::{Param, Values, ValuesSeed, typed};

/// A generated table and what else the generator reported.
pub struct Generated {
    /// The table.
    pub table: PointTable,
    /// Master range of the synchronised zone, where the generator has one.
    pub sync: Option<(i64, i64)>,
    /// The generator's name as `ecam table gen` spells it.
    pub name: &'static str,
    /// Extra results (e.g. the S-curve's P8–P11), as label and value
    /// (`ecam table gen` prints them to stderr).
    pub outputs: Vec<(&'static str, String)>,
    /// Exact velocity, acceleration and jerk at each point, from the curve
    /// the table samples (the points themselves are rounded to whole pulses).
    pub kinematics: Option<Vec<Kinematics>>,
    /// The exact curve the table samples, where the generator knows one:
    /// the design of the S-curve, rotary cut and flying saw before rounding,
    /// the key points' laws (what `--plot` draws, where steps are read).
    pub exact: Option<ExactCurve>,
    /// The solved segment cam behind a `segments` table (exact; its
    /// continuity and per-segment peaks; a table file keeps it).
    pub segments: Option<SegmentCam>,
}

/// The design curve's derivatives at each point of `table`, keeping the
/// table's (rounded) positions.
fn design_along(table: &PointTable, design: &DesignCurve) -> Vec<Kinematics> {
    table
        .points()
        .iter()
        .map(|p| Kinematics {
            s: p.slave as f64,
            ..design.eval(p.master as f64)
        })
        .collect()
}

/// The exact curve's derivatives at each point of `table`, keeping the
/// table's (rounded) positions.
fn kinematics_along(table: &PointTable, curve: &impl CamCurve) -> Vec<Kinematics> {
    let mut cursor = Cursor::new();
    table
        .points()
        .iter()
        .map(|p| Kinematics {
            s: p.slave as f64,
            ..curve.eval(p.master as f64, &mut cursor)
        })
        .collect()
}

/// Generates from a scenario's `[table]` (without the `generator` key).
///
/// # Errors
/// Unknown generator names or parameters, or bad values.
pub fn from_toml(name: &str, params: toml::Table) -> Result<Generated, GenerateError> {
    from_toml_within(name, params, &mut Budget::per_run())
}

/// As [`from_toml`], taking the work from `budget`.
///
/// # Errors
/// As [`from_toml`]; the budget used up.
pub fn from_toml_within(
    name: &str,
    params: toml::Table,
    budget: &mut Budget,
) -> Result<Generated, GenerateError> {
    let generator = find(name)?;
    let values = ValuesSeed::new(generator, false)
        .deserialize(toml::Value::Table(params))
        .map_err(|e| GenerateError::Params {
            generator: name.to_string(),
            message: ecam_core::io::plain_serde_message(&e.to_string()),
        })?;
    generate_within(generator, values, budget)
}

/// Generates from the `params` object of the designer's HTTP request.
///
/// # Errors
/// As [`from_toml`]; a value that is not an object.
pub fn from_json(name: &str, params: serde_json::Value) -> Result<Generated, GenerateError> {
    from_json_within(name, params, &mut Budget::per_run())
}

/// As [`from_json`], taking the work from `budget` (see
/// [`generate_within`]).
///
/// # Errors
/// As [`from_json`]; the budget used up or the request given up.
pub fn from_json_within(
    name: &str,
    params: serde_json::Value,
    budget: &mut Budget,
) -> Result<Generated, GenerateError> {
    let generator = find(name)?;
    if !params.is_object() {
        return Err(GenerateError::NotAnObject);
    }
    let values = ValuesSeed::new(generator, true)
        .deserialize(params)
        .map_err(|e| GenerateError::Params {
            generator: name.to_string(),
            message: ecam_core::io::plain_serde_message(&e.to_string()),
        })?;
    generate_within(generator, values, budget)
}

/// The generator called `name` (or one of its aliases).
///
/// # Errors
/// An unknown name; the message lists the known ones.
pub fn find(name: &str) -> Result<&'static Schema, GenerateError> {
    schema::find(name).ok_or_else(|| GenerateError::UnknownGenerator {
        name: name.to_string(),
    })
}

/// Runs `generator` with `values`; parameters not among them keep their
/// defaults.
///
/// # Errors
/// Values of the wrong kind or name, or parameters the generator refuses
/// (with the PLC's error code).
pub fn generate(generator: &Schema, values: Values) -> Result<Generated, GenerateError> {
    generate_within(generator, values, &mut Budget::per_run())
}

/// As [`generate`], taking the work from `budget`: the `function`
/// generator spends one unit per term of its expression at each
/// evaluation (five per table point: the value and the four around it of
/// its exact derivatives); the others, bounded by their parameters'
/// ranges, only look at whether the request was given up.
///
/// # Errors
/// As [`generate`]; the budget used up, or the request given up.
pub fn generate_within(
    generator: &Schema,
    mut values: Values,
    budget: &mut Budget,
) -> Result<Generated, GenerateError> {
    budget.check().map_err(GenerateError::from)?;
    match generator.name {
        "s-curve" => s_curve_table(&typed(values)?),
        "rotary-cut" => rotary_cut_table(&typed(values)?),
        "fly-saw" => {
            let cycle = matches!(values.remove("cycle"), Some(Param::Bool(true)));
            fly_saw_table(&typed(values)?, cycle)
        }
        "keypoints" => key_points_table(&typed(values)?),
        "segments" => segments_table(&typed(values)?),
        _ => function(&typed(values)?, budget),
    }
}

/// The default of every field of `g` as its `Params` writes it (choices as
/// names, key points as tables); a switch is off.
pub fn default_values(g: &Schema) -> serde_json::Map<String, Value> {
    let value = match g.name {
        "s-curve" => serde_json::to_value(s_curve::Params::default()),
        "rotary-cut" | "fly-saw" => serde_json::to_value(CutParams::default()),
        "keypoints" => serde_json::to_value(key_points::Params::default()),
        "segments" => serde_json::to_value(segments::Params::default()),
        _ => serde_json::to_value(function::Params::default()),
    };
    match value {
        Ok(Value::Object(map)) => map,
        _ => serde_json::Map::new(),
    }
}

// ---------------------------------------------------------------- s-curve

fn s_curve_table(params: &s_curve::Params) -> Result<Generated, GenerateError> {
    let g = s_curve::generate(params)?;
    Ok(Generated {
        outputs: vec![
            (
                "duration (master counts = ms at 1 kHz)",
                g.duration.to_string(),
            ),
            ("P8 last section master", g.last_section_master.to_string()),
            ("P9 last section slave", g.last_section_slave.to_string()),
            ("P10 uniform time", g.uniform_time.to_string()),
            ("P11 max speed (Hz)", g.max_speed_hz.to_string()),
        ],
        kinematics: Some(design_along(&g.table, &g.design)),
        table: g.table,
        sync: g.sync,
        name: "s-curve",
        exact: Some(ExactCurve::Design(g.design)),
        segments: None,
    })
}

// ---------------------------------------------------------------- rotary cut, flying saw

fn rotary_cut_table(params: &CutParams) -> Result<Generated, GenerateError> {
    let g = rotary_cut::generate(params)?;
    Ok(Generated {
        outputs: vec![
            ("regime", g.regime.to_string()),
            (
                "sync zone",
                format!(
                    "master {}, slave {} .. {}, ratio {}",
                    g.sync
                        .map_or_else(|| "none".to_string(), |(lo, hi)| format!("{lo} .. {hi}")),
                    g.sync_slave.0,
                    g.sync_slave.1,
                    crate::short(g.sync_ratio)
                ),
            ),
            ("peak ratio", crate::short(g.peak_ratio)),
            ("capped at max ratio", g.capped_at_max.to_string()),
        ],
        kinematics: Some(design_along(&g.table, &g.design)),
        table: g.table,
        sync: g.sync,
        name: "rotary-cut",
        exact: Some(ExactCurve::Design(g.design)),
        segments: None,
    })
}

fn fly_saw_table(params: &CutParams, cycle: bool) -> Result<Generated, GenerateError> {
    if !cycle {
        let g = flying_saw::generate(params)?;
        return Ok(Generated {
            outputs: vec![
                ("stroke", g.stroke.to_string()),
                (
                    "constant-speed zone (master)",
                    format!("{} .. {}", g.constant_zone.0, g.constant_zone.1),
                ),
                ("peak ratio", crate::short(g.peak_ratio)),
            ],
            kinematics: Some(design_along(&g.table, &g.design)),
            table: g.table,
            sync: g.sync,
            name: "fly-saw",
            exact: Some(ExactCurve::Design(g.design)),
            segments: None,
        });
    }
    let (forward, back) = flying_saw::generate_pair(params)?;
    let (m_end, s_end) = (forward.table.master_last(), forward.table.slave_last());
    let mut points = forward.table.points().to_vec();
    for q in back.table.points().iter().skip(1) {
        let master = q
            .master
            .checked_add(m_end)
            .ok_or(GenerateError::Overflow { what: "master" })?;
        let slave = q
            .slave
            .checked_add(s_end)
            .ok_or(GenerateError::Overflow { what: "slave" })?;
        points.push(CamPoint::new(master, slave));
    }
    let table = PointTable::new(points)?;
    let design = forward.design.followed_by(&back.design);
    Ok(Generated {
        outputs: vec![(
            "peak ratio",
            crate::short(forward.peak_ratio.max(back.peak_ratio)),
        )],
        kinematics: Some(design_along(&table, &design)),
        table,
        sync: forward.sync,
        name: "fly-saw",
        exact: Some(ExactCurve::Design(design)),
        segments: None,
    })
}

// ---------------------------------------------------------------- keypoints

/// Reads one `--key` value of `ecam table gen keypoints`: the key-point
/// line syntax (`MASTER:SLAVE[:CURVE[:RESOLUTION]]`), errors worded for
/// that flag.
///
/// # Errors
/// What is wrong with `text`, naming the flag.
pub fn parse_key(text: &str) -> Result<KeyPoint, String> {
    let quoted = excerpt(text);
    KeyPoint::parse_line(text).map_err(|e| match e {
        LineError::TooFew => {
            format!("--key {quoted:?}: expected MASTER:SLAVE[:CURVE[:RESOLUTION]]")
        }
        LineError::TooMany => format!("--key {quoted:?}: too many fields"),
        LineError::NotInteger { what, text: field } => {
            let field = excerpt(field);
            format!("{what} {field:?} in --key {quoted:?} is not an integer")
        }
        LineError::UnknownCurve(c) => {
            format!("unknown curve {:?}; use {}", excerpt(c), CurveType::NAMES)
        }
        LineError::BadResolution(r) => {
            format!(
                "resolution {:?} in --key {quoted:?} must be 0..=512",
                excerpt(r)
            )
        }
    })
}

/// Reads the designer page's key-point box, one key point per line.
///
/// # Errors
/// The first bad line, by number, and what is wrong with it.
pub fn parse_key_lines(text: &str) -> Result<Vec<KeyPoint>, String> {
    key_points::parse_lines(text).map_err(|(line, e)| {
        let what = match e {
            LineError::TooFew => "expected MASTER SLAVE [CURVE [RESOLUTION]]".to_string(),
            LineError::TooMany => "too many fields".to_string(),
            LineError::NotInteger { what, text } => {
                format!("{what} {:?} is not an integer", excerpt(text))
            }
            LineError::UnknownCurve(c) => {
                format!("unknown curve {:?}; use {}", excerpt(c), CurveType::NAMES)
            }
            LineError::BadResolution(r) => format!("resolution {:?} must be 0..=512", excerpt(r)),
        };
        format!("key point line {line}: {what}")
    })
}

fn key_points_table(params: &key_points::Params) -> Result<Generated, GenerateError> {
    let generated = key_points::generate(params)?;
    Ok(Generated {
        kinematics: Some(kinematics_along(&generated.table, &generated.profile)),
        table: generated.table,
        sync: generated.sync,
        name: "keypoints",
        exact: Some(ExactCurve::Profile(generated.profile)),
        segments: None,
        outputs: vec![(
            "segment resolutions",
            generated
                .resolutions
                .iter()
                .map(u16::to_string)
                .collect::<Vec<_>>()
                .join(","),
        )],
    })
}

// ---------------------------------------------------------------- function

fn function(params: &function::Params, budget: &mut Budget) -> Result<Generated, GenerateError> {
    let expr = params.expr.as_deref().ok_or(GenerateError::MissingExpr)?;
    let (from, to, points) = (params.from, params.to, params.points);
    let limit = ecam_core::limits::MAX_TABLE_POINTS;
    if points > limit {
        return Err(GenerateError::TooManyPoints { points, limit });
    }
    let f = MasterFunction::parse(expr)?;
    // The four evaluations per point of the exact derivatives, taken
    // before any work so that a table that cannot fit is refused at once.
    let evaluations = u64::try_from(points).unwrap_or(u64::MAX);
    budget
        .spend(f.cost().saturating_mul(4).saturating_mul(evaluations))
        .map_err(|error| GenerateError::OverBudget {
            work: format!(
                "{points} points of an expression of {} terms, each evaluated 5 times",
                f.cost()
            ),
            error,
        })?;
    let table = function_table_within(expr, from, to, points, budget)?;
    // Central differences a quarter of the point spacing wide: small
    // against the curve's features, large against f64 round-off.
    let h = (to as f64 - from as f64) / (points.max(2) - 1) as f64 / 4.0;
    let kinematics = table
        .points()
        .iter()
        .map(|p| {
            budget.check()?;
            let k = f.kinematics(p.master as f64, h)?;
            Ok(Kinematics {
                s: p.slave as f64,
                ..k
            })
        })
        .collect::<Result<Vec<_>, GenerateError>>()?;
    Ok(Generated {
        table,
        sync: None,
        name: "function",
        outputs: Vec::new(),
        kinematics: Some(kinematics),
        exact: None,
        segments: None,
    })
}

// ---------------------------------------------------------------- segments

fn segments_table(params: &segments::Params) -> Result<Generated, GenerateError> {
    let g = segments::generate(params)?;
    let report = g.cam.continuity();
    let joints: Vec<String> = report
        .joints
        .iter()
        .map(|j| {
            format!(
                "{}{} {}",
                if j.seam { "seam " } else { "" },
                j.point,
                j.class
            )
        })
        .collect();
    Ok(Generated {
        kinematics: Some(kinematics_along(&g.table, &g.cam)),
        table: g.table,
        sync: g.sync,
        name: "segments",
        exact: Some(ExactCurve::Segments(g.cam.clone())),
        outputs: vec![
            (
                "segment cam continuity",
                format!("{} (seam {})", report.cam, report.seam),
            ),
            ("at the points", joints.join(", ")),
            (
                "segment resolutions",
                g.resolutions
                    .iter()
                    .map(u16::to_string)
                    .collect::<Vec<_>>()
                    .join(","),
            ),
        ],
        segments: Some(g.cam),
    })
}

/// Reads one `--start` value of `ecam table gen segments`:
/// `MASTER:SLAVE[:V[:A[:J]]]`, an empty field left free; values may be
/// arithmetic (`5/3`).
///
/// # Errors
/// What is wrong with `text`, naming the flag.
pub fn parse_point_flag(text: &str) -> Result<ecam_core::segments::InterpolationPoint, String> {
    let fields: Vec<&str> = text.split(':').map(str::trim).collect();
    if fields.len() < 2 || fields.len() > 5 {
        return Err(format!(
            "--start {text:?}: expected MASTER:SLAVE[:V[:A[:J]]]"
        ));
    }
    point_fields(&fields, "--start", text)
}

fn point_fields(
    fields: &[&str],
    flag: &str,
    text: &str,
) -> Result<ecam_core::segments::InterpolationPoint, String> {
    let whole = |what: &str, f: &str| {
        f.parse::<i64>()
            .map_err(|_| format!("{what} {f:?} in {flag} {text:?} is not an integer"))
    };
    let value = |i: usize| -> Result<Option<f64>, String> {
        match fields.get(i).copied().unwrap_or("") {
            "" => Ok(None),
            f => crate::expr::number(f)
                .map(Some)
                .map_err(|e| format!("{f:?} in {flag} {text:?}: {e:#}")),
        }
    };
    Ok(ecam_core::segments::InterpolationPoint {
        master: whole("master", fields[0])?,
        slave: whole("slave", fields[1])?,
        velocity: value(2)?,
        acceleration: value(3)?,
        jerk: value(4)?,
    })
}

/// Reads one `--segment` value of `ecam table gen segments`:
/// `LAW:MASTER:SLAVE[:V[:A[:J[:POINTS]]]]`, an empty field left free.
///
/// # Errors
/// What is wrong with `text`, naming the flag.
pub fn parse_segment_flag(text: &str) -> Result<ecam_core::segments::SegmentSpec, String> {
    use ecam_core::segments::{SegmentLaw, SegmentSpec};
    let fields: Vec<&str> = text.split(':').map(str::trim).collect();
    if fields.len() < 3 || fields.len() > 7 {
        return Err(format!(
            "--segment {text:?}: expected LAW:MASTER:SLAVE[:V[:A[:J[:POINTS]]]]"
        ));
    }
    let law = SegmentLaw::from_name(fields[0]).ok_or_else(|| {
        format!(
            "unknown segment law {:?} in --segment {text:?}; use poly-5, poly-7, vv-cycloid or a motion law (`ecam law --list`)",
            fields[0]
        )
    })?;
    let end = point_fields(&fields[1..fields.len().min(6)], "--segment", text)?;
    let resolution = match fields.get(6).copied().unwrap_or("") {
        "" => None,
        f => Some(
            f.parse::<u16>()
                .map_err(|_| format!("points {f:?} in --segment {text:?} must be 1..=512"))?,
        ),
    };
    Ok(SegmentSpec {
        resolution,
        ..SegmentSpec::new(law, 0, 0).with_end(end)
    })
}

/// Samples `expr` (a function of `x`) at `points` masters from `from` to `to`.
///
/// # Errors
/// Parse or evaluation errors (naming the master where it failed), or a
/// table the core refuses.
pub fn function_table(
    expr: &str,
    from: i64,
    to: i64,
    points: usize,
) -> Result<PointTable, GenerateError> {
    function_table_within(expr, from, to, points, &mut Budget::per_run())
}

/// As [`function_table`], one unit of `budget` per term of the expression
/// at each point.
///
/// # Errors
/// As [`function_table`]; the budget used up, or the request given up.
pub fn function_table_within(
    expr: &str,
    from: i64,
    to: i64,
    points: usize,
    budget: &mut Budget,
) -> Result<PointTable, GenerateError> {
    use ecam_core::limits::{MAX_EXPRESSION_LEN, MAX_TABLE_POINTS};
    if points > MAX_TABLE_POINTS {
        return Err(GenerateError::TooManyPoints {
            points,
            limit: MAX_TABLE_POINTS,
        });
    }
    if expr.len() > MAX_EXPRESSION_LEN {
        return Err(crate::error::ExprError::TooLong {
            len: expr.len(),
            limit: MAX_EXPRESSION_LEN,
        }
        .into());
    }
    let f = MasterFunction::parse(expr)?;
    // The core reports this as a non-increasing last point (6782), which
    // names a section the user never wrote; say which settings clash.
    if to <= from {
        return Err(GenerateError::EmptyRange { from, to });
    }
    // Known before the work starts: refused at once when it cannot fit;
    // each point then only looks at whether the request was given up.
    let evaluations = u64::try_from(points).unwrap_or(u64::MAX);
    budget
        .spend(f.cost().saturating_mul(evaluations))
        .map_err(|error| GenerateError::OverBudget {
            work: format!("{points} points of an expression of {} terms", f.cost()),
            error,
        })?;
    let budget = &*budget;
    let first_error = std::cell::RefCell::new(None);
    let sampled = ecam_core::table::sample_function(
        |x| match budget
            .check()
            .map_err(GenerateError::from)
            .and_then(|()| f.at(x).map_err(GenerateError::from))
        {
            Ok(y) => y,
            Err(e) => {
                first_error.borrow_mut().get_or_insert(e);
                f64::NAN
            }
        },
        from,
        to,
        points,
    );
    if let Some(e) = first_error.into_inner() {
        return Err(e);
    }
    Ok(sampled?)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {

    #[test]
    fn ratios_print_at_most_six_decimals() {
        assert_eq!(crate::short(5.0 / 3.0), "1.666667");
        assert_eq!(crate::short(2.0), "2");
        assert_eq!(crate::short(0.5), "0.5");
        assert_eq!(crate::short(-0.0000001), "0");
    }

    use super::*;
    use ecam_core::CamCurve;

    #[test]
    fn the_rotary_cut_demo() {
        let t: toml::Table = toml::from_str(
            "master = 3183\nslave = 1000\nsync = 333\nratio = \"5/3\"\nmax_ratio = \"50/3\"",
        )
        .unwrap();
        let g = from_toml("rotary-cut", t).unwrap();
        assert_eq!((g.table.master_last(), g.table.slave_last()), (3183, 1000));
        assert!(g.sync.is_some());
    }

    #[test]
    fn the_fly_saw_demo_as_a_whole_cycle() {
        let t: toml::Table = toml::from_str(
            "master = 1750\nslave = 2000\nsync = 667\nratio = \"3*pi\"\nmax_ratio = 10\ncycle = true",
        )
        .unwrap();
        let g = from_toml("fly-saw", t).unwrap();
        assert_eq!((g.table.master_last(), g.table.slave_last()), (3500, 0));
        let peak = g.table.points().iter().map(|p| p.slave).max().unwrap();
        assert_eq!(peak, 2000);
    }

    #[test]
    fn the_s_curve_example() {
        let g = from_toml("s-curve", toml::Table::new()).unwrap();
        assert_eq!(g.table.slave_last(), 10000);
        assert_eq!(g.table.master_last(), 300);
    }

    #[test]
    fn unknown_names_are_refused() {
        let t: toml::Table = toml::from_str("accel = \"wobbly\"").unwrap();
        let err = from_toml("rotary-cut", t).err().unwrap();
        assert!(format!("{err:#}").contains("wobbly"));
        assert!(from_toml("laser", toml::Table::new()).is_err());
        let t: toml::Table = toml::from_str("colour = 3").unwrap();
        assert!(from_toml("rotary-cut", t).is_err());
    }

    #[test]
    fn key_flags_parse() {
        let k = parse_key("1500:2000:cycloid:20").unwrap();
        assert_eq!(
            (k.master, k.slave, k.curve, k.resolution),
            (1500, 2000, CurveType::Cycloid, 20)
        );
        assert_eq!(
            parse_key("600:0").unwrap().curve,
            CurveType::ConstantAcceleration
        );
        assert!(parse_key("600").is_err());
        assert!(parse_key("600:0:wobble").is_err());
    }

    #[test]
    fn key_points_default_is_the_appendix_case() {
        let g = from_toml("keypoints", toml::Table::new()).unwrap();
        assert_eq!(g.table.points().len(), 100);
        assert_eq!(g.table.master_last(), 2000);
    }

    #[test]
    fn key_points_from_toml() {
        let t: toml::Table = toml::from_str(
            "resolution = 20\n[[key]]\nmaster = 100\nslave = 50\ncurve = \"cycloid\"\n",
        )
        .unwrap();
        let g = from_toml("keypoints", t).unwrap();
        assert_eq!(g.table.points().len(), 20);
        assert_eq!(g.table.slave_last(), 50);
    }

    #[test]
    fn the_sine_example() {
        let t = function_table("1000*sin(2*pi*x/36000)", 0, 36000, 361).unwrap();
        assert_eq!(t.points().len(), 361);
        assert_eq!(t.points()[90].slave, 1000);
        assert_eq!(t.points()[270].slave, -1000);
    }

    #[test]
    fn generated_tables_carry_exact_derivatives() {
        let t: toml::Table = toml::from_str("expr = \"x*x\"\nto = 100\npoints = 11").unwrap();
        let g = from_toml("function", t).unwrap();
        let k = g.kinematics.unwrap();
        assert!((k[5].v - 100.0).abs() < 1e-9);
        assert!((k[5].a - 2.0).abs() < 1e-9);
        assert!(k[5].j.abs() < 1e-9);
    }

    #[test]
    fn a_reversed_function_range_names_both_ends() {
        let e = function_table("x", 10, 10, 11).err().unwrap().to_string();
        assert!(
            e.contains("(10) must be greater than the first (10)"),
            "{e}"
        );
        assert!(function_table("x", 10, 0, 11).is_err());
    }

    #[test]
    fn function_errors_name_the_master() {
        let err = function_table("1/(x-50)", 0, 100, 11).unwrap_err();
        assert!(format!("{err:#}").contains("x = 50"), "{err:#}");
    }

    #[test]
    fn numbers_take_arithmetic() {
        use crate::params::Number;
        let n: Number = toml::Value::String("50/3".into()).try_into().unwrap();
        assert!((n.0 - 50.0 / 3.0).abs() < 1e-12);
        let n: Number = toml::Value::Integer(3).try_into().unwrap();
        assert_eq!(n.0, 3.0);
    }
}
