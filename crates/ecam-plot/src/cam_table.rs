//! What a cam-table plot shows: displacement, velocity, acceleration and
//! jerk over the master, the synchronised zone shaded.
//!
//! Three cases, by what is known beyond the points:
//! - **an exact curve** (a generator's [`ExactCurve`]: the S-curve, rotary
//!   cut and flying saw's design, the key points' laws; or a segment
//!   profile file): its exact derivatives, sampled densely with both sides
//!   of every corner, so steps show as vertical edges, with the table's
//!   rounded points dotted over the displacement;
//! - **derivatives at each point** (a file with `velocity,acceleration,jerk`
//!   columns, a function's table): the velocity the table commands (its
//!   section slopes, a staircase) with the file's columns dotted at the
//!   points. Nothing is known between two points, so nothing is drawn
//!   there as if it were;
//! - **only the points** (a plain `master,slave` file, an evenly spaced
//!   table): the section velocities as a staircase, acceleration and jerk
//!   estimated from the points (see [`derivatives`]) and dotted, one dot
//!   per estimate; the title says so.
//!
//! Every step of velocity is an acceleration impulse and every step of
//! acceleration a jerk impulse, drawn as arrows ([`Style::Impulses`])
//! labelled `Δv` / `Δa` and the step's size, where [`Steps`] finds them: at
//! the curve's corners and its seam (the seam's at the last master), by the
//! one rule of [`ecam_core::table::steps`]. For a table of straight
//! sections that is every point whose sections' slopes differ.

use ecam_core::generator::ExactCurve;
use ecam_core::table::steps::{Step, Steps};
use ecam_core::{CamCurve, CamPoint, Cursor, Kinematics, SegmentProfile, UniformTable};

use ecam_core::io::TableFile;
use ecam_core::table::derivatives;

use crate::{Chart, ChartPanel, Style, Trace};

/// Samples of an exact curve drawn in all (spread over its pieces).
const DESIGN_SAMPLES: usize = 2000;
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

/// The plot of `file`, over `exact` when the table was generated from one.
pub fn chart(file: &TableFile, exact: Option<&ExactCurve>, name: &str) -> Chart {
    let points = file.table.points();
    let shaded = file
        .sync
        .map(|(lo, hi)| vec![(lo as f64, hi as f64)])
        .unwrap_or_default();
    let (title, panels) = match (exact, &file.kinematics) {
        (Some(exact), _) => (
            format!(
                "cam table: {name} (lines: its exact curve; arrows: its steps as impulses; dots: the table's {} points)",
                points.len()
            ),
            exact_panels(exact, "design", ("table points", points)),
        ),
        (None, Some(known)) if known.len() == points.len() => (
            format!("cam table: {name} (dots: the file's derivative columns at its points)"),
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
    Trace::new(name, x, y, LINE)
}

/// Values known only at points, as dots: joining them with lines would
/// draw a ramp across a long section where none is known.
fn dots(name: &str, x: Vec<f64>, y: Vec<f64>) -> Trace {
    Trace::new(name, x, y, Style::Markers)
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

/// The impulses of `steps` as one trace named `name`, each labelled with
/// `quantity` (`Δv`, `Δa`), the seam's as such; `None` without steps.
pub fn impulses(name: &str, steps: &[Step], quantity: &str) -> Option<Trace> {
    if steps.is_empty() {
        return None;
    }
    let mut trace = Trace::new(
        name,
        steps.iter().map(|s| s.master).collect(),
        steps.iter().map(|s| s.size).collect(),
        Style::Impulses,
    );
    trace.tags = steps
        .iter()
        .map(|s| {
            if s.seam {
                format!("seam {quantity}")
            } else {
                quantity.to_string()
            }
        })
        .collect();
    Some(trace)
}

/// The acceleration and jerk panels' impulses: `steps`' velocity steps and
/// acceleration steps.
fn with_impulses(
    mut acceleration: Vec<Trace>,
    mut jerk: Vec<Trace>,
    steps: &Steps,
) -> [Vec<Trace>; 2] {
    acceleration.extend(impulses(ACCELERATION_IMPULSE, &steps.velocity, "Δv"));
    jerk.extend(impulses(JERK_IMPULSE, &steps.acceleration, "Δa"));
    [acceleration, jerk]
}

/// The panels of an exact curve named `name`, sampled densely, with
/// `marks` (a label and points) dotted over its displacement.
fn exact_panels(exact: &ExactCurve, name: &str, marks: (&str, &[CamPoint])) -> Vec<ChartPanel> {
    let samples = exact.samples(DESIGN_SAMPLES);
    let x: Vec<f64> = samples.iter().map(|(m, _)| *m).collect();
    let of = |f: fn(&Kinematics) -> f64| samples.iter().map(|(_, k)| f(k)).collect::<Vec<_>>();
    let [acceleration, jerk] = with_impulses(
        vec![line(name, x.clone(), of(|k| k.a))],
        vec![line(name, x.clone(), of(|k| k.j))],
        &Steps::of(exact),
    );
    vec![
        panel(
            DISPLACEMENT,
            vec![
                line(name, x.clone(), of(|k| k.s)),
                dots(marks.0, masters(marks.1), slaves(marks.1)),
            ],
        ),
        panel(VELOCITY, vec![line(name, x, of(|k| k.v))]),
        panel(ACCELERATION, acceleration),
        panel(JERK, jerk),
    ]
}

fn known_panels(points: &[CamPoint], known: &[Kinematics]) -> Vec<ChartPanel> {
    let x = masters(points);
    let of = |f: fn(&Kinematics) -> f64| known.iter().map(f).collect::<Vec<_>>();
    let sections = derivatives::forward(&x, &slaves(points));
    let [acceleration, jerk] = with_impulses(
        vec![dots("acceleration column", x.clone(), of(|k| k.a))],
        vec![dots("jerk column", x.clone(), of(|k| k.j))],
        &Steps::of_columns(points, known),
    );
    vec![
        panel(
            DISPLACEMENT,
            vec![
                line("table", x.clone(), slaves(points)),
                dots("points", x.clone(), slaves(points)),
            ],
        ),
        panel(
            VELOCITY,
            vec![
                Trace::new(
                    "table as run (section slopes)",
                    x.clone(),
                    sections,
                    Style::Steps,
                ),
                dots("velocity column", x, of(|k| k.v)),
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
    let steps = match ecam_core::PointTable::new(points.to_vec()) {
        Ok(table) => Steps::of(&table),
        Err(_) => Steps::default(),
    };
    straight_panels(straight, "points", &steps)
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

/// The panels of straight sections: their velocity steps at every corner
/// are the acceleration impulses, drawn over the estimates of the motion
/// the points sample.
fn straight_panels(straight: Straight, marks: &str, steps: &Steps) -> Vec<ChartPanel> {
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
    let smoothed = format!("estimate over ±{SMOOTHING_SECTIONS} sections");
    let [acceleration, jerk] = with_impulses(
        vec![
            dots("estimate per joint", x_inner, per_joint),
            dots(&smoothed, xs.clone(), a),
        ],
        vec![dots(&smoothed, xs, j)],
        steps,
    );
    vec![
        panel(
            DISPLACEMENT,
            vec![
                line("table", x.clone(), s.clone()),
                dots(marks, x.clone(), s),
            ],
        ),
        panel(
            "velocity (pulses/count, per section)",
            vec![Trace::new("section velocity", x, v, Style::Steps)],
        ),
        panel("acceleration (pulses/count², estimated)", acceleration),
        panel("jerk (pulses/count³, estimated)", jerk),
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
    chart_over(
        title,
        straight_panels(straight, "values", &Steps::of(table)),
        sync,
    )
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
    let key_points: Vec<CamPoint> = profile.key_points().collect();
    let exact = ExactCurve::Profile(profile.clone());
    let panels = exact_panels(&exact, "profile", ("key points", &key_points));
    let title = format!(
        "cam table: {name} (lines: its motion laws, exact; arrows: their steps as impulses; dots: its {} key points)",
        key_points.len()
    );
    chart_over(title, panels, sync)
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
    let points: Vec<CamPoint> = cam
        .points()
        .iter()
        .map(|p| CamPoint::new(p.master, p.slave))
        .collect();
    let title = format!(
        "segment cam {name}: each segment's law, exact; arrows: its steps as impulses ({} interpolation points dotted)",
        points.len()
    );
    let exact = ExactCurve::Segments(cam.clone());
    let panels = exact_panels(&exact, "profile", ("interpolation points", &points));
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

    fn impulses_of(panel: &ChartPanel) -> Vec<(f64, f64, String)> {
        panel
            .traces
            .iter()
            .filter(|t| t.style == Style::Impulses)
            .flat_map(|t| {
                t.x.iter()
                    .zip(&t.y)
                    .zip(&t.tags)
                    .map(|((x, y), tag)| (*x, *y, tag.clone()))
            })
            .collect()
    }

    #[test]
    fn a_design_is_drawn_densely_with_the_points_dotted() {
        let g = rotary_cut::generate(&rotary_cut::Params::default()).unwrap();
        let n = g.table.points().len();
        let exact = ExactCurve::Design(g.design);
        let c = chart(&file(g.table.clone(), None), Some(&exact), "rotary-cut");
        assert!(c.title.contains("exact curve"));
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
            assert!(
                panel
                    .traces
                    .iter()
                    .all(|t| matches!(t.style, Style::Markers | Style::Impulses))
            );
        }
        // Interior joints only: masters 10 and 40.
        assert_eq!(c.panels[2].traces[0].x, vec![10.0, 40.0]);
        assert!((c.panels[2].traces[0].y[0] - 0.1).abs() < 1e-12);
        assert_eq!(c.panels[2].traces[1].x, vec![10.0, 40.0]);
        // The sections' velocity steps (1 → 3 → 0, and back to 1 at the
        // seam) are the acceleration's impulses.
        assert_eq!(
            impulses_of(&c.panels[2]),
            vec![
                (10.0, 2.0, "Δv".into()),
                (40.0, -3.0, "Δv".into()),
                (50.0, 1.0, "seam Δv".into())
            ]
        );
        assert!(impulses_of(&c.panels[3]).is_empty());
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
        for trace in c.panels[2]
            .traces
            .iter()
            .filter(|t| t.style == Style::Markers)
        {
            assert_eq!(trace.x.len(), 2);
            for a in &trace.y {
                assert!((a - 0.9).abs() < 1e-9, "{}: {:?}", trace.name, trace.y);
            }
        }
        let steps: Vec<f64> = impulses_of(&c.panels[2]).iter().map(|i| i.1).collect();
        for (got, want) in steps.iter().zip([3.0, 3.0, -6.0]) {
            assert!((got - want).abs() < 1e-9, "{steps:?}");
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
        // That velocity step is an acceleration impulse of 10 at 200, and
        // the seam (10 back to the cycloid's 0) one of −10; the cycloid's
        // acceleration ends at 0, as the dwell's and the constant
        // velocity's are: no jerk impulse.
        let a = impulses_of(&c.panels[2]);
        assert_eq!(a.len(), 2);
        assert_eq!((a[0].0, a[1].0), (200.0, 300.0));
        assert!((a[0].1 - 10.0).abs() < 1e-9 && (a[1].1 + 10.0).abs() < 1e-9);
        assert_eq!(a[1].2, "seam Δv");
        assert!(impulses_of(&c.panels[3]).is_empty());
    }

    fn kin(v: f64, a: f64, j: f64) -> Kinematics {
        Kinematics { s: 0.0, v, a, j }
    }

    #[test]
    fn known_derivatives_are_dots_with_their_steps_as_impulses() {
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
        assert!(c.title.contains("derivative columns"), "{}", c.title);
        let acceleration = &c.panels[2].traces[0];
        assert_eq!(acceleration.style, Style::Markers);
        assert_eq!(acceleration.y, vec![0.0, a, 0.0, 0.0]);
        // The velocity the table commands is its section slopes.
        assert_eq!(c.panels[1].traces[0].style, Style::Steps);
        assert_eq!(c.panels[1].traces[1].style, Style::Markers);
        // The jerk column is 0, but the acceleration steps at 200 and 600:
        // impulses there, sized by the steps.
        let jerk = impulses_of(&c.panels[3]);
        assert_eq!(jerk.len(), 2, "{jerk:?}");
        assert_eq!((jerk[0].0, jerk[1].0), (200.0, 600.0));
        assert!((jerk[0].1 - a).abs() < 1e-15 && (jerk[1].1 + a).abs() < 1e-15);
        // The velocity column is explained by the acceleration between
        // points; the seam's velocity steps from 0 to 5/3.
        let velocity = impulses_of(&c.panels[2]);
        assert_eq!(velocity.len(), 1, "{velocity:?}");
        assert_eq!(velocity[0].2, "seam Δv");
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
        let jerk = hz.panels[3]
            .traces
            .iter()
            .find(|t| t.style == Style::Impulses)
            .unwrap();
        assert!((jerk.y[0] - a * 1e6).abs() < 1e-9);
        assert_eq!(jerk.name, "impulse: acceleration step (Hz/s)");
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
    fn a_designs_acceleration_steps_are_jerk_impulses_seam_included() {
        let g = rotary_cut::generate(&rotary_cut::Params::default()).unwrap();
        let exact = ExactCurve::Design(g.design);
        let c = chart(&file(g.table.clone(), None), Some(&exact), "rotary-cut");
        let jerk = &c.panels[3];
        // The design's jerk is 0 everywhere (constant accelerations)...
        assert!(jerk.traces[0].y.iter().all(|j| *j == 0.0));
        // ...and its acceleration steps: each step an impulse, sized by it,
        // the seam's (the ramp into the sync zone ends) last.
        let impulses = impulses_of(jerk);
        assert_eq!(impulses.len(), 4, "{impulses:?}");
        assert_eq!(impulses[3].2, "seam Δa");
        assert_eq!(impulses[3].0, g.table.master_last() as f64);
        let (xs, ys) = (&c.panels[2].traces[0].x, &c.panels[2].traces[0].y);
        for (at, size, _) in &impulses[..3] {
            let k = xs.iter().position(|x| x == at).unwrap();
            assert!((ys[k + 1] - ys[k] - size).abs() < 1e-12, "at {at}");
        }
        assert!((impulses[3].1 - (ys[0] - ys[ys.len() - 1])).abs() < 1e-12);
        // Velocity is continuous: no acceleration impulse.
        assert!(impulses_of(&c.panels[2]).is_empty());
    }
}
