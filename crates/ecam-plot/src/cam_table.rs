//! What a cam-table plot shows: displacement, velocity, acceleration and
//! jerk over the master, the synchronised zone shaded.
//!
//! Three cases, by what is known beyond the points:
//! - **a design curve** (`ecam table gen s-curve | rotary-cut | fly-saw`):
//!   its exact derivatives, sampled densely so jumps at joints show as
//!   vertical edges, with the table's rounded points dotted over the
//!   displacement;
//! - **derivatives at each point** (a generator that knows its curve only
//!   there, or a file with `velocity,acceleration,jerk` columns): the
//!   velocity the table commands (its section slopes, a staircase) with the
//!   file's velocity column dotted, and the acceleration and jerk columns
//!   each held until the next point (a staircase). Nothing is known between
//!   two points, so nothing is drawn there as if it were: a straight line
//!   from one acceleration sample to the next would show a ramp across a
//!   constant-velocity zone that has none;
//! - **only the points** (a plain `master,slave` file): the section
//!   velocities as a staircase, acceleration and jerk estimated from the
//!   points (see [`derivatives`]) and dotted, one dot per estimate; the
//!   title says so.
//!
//! Wherever a quantity steps (a design's acceleration at a joint, or a
//! file's acceleration column by more than its jerk column explains), the
//! next derivative has an impulse there, not a flat 0: it is drawn as an
//! arrow ([`Style::Impulses`]) labelled with the step's size.
//!
//! `ecam_core`'s other table kinds are drawn from the curve itself:
//! - **a segment profile** ([`profile_chart`]): each segment's motion law,
//!   sampled densely with both ends, so steps at the joints show as vertical
//!   edges; the key points dotted;
//! - **an evenly spaced table** ([`uniform_chart`], document 002): straight
//!   pieces between values at `k · CamCounts / (N − 1)`, drawn as a plain
//!   point table is (the spacing may be a fraction of a count).

use ecam_core::generator::DesignCurve;
use ecam_core::{CamCurve, CamPoint, Cursor, Kinematics, SegmentProfile, UniformTable};

use ecam_core::io::TableFile;
use ecam_core::table::derivatives;

use crate::{Chart, ChartPanel, Style, Trace};

/// Samples of the design curve drawn in all (spread over its pieces).
const DESIGN_SAMPLES: usize = 2000;
/// A step in a sampled column is drawn as an impulse of the next
/// derivative when the step is at least this share of the column's peak
/// and the next column does not account for it (see [`unexplained_steps`]).
/// A smooth law sampled at 10 points per stroke leaves about 2 % of its
/// peak unexplained; a real step is a sizeable share of the peak.
const STEP_SHARE: f64 = 0.05;
/// Relative size of a jump between the two ends of a joint of an exact
/// curve that counts as a step (laws in `f64` agree to ~1e-12).
const JOINT_TOLERANCE: f64 = 1e-7;
const ACCELERATION_IMPULSE: &str = "impulse: velocity step (pulses/count)";
const JERK_IMPULSE: &str = "impulse: acceleration step (pulses/count²)";

/// Sections on each side of a joint whose chords estimate a plain table's
/// acceleration and jerk (see [`derivatives::over_sections`]).
const SMOOTHING_SECTIONS: usize = 4;

const DISPLACEMENT: &str = "displacement (pulses)";
const VELOCITY: &str = "velocity (pulses/count)";
const ACCELERATION: &str = "acceleration (pulses/count²)";
const JERK: &str = "jerk (pulses/count³)";
const LINE: Style = Style::Line { width: 2 };

/// The plot of `file`, over `design` when the table was generated from one.
pub fn chart(file: &TableFile, design: Option<&DesignCurve>, name: &str) -> Chart {
    let points = file.table.points();
    let shaded = file
        .sync
        .map(|(lo, hi)| vec![(lo as f64, hi as f64)])
        .unwrap_or_default();
    let (title, panels) = match (design, &file.kinematics) {
        (Some(design), _) => (
            format!(
                "cam table: {name} (lines: design curve; arrows: its steps as impulses; dots: the table's {} points)",
                points.len()
            ),
            design_panels(points, design),
        ),
        (None, Some(known)) if known.len() == points.len() => (
            format!(
                "cam table: {name} (the file's derivative columns, each value held to the next point)"
            ),
            known_panels(points, known),
        ),
        _ => (
            format!(
                "cam table: {name} (velocity per section; acceleration, jerk estimated from the points)"
            ),
            estimated_panels(points),
        ),
    };
    Chart {
        title,
        x_label: "master (counts)".into(),
        panels,
        shaded,
    }
}

fn line(name: &str, x: Vec<f64>, y: Vec<f64>) -> Trace {
    Trace {
        name: name.into(),
        x,
        y,
        style: LINE,
    }
}

/// Estimates at points, as dots: joining them with lines would draw a
/// ramp across a long section where none is known.
fn estimates(name: &str, x: Vec<f64>, y: Vec<f64>) -> Trace {
    Trace {
        name: name.into(),
        x,
        y,
        style: Style::Markers,
    }
}

fn panel(title: &str, traces: Vec<Trace>) -> ChartPanel {
    ChartPanel {
        title: title.into(),
        traces,
    }
}

fn masters(points: &[CamPoint]) -> Vec<f64> {
    points.iter().map(|p| p.master as f64).collect()
}

fn slaves(points: &[CamPoint]) -> Vec<f64> {
    points.iter().map(|p| p.slave as f64).collect()
}

fn design_panels(points: &[CamPoint], design: &DesignCurve) -> Vec<ChartPanel> {
    let per_piece = DESIGN_SAMPLES / design.piece_count().max(1);
    let samples = design.sample_pieces(per_piece.clamp(8, DESIGN_SAMPLES));
    let x: Vec<f64> = samples.iter().map(|(m, _)| *m).collect();
    let of = |f: fn(&Kinematics) -> f64| samples.iter().map(|(_, k)| f(k)).collect::<Vec<_>>();
    vec![
        panel(
            DISPLACEMENT,
            vec![
                line("design", x.clone(), of(|k| k.s)),
                Trace {
                    name: "table points".into(),
                    x: masters(points),
                    y: slaves(points),
                    style: Style::Markers,
                },
            ],
        ),
        panel(VELOCITY, vec![line("design", x.clone(), of(|k| k.v))]),
        exact_panel(
            ACCELERATION,
            "design",
            &x,
            of(|k| k.a),
            &of(|k| k.v),
            ACCELERATION_IMPULSE,
        ),
        exact_panel(JERK, "design", &x, of(|k| k.j), &of(|k| k.a), JERK_IMPULSE),
    ]
}

/// A panel of an exact curve's derivative `y` over `x`, with an impulse
/// wherever the quantity it derives from (`integral`) steps at a joint.
fn exact_panel(
    title: &str,
    name: &str,
    x: &[f64],
    y: Vec<f64>,
    integral: &[f64],
    impulse: &str,
) -> ChartPanel {
    let mut traces = vec![line(name, x.to_vec(), y)];
    let (at, size) = joint_steps(x, integral);
    if !at.is_empty() {
        traces.push(Trace {
            name: impulse.into(),
            x: at,
            y: size,
            style: Style::Impulses,
        });
    }
    panel(title, traces)
}

/// Steps of a densely sampled exact curve: two samples at the same x (both
/// ends of a joint) whose values differ. Returns their x and the step sizes.
pub fn joint_steps(x: &[f64], y: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let scale = y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let span = x.last().copied().unwrap_or(0.0) - x.first().copied().unwrap_or(0.0);
    let same_x = 1e-12 * span.abs().max(1.0);
    x.windows(2)
        .zip(y.windows(2))
        .filter_map(|(x, y)| match (x, y) {
            ([x0, x1], [y0, y1])
                if (x1 - x0).abs() <= same_x && (y1 - y0).abs() > JOINT_TOLERANCE * scale =>
            {
                Some((*x1, y1 - y0))
            }
            _ => None,
        })
        .unzip()
}

/// Steps of a column `y` sampled at points `x` that its derivative column
/// `dy` does not account for: from one point to the next, `y` changes by
/// what `dy` integrates to (held from the left point, or averaged over the
/// section; a column of values that hold between points, or one sampled
/// from a smooth law), give or take 5 % of `y`'s peak; the rest
/// is a step at the later point. Returns their x and sizes.
pub fn unexplained_steps(x: &[f64], y: &[f64], dy: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let scale = y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let n = x.len().min(y.len()).min(dy.len());
    (1..n)
        .filter_map(|i| {
            let (x0, x1) = (*x.get(i - 1)?, *x.get(i)?);
            let (y0, y1) = (*y.get(i - 1)?, *y.get(i)?);
            let (d0, d1) = (*dy.get(i - 1)?, *dy.get(i)?);
            let (h, change) = (x1 - x0, y1 - y0);
            let held = change - d0 * h;
            let averaged = change - 0.5 * (d0 + d1) * h;
            // A step when neither reading explains the change; its size is
            // the rest after the section's mean derivative.
            (held.abs().min(averaged.abs()) > STEP_SHARE * scale).then_some((x1, averaged))
        })
        .unzip()
}

fn known_panels(points: &[CamPoint], known: &[Kinematics]) -> Vec<ChartPanel> {
    let x = masters(points);
    let of = |f: fn(&Kinematics) -> f64| known.iter().map(f).collect::<Vec<_>>();
    let held = |name: &str, y: Vec<f64>| Trace {
        name: name.into(),
        x: x.clone(),
        y,
        style: Style::Steps,
    };
    let (v, a, j) = (of(|k| k.v), of(|k| k.a), of(|k| k.j));
    let sections = derivatives::forward(&x, &slaves(points));
    let mut acceleration = vec![held("acceleration column", a.clone())];
    let mut jerk = vec![held("jerk column", j.clone())];
    for (traces, (at, size), name) in [
        (
            &mut acceleration,
            unexplained_steps(&x, &v, &a),
            ACCELERATION_IMPULSE,
        ),
        (&mut jerk, unexplained_steps(&x, &a, &j), JERK_IMPULSE),
    ] {
        if !at.is_empty() {
            traces.push(Trace {
                name: name.into(),
                x: at,
                y: size,
                style: Style::Impulses,
            });
        }
    }
    vec![
        panel(
            DISPLACEMENT,
            vec![
                line("table", x.clone(), slaves(points)),
                Trace {
                    name: "points".into(),
                    x: x.clone(),
                    y: slaves(points),
                    style: Style::Markers,
                },
            ],
        ),
        panel(
            VELOCITY,
            vec![
                held("table as run (section slopes)", sections),
                Trace {
                    name: "velocity column".into(),
                    x: x.clone(),
                    y: v,
                    style: Style::Markers,
                },
            ],
        ),
        panel(ACCELERATION, acceleration),
        panel(JERK, jerk),
    ]
}

fn estimated_panels(points: &[CamPoint]) -> Vec<ChartPanel> {
    let k = derivatives::of_points(points);
    let straight = Straight {
        x: masters(points),
        s: slaves(points),
        v: k.iter().map(|k| k.v).collect(),
        a: k.iter().map(|k| k.a).collect(),
        chords: derivatives::over_sections(points, SMOOTHING_SECTIONS),
    };
    straight_panels(straight, "points")
}

/// A curve of straight sections between its points, with the estimates
/// [`derivatives`] makes of the motion they sample.
struct Straight {
    /// Master of each point.
    x: Vec<f64>,
    /// Slave of each point.
    s: Vec<f64>,
    /// Velocity of the section starting at each point.
    v: Vec<f64>,
    /// Acceleration estimated per joint (0 at both ends).
    a: Vec<f64>,
    /// `(x, acceleration, jerk)` from chords over several sections.
    chords: (Vec<f64>, Vec<f64>, Vec<f64>),
}

fn straight_panels(straight: Straight, dots: &str) -> Vec<ChartPanel> {
    let Straight {
        x,
        s,
        v,
        a: joints,
        chords: (xs, a, j),
    } = straight;
    // The per-joint estimate is 0 at the ends only for want of a second
    // section: draw the interior joints.
    let inner = 1..x.len().saturating_sub(1);
    let per_joint = joints.get(inner.clone()).unwrap_or_default().to_vec();
    let x_inner = x.get(inner).unwrap_or_default().to_vec();
    let smoothed = format!("over ±{SMOOTHING_SECTIONS} sections");
    vec![
        panel(
            DISPLACEMENT,
            vec![
                line("table", x.clone(), s.clone()),
                Trace {
                    name: dots.into(),
                    x: x.clone(),
                    y: s,
                    style: Style::Markers,
                },
            ],
        ),
        panel(
            "velocity (pulses/count, per section)",
            vec![Trace {
                name: "section velocity".into(),
                x,
                y: v,
                style: Style::Steps,
            }],
        ),
        panel(
            "acceleration (pulses/count², estimated)",
            vec![
                Trace {
                    name: "per joint (neighbouring sections)".into(),
                    x: x_inner,
                    y: per_joint,
                    style: Style::Markers,
                },
                estimates(&smoothed, xs.clone(), a),
            ],
        ),
        panel(
            "jerk (pulses/count³, estimated)",
            vec![estimates(&smoothed, xs, j)],
        ),
    ]
}

fn chart_over(title: String, panels: Vec<ChartPanel>, sync: Option<(i64, i64)>) -> Chart {
    Chart {
        title,
        x_label: "master (counts)".into(),
        panels,
        shaded: sync
            .map(|(lo, hi)| vec![(lo as f64, hi as f64)])
            .unwrap_or_default(),
    }
}

/// The plot of an evenly spaced table (document 002): its straight pieces,
/// velocity per piece, acceleration and jerk estimated as for a point table,
/// the values dotted at their (possibly fractional) masters.
pub fn uniform_chart(table: &UniformTable, sync: Option<(i64, i64)>, name: &str) -> Chart {
    let values = table.values();
    let pieces = values.len().saturating_sub(1).max(1) as f64;
    let counts = table.cam_counts() as f64;
    let x: Vec<f64> = (0..values.len())
        .map(|k| k as f64 * counts / pieces)
        .collect();
    let s: Vec<f64> = values.iter().map(|&v| v as f64).collect();
    // Each piece's own slope, from the curve at the piece's middle (at a
    // value's master rounding could land in the piece before); the last
    // value repeats the last piece's, as for point tables.
    let mut cursor = Cursor::new();
    let mut v: Vec<f64> = x
        .windows(2)
        .map(|w| match w {
            [lo, hi] => table.eval(0.5 * (lo + hi), &mut cursor).v,
            _ => 0.0,
        })
        .collect();
    if let Some(&last) = v.last() {
        v.push(last);
    }
    let a = derivatives::at_joints(&x, &v);
    let straight = Straight {
        chords: uniform_chords(table),
        x,
        s,
        v,
        a,
    };
    let title = format!(
        "cam table: {name} ({} evenly spaced values over {} counts; acceleration, jerk estimated)",
        values.len(),
        table.cam_counts()
    );
    chart_over(title, straight_panels(straight, "values"), sync)
}

/// [`derivatives::over_sections`] of an evenly spaced table. Its masters
/// `k · CamCounts / (N − 1)` may be fractional, so the chords are taken over
/// masters scaled by `N − 1` (whole `k · CamCounts`) and scaled back:
/// x by `1/(N − 1)`, acceleration by `(N − 1)²`, jerk by `(N − 1)³`.
fn uniform_chords(table: &UniformTable) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let values = table.values();
    let scale = values.len().saturating_sub(1).max(1) as f64;
    let scaled: Option<Vec<CamPoint>> = values
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            let k = i64::try_from(k).ok()?;
            Some(CamPoint::new(k.checked_mul(table.cam_counts())?, v))
        })
        .collect();
    // Beyond i64 (over 2^34 values): no chord estimate rather than a wrong one.
    let Some(scaled) = scaled else {
        return Default::default();
    };
    let (x, a, j) = derivatives::over_sections(&scaled, SMOOTHING_SECTIONS);
    (
        x.into_iter().map(|x| x / scale).collect(),
        a.into_iter().map(|a| a * scale * scale).collect(),
        j.into_iter().map(|j| j * scale * scale * scale).collect(),
    )
}

/// The plot of a segment profile: each segment's law evaluated exactly at
/// dense samples, the key points dotted over the displacement.
pub fn profile_chart(profile: &SegmentProfile, sync: Option<(i64, i64)>, name: &str) -> Chart {
    let segments = profile.segments();
    let per_segment = (DESIGN_SAMPLES / segments.len().max(1)).clamp(8, DESIGN_SAMPLES);
    let mut samples: Vec<(f64, Kinematics)> =
        Vec::with_capacity(segments.len().saturating_mul(per_segment + 1));
    let mut from = profile.start();
    for segment in segments {
        // As `SegmentProfile::eval` does, but with both ends of every
        // segment: at a joint `eval` gives the next segment's values, and
        // the left end is what makes a step show as a vertical edge.
        let span = segment.master_end.saturating_sub(from.master) as f64;
        let rise = segment.slave_end.saturating_sub(from.slave) as f64;
        for i in 0..=per_segment {
            let u = i as f64 / per_segment as f64;
            let k = segment.law.eval(u).scaled(from.slave as f64, rise, span);
            samples.push((from.master as f64 + span * u, k));
        }
        from = CamPoint::new(segment.master_end, segment.slave_end);
    }
    let key_points: Vec<CamPoint> = profile.key_points().collect();
    let title = format!(
        "cam table: {name} (lines: its motion laws, exact; arrows: their steps as impulses; dots: its {} key points)",
        key_points.len()
    );
    exact_chart(&samples, &key_points, "key points", sync, title)
}

/// The plot of a segment cam ([`ecam_core::segments::SegmentCam`]): each
/// segment's solved law evaluated exactly at dense samples (both ends of
/// every segment, so a step at a point is a vertical edge and an impulse in
/// the next panel), its interpolation points dotted over the displacement.
pub fn segment_cam_chart(
    cam: &ecam_core::segments::SegmentCam,
    sync: Option<(i64, i64)>,
    name: &str,
) -> Chart {
    let per_segment = (DESIGN_SAMPLES / cam.segments().len().max(1)).clamp(8, DESIGN_SAMPLES);
    let samples = cam.sample_segments(per_segment);
    let points: Vec<CamPoint> = cam
        .points()
        .iter()
        .map(|p| CamPoint::new(p.master, p.slave))
        .collect();
    let title = format!(
        "segment cam {name}: each segment's law, exact ({} interpolation points dotted)",
        points.len()
    );
    exact_chart(&samples, &points, "interpolation points", sync, title)
}

/// Four panels of exact samples (two at a master where a step is), `marks`
/// dotted over the displacement.
fn exact_chart(
    samples: &[(f64, Kinematics)],
    marks: &[CamPoint],
    marks_name: &str,
    sync: Option<(i64, i64)>,
    title: String,
) -> Chart {
    let x: Vec<f64> = samples.iter().map(|(m, _)| *m).collect();
    let of = |f: fn(&Kinematics) -> f64| samples.iter().map(|(_, k)| f(k)).collect::<Vec<_>>();
    let panels = vec![
        panel(
            DISPLACEMENT,
            vec![
                line("profile", x.clone(), of(|k| k.s)),
                Trace {
                    name: marks_name.into(),
                    x: masters(marks),
                    y: slaves(marks),
                    style: Style::Markers,
                },
            ],
        ),
        panel(VELOCITY, vec![line("profile", x.clone(), of(|k| k.v))]),
        exact_panel(
            ACCELERATION,
            "profile",
            &x,
            of(|k| k.a),
            &of(|k| k.v),
            ACCELERATION_IMPULSE,
        ),
        exact_panel(JERK, "profile", &x, of(|k| k.j), &of(|k| k.a), JERK_IMPULSE),
    ];
    chart_over(title, panels, sync)
}

/// The machine a cam table runs on, for a plot in physical units: the
/// master's speed and, optionally, the slave's length unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Machine<'a> {
    /// Master speed, counts per second (the master encoder's frequency).
    pub master_hz: f64,
    /// The slave's unit (`mm`, `deg`) and its size per slave pulse.
    pub unit: Option<(&'a str, f64)>,
}

/// `chart` (one of this module's: displacement, velocity, acceleration,
/// jerk over the master) redrawn in physical units at a constant master
/// speed `f`: velocity × f (pulses/s = Hz), acceleration × f² (Hz/s), jerk
/// × f³ (Hz/s²), impulses alike; with a unit, pulses × unit per pulse
/// (mm, mm/s, mm/s², mm/s³). The x axis stays the master in counts.
pub fn at_speed(mut chart: Chart, machine: Machine<'_>) -> Chart {
    let f = machine.master_hz;
    let (per_pulse, names) = match machine.unit {
        Some((unit, per)) => (
            per,
            [
                format!("displacement ({unit})"),
                format!("slave speed ({unit}/s)"),
                format!("acceleration ({unit}/s²)"),
                format!("jerk ({unit}/s³)"),
            ],
        ),
        None => (
            1.0,
            [
                DISPLACEMENT.to_string(),
                "slave speed (Hz = pulses/s)".to_string(),
                "acceleration (Hz/s)".to_string(),
                "jerk (Hz/s²)".to_string(),
            ],
        ),
    };
    for (k, (panel, name)) in chart.panels.iter_mut().zip(names).enumerate() {
        let order = i32::try_from(k).unwrap_or(0);
        let scale = per_pulse * f.powi(order);
        // An impulse in panel k is the step of the quantity of panel k − 1.
        let impulse_scale = per_pulse * f.powi(order - 1);
        let step_unit = match machine.unit {
            Some((unit, _)) => [unit.to_string(), format!("{unit}/s"), format!("{unit}/s²")],
            None => ["pulses".into(), "Hz".into(), "Hz/s".into()],
        };
        for trace in &mut panel.traces {
            let by = if trace.style == Style::Impulses {
                // Named after the quantity that steps, in its new unit.
                let stepped = trace.name.split(" step").next().unwrap_or_default();
                let unit = step_unit
                    .get(k.saturating_sub(1))
                    .cloned()
                    .unwrap_or_default();
                trace.name = format!("{stepped} step ({unit})");
                impulse_scale
            } else {
                scale
            };
            trace.y.iter_mut().for_each(|y| *y *= by);
        }
        let note = panel.title.find(", ").map(|at| &panel.title[at..]);
        panel.title = match note {
            // Keep what the estimate notes say ("…, per section)").
            Some(note) => format!("{}{note}", name.trim_end_matches(')')),
            None => name,
        };
    }
    chart.title = format!("{} at master {} counts/s", chart.title, f);
    chart
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use ecam_core::PointTable;
    use ecam_core::generator::rotary_cut;

    fn file(table: PointTable, kinematics: Option<Vec<Kinematics>>) -> TableFile {
        TableFile {
            table,
            sync: Some((0, 10)),
            generator: None,
            kinematics,
            segments: None,
        }
    }

    #[test]
    fn a_design_is_drawn_densely_with_the_points_dotted() {
        let g = rotary_cut::generate(&rotary_cut::Params::default()).unwrap();
        let n = g.table.points().len();
        let c = chart(&file(g.table.clone(), None), Some(&g.design), "rotary-cut");
        assert!(c.title.contains("design"));
        let displacement = &c.panels[0].traces;
        assert_eq!(displacement[1].style, Style::Markers);
        assert_eq!(displacement[1].x.len(), n);
        assert!(displacement[0].x.len() > 1000);
        assert_eq!(c.shaded, vec![(0.0, 10.0)]);
    }

    #[test]
    fn plain_points_say_their_derivatives_are_estimated() {
        let t = PointTable::from_pairs(&[(0, 0), (10, 10), (40, 100), (50, 100)]).unwrap();
        let c = chart(&file(t, None), None, "t.csv");
        assert!(c.title.contains("estimated from the points"));
        assert_eq!(c.panels[1].traces[0].style, Style::Steps);
        // Estimates are dots: no line joins them across a long section.
        for panel in &c.panels[2..] {
            assert!(panel.traces.iter().all(|t| t.style == Style::Markers));
        }
        // Interior joints only: masters 10 and 40.
        assert_eq!(c.panels[2].traces[0].x, vec![10.0, 40.0]);
        assert!((c.panels[2].traces[0].y[0] - 0.1).abs() < 1e-12);
        assert_eq!(c.panels[2].traces[1].x, vec![10.0, 40.0]);
    }

    #[test]
    fn a_uniform_table_is_drawn_as_its_pieces_at_fractional_masters() {
        // 4 values over 10 counts: a value every 3⅓ counts.
        let t = UniformTable::new(vec![0, 10, 30, 60], 10).unwrap();
        let c = uniform_chart(&t, Some((2, 5)), "u.json");
        assert!(
            c.title.contains("4 evenly spaced values over 10 counts"),
            "{}",
            c.title
        );
        assert_eq!(c.shaded, vec![(2.0, 5.0)]);
        let dots = &c.panels[0].traces[1];
        assert_eq!(dots.style, Style::Markers);
        assert_eq!(dots.y, vec![0.0, 10.0, 30.0, 60.0]);
        assert!((dots.x[1] - 10.0 / 3.0).abs() < 1e-12 && dots.x[3] == 10.0);
        let v = &c.panels[1].traces[0];
        assert_eq!(v.style, Style::Steps);
        for (got, want) in v.y.iter().zip([3.0, 6.0, 9.0, 9.0]) {
            assert!((got - want).abs() < 1e-12, "{:?}", v.y);
        }
        // Slopes rise by 3 per piece of 10/3 counts: 0.9 pulses/count², per
        // joint and over chords alike (the values sample a parabola).
        for trace in &c.panels[2].traces {
            assert_eq!(trace.x.len(), 2);
            for a in &trace.y {
                assert!((a - 0.9).abs() < 1e-9, "{}: {:?}", trace.name, trace.y);
            }
        }
    }

    #[test]
    fn a_profile_is_drawn_from_its_laws_with_steps_at_the_joints() {
        use ecam_core::{MotionLaw, Segment};
        let p = SegmentProfile::new(
            CamPoint::new(0, 0),
            vec![
                Segment::new(100, 1000, MotionLaw::Cycloid),
                Segment::new(200, 1000, MotionLaw::Cycloid),
                Segment::new(300, 2000, MotionLaw::ConstantVelocity),
            ],
        )
        .unwrap();
        let c = profile_chart(&p, None, "p.json");
        assert!(c.title.contains("4 key points"), "{}", c.title);
        assert!(c.shaded.is_empty());
        let dots = &c.panels[0].traces[1];
        assert_eq!(dots.x, vec![0.0, 100.0, 200.0, 300.0]);
        let v = &c.panels[1].traces[0];
        assert!(v.x.len() > 1000);
        // Peak velocity of a cycloid: 2·h/β = 20 at mid-segment.
        let peak = v.y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!((peak - 20.0).abs() < 1e-9, "{peak}");
        // At master 200 the velocity steps from 0 to 10: both ends drawn.
        let at_200: Vec<f64> =
            v.x.iter()
                .zip(&v.y)
                .filter(|(x, _)| **x == 200.0)
                .map(|(_, v)| *v)
                .collect();
        assert_eq!(at_200.len(), 2);
        assert!(at_200[0].abs() < 1e-9 && (at_200[1] - 10.0).abs() < 1e-9);
        // That velocity step is an acceleration impulse of 10 at 200; the
        // cycloid's acceleration ends at 0, as the dwell's and the
        // constant velocity's are: no jerk impulse.
        let impulses = &c.panels[2].traces[1];
        assert_eq!(impulses.style, Style::Impulses);
        assert_eq!(impulses.x, vec![200.0]);
        assert!((impulses.y[0] - 10.0).abs() < 1e-9);
        assert_eq!(c.panels[3].traces.len(), 1);
    }

    fn kin(v: f64, a: f64, j: f64) -> Kinematics {
        Kinematics { s: 0.0, v, a, j }
    }

    #[test]
    fn known_derivatives_are_held_not_joined() {
        // A rotary cut's columns: constant velocity to 200, deceleration to
        // 600, dwell to 2800. A line from the acceleration at 0 to the one
        // at 200 would ramp across the synchronised zone.
        let t = PointTable::from_pairs(&[(0, 0), (200, 333), (600, 666), (2800, 666)]).unwrap();
        let a = -1.0 / 240.0;
        let k = vec![
            kin(5.0 / 3.0, 0.0, 0.0),
            kin(5.0 / 3.0, a, 0.0),
            kin(0.0, 0.0, 0.0),
            kin(0.0, 0.0, 0.0),
        ];
        let c = chart(&file(t, Some(k)), None, "t.csv");
        assert!(c.title.contains("held to the next point"), "{}", c.title);
        let acceleration = &c.panels[2].traces[0];
        assert_eq!(acceleration.style, Style::Steps);
        assert_eq!(acceleration.y, vec![0.0, a, 0.0, 0.0]);
        // The velocity the table commands is its section slopes.
        assert_eq!(c.panels[1].traces[0].style, Style::Steps);
        assert_eq!(c.panels[1].traces[1].style, Style::Markers);
        // The jerk column is 0, but the acceleration steps at 200 and 600:
        // impulses there, sized by the steps.
        let impulses = &c.panels[3].traces[1];
        assert_eq!(impulses.style, Style::Impulses);
        assert_eq!(impulses.x, vec![200.0, 600.0]);
        assert!((impulses.y[0] - a).abs() < 1e-15 && (impulses.y[1] + a).abs() < 1e-15);
        // The velocity column is explained by the held acceleration: no
        // acceleration impulse.
        assert_eq!(c.panels[2].traces.len(), 1);
    }

    #[test]
    fn machine_units_scale_each_derivative_by_the_master_speed() {
        let t = PointTable::from_pairs(&[(0, 0), (200, 333), (600, 666), (2800, 666)]).unwrap();
        let a = -1.0 / 240.0;
        let k = vec![
            kin(2.0, 0.0, 0.0),
            kin(2.0, a, 0.0),
            kin(0.0, 0.0, 0.0),
            kin(0.0, 0.0, 0.0),
        ];
        let c = chart(&file(t, Some(k)), None, "t.csv");
        let hz = at_speed(
            c.clone(),
            Machine {
                master_hz: 1000.0,
                unit: None,
            },
        );
        assert_eq!(hz.panels[1].title, "slave speed (Hz = pulses/s)");
        assert_eq!(hz.panels[1].traces[1].y[0], 2000.0);
        assert!((hz.panels[2].traces[0].y[1] - a * 1e6).abs() < 1e-9);
        // The jerk impulse is an acceleration step: Hz/s, not Hz/s².
        assert!((hz.panels[3].traces[1].y[0] - a * 1e6).abs() < 1e-9);
        assert_eq!(
            hz.panels[3].traces[1].name,
            "impulse: acceleration step (Hz/s)"
        );
        let mm = at_speed(
            c,
            Machine {
                master_hz: 1000.0,
                unit: Some(("mm", 0.01)),
            },
        );
        assert_eq!(mm.panels[1].title, "slave speed (mm/s)");
        assert_eq!(mm.panels[1].traces[1].y[0], 20.0);
        assert_eq!(mm.panels[0].title, "displacement (mm)");
        assert!(
            mm.title.ends_with("at master 1000 counts/s"),
            "{}",
            mm.title
        );
    }

    #[test]
    fn a_smooth_law_sampled_coarsely_has_no_impulses() {
        // A cycloid (h = 1, β = 1) sampled at 11 points: its acceleration
        // changes between samples only as its jerk says.
        let tau = core::f64::consts::TAU;
        let x: Vec<f64> = (0..=10).map(|i| i as f64 / 10.0).collect();
        let a: Vec<f64> = x.iter().map(|u| tau * (tau * u).sin()).collect();
        let j: Vec<f64> = x.iter().map(|u| tau * tau * (tau * u).cos()).collect();
        assert_eq!(unexplained_steps(&x, &a, &j), (vec![], vec![]));
        // The same acceleration with a step of a quarter of its peak at 0.5.
        let mut stepped = a.clone();
        for v in &mut stepped[5..] {
            *v += 0.25 * tau;
        }
        let (at, size) = unexplained_steps(&x, &stepped, &j);
        assert_eq!(at, vec![0.5]);
        assert!((size[0] - 0.25 * tau).abs() < 0.05 * tau, "{size:?}");
    }

    #[test]
    fn a_designs_acceleration_steps_are_jerk_impulses() {
        let g = rotary_cut::generate(&rotary_cut::Params::default()).unwrap();
        let c = chart(&file(g.table.clone(), None), Some(&g.design), "rotary-cut");
        let jerk = &c.panels[3];
        // The design's jerk is 0 everywhere (constant accelerations)...
        assert!(jerk.traces[0].y.iter().all(|j| *j == 0.0));
        // ...and its acceleration steps: each step an impulse, sized by it.
        let impulses = jerk
            .traces
            .iter()
            .find(|t| t.style == Style::Impulses)
            .unwrap();
        assert!(!impulses.x.is_empty());
        let (xs, ys) = (&c.panels[2].traces[0].x, &c.panels[2].traces[0].y);
        for (at, size) in impulses.x.iter().zip(&impulses.y) {
            let k = xs.iter().position(|x| x == at).unwrap();
            assert!((ys[k + 1] - ys[k] - size).abs() < 1e-12, "at {at}");
        }
    }
}
