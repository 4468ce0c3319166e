//! What a cam-table plot shows: displacement, velocity, acceleration and
//! jerk over the master, the synchronised zone shaded.
//!
//! Three cases, by what is known beyond the points:
//! - **a design curve** (`ecam table gen s-curve | rotary-cut | fly-saw`):
//!   its exact derivatives, sampled densely so jumps at joints show as
//!   vertical edges, with the table's rounded points dotted over the
//!   displacement;
//! - **derivatives at each point** (a generator that knows its curve only
//!   there, or a file with `velocity,acceleration,jerk` columns): lines
//!   through those values;
//! - **only the points** (a plain `master,slave` file): the section
//!   velocities as a staircase, acceleration and jerk estimated from the
//!   points (see [`crate::derivatives`]); the title says so.

use ecam_core::generator::design_curve::DesignCurve;
use ecam_core::{CamPoint, Kinematics};

use super::{Chart, ChartPanel, Style, Trace};
use crate::derivatives;
use crate::table_file::TableFile;

/// Samples of the design curve drawn in all (spread over its pieces).
const DESIGN_SAMPLES: usize = 2000;
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
                "cam table: {name} (lines: design curve; dots: the table's {} points)",
                points.len()
            ),
            design_panels(points, design),
        ),
        (None, Some(known)) if known.len() == points.len() => {
            (format!("cam table: {name}"), known_panels(points, known))
        }
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
        panel(ACCELERATION, vec![line("design", x.clone(), of(|k| k.a))]),
        panel(JERK, vec![line("design", x, of(|k| k.j))]),
    ]
}

fn known_panels(points: &[CamPoint], known: &[Kinematics]) -> Vec<ChartPanel> {
    let x = masters(points);
    let of = |f: fn(&Kinematics) -> f64| known.iter().map(f).collect::<Vec<_>>();
    let single = |title: &str, y: Vec<f64>| {
        let name = title.split(' ').next().unwrap_or(title);
        panel(title, vec![line(name, x.clone(), y)])
    };
    vec![
        single(DISPLACEMENT, slaves(points)),
        single(VELOCITY, of(|k| k.v)),
        single(ACCELERATION, of(|k| k.a)),
        single(JERK, of(|k| k.j)),
    ]
}

fn estimated_panels(points: &[CamPoint]) -> Vec<ChartPanel> {
    let x = masters(points);
    let k = derivatives::of_points(points);
    // The per-joint estimate is 0 at the ends only for want of a second
    // section: draw the interior joints.
    let inner = 1..x.len().saturating_sub(1);
    let per_joint: Vec<f64> = k
        .get(inner.clone())
        .unwrap_or_default()
        .iter()
        .map(|k| k.a)
        .collect();
    let x_inner = x.get(inner).unwrap_or_default().to_vec();
    let (xs, a, j) = derivatives::over_sections(points, SMOOTHING_SECTIONS);
    let smoothed = format!("over ±{SMOOTHING_SECTIONS} sections");
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
            "velocity (pulses/count, per section)",
            vec![Trace {
                name: "section velocity".into(),
                x,
                y: k.iter().map(|k| k.v).collect(),
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
                    style: Style::Line { width: 1 },
                },
                line(&smoothed, xs.clone(), a),
            ],
        ),
        panel(
            "jerk (pulses/count³, estimated)",
            vec![line(&smoothed, xs, j)],
        ),
    ]
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
        // Interior joints only: masters 10 and 40.
        assert_eq!(c.panels[2].traces[0].x, vec![10.0, 40.0]);
        assert!((c.panels[2].traces[0].y[0] - 0.1).abs() < 1e-12);
        assert_eq!(c.panels[2].traces[1].x, vec![10.0, 40.0]);
    }

    #[test]
    fn known_derivatives_are_drawn_as_given() {
        let t = PointTable::from_pairs(&[(0, 0), (10, 10)]).unwrap();
        let k = vec![Kinematics::at_rest(0.0), Kinematics::at_rest(10.0)];
        let c = chart(&file(t, Some(k)), None, "t.csv");
        assert_eq!(c.title, "cam table: t.csv");
        assert_eq!(c.panels[1].traces[0].y, vec![0.0, 0.0]);
        assert_eq!(c.panels[1].traces[0].name, "velocity");
    }
}
