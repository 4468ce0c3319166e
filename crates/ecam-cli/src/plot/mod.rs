//! Plots: stacked panels sharing one x axis, drawn to SVG or PNG.
//!
//! A cam table is shown as displacement, velocity, acceleration and jerk over
//! the master; a simulation trace as master, slave, velocity and backlog over
//! time. Both are a [`Figure`]: one x vector, several panels of y series, and
//! optional shaded x ranges (the synchronised zone of a rotary cut, or the
//! times a sync window output was on).
//!
//! A [`Chart`] is the general form: every [`Trace`] has its own x values and
//! a [`Style`], so a smooth design curve sampled densely can share a panel
//! with the few points of the table that samples it. A [`Figure`] is drawn
//! as the chart whose traces all share its x.

pub mod cam_table;
mod font;

use std::path::Path;

use anyhow::{Context, anyhow, bail};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One line in a panel.
pub struct Series {
    /// Legend name.
    pub name: String,
    /// One y value per x of the figure.
    pub values: Vec<f64>,
}

/// One panel: a y axis with its series.
pub struct Panel {
    /// The y quantity, with its unit, e.g. "velocity (pulse/count)".
    pub title: String,
    /// The lines drawn in this panel.
    pub series: Vec<Series>,
}

/// Panels stacked over one shared x axis.
pub struct Figure {
    /// Title above the first panel.
    pub title: String,
    /// The x quantity, with its unit.
    pub x_label: String,
    /// The shared x values.
    pub x: Vec<f64>,
    /// Panels, top to bottom.
    pub panels: Vec<Panel>,
    /// x ranges shaded in every panel.
    pub shaded: Vec<(f64, f64)>,
}

/// How a trace is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// A line through the points, `width` pixels wide.
    Line {
        /// Stroke width in pixels.
        width: u32,
    },
    /// A staircase: `y[i]` holds from `x[i]` to `x[i + 1]` (a point table's
    /// section velocities); the last value is drawn as a point.
    Steps,
    /// A small dot at each point, no line (a table's points over its design).
    Markers,
}

/// One drawn series with its own x values.
pub struct Trace {
    /// Legend name.
    pub name: String,
    /// x values, one per y.
    pub x: Vec<f64>,
    /// y values.
    pub y: Vec<f64>,
    /// How it is drawn.
    pub style: Style,
}

/// One panel of a [`Chart`]: a y axis with its traces.
pub struct ChartPanel {
    /// The y quantity, with its unit.
    pub title: String,
    /// The traces, drawn in order (later ones on top).
    pub traces: Vec<Trace>,
}

/// Panels stacked over one shared x axis, each trace with its own x values.
pub struct Chart {
    /// Title above the first panel.
    pub title: String,
    /// The x quantity, with its unit.
    pub x_label: String,
    /// Panels, top to bottom.
    pub panels: Vec<ChartPanel>,
    /// x ranges shaded in every panel.
    pub shaded: Vec<(f64, f64)>,
}

impl From<&Figure> for Chart {
    fn from(figure: &Figure) -> Self {
        // Wide strokes on dense zig-zags grow miter spikes past the
        // panel: thin lines once there are more points than pixels.
        let width = if figure.x.len() > 1000 { 1 } else { 2 };
        Self {
            title: figure.title.clone(),
            x_label: figure.x_label.clone(),
            panels: figure
                .panels
                .iter()
                .map(|p| ChartPanel {
                    title: p.title.clone(),
                    traces: p
                        .series
                        .iter()
                        .map(|s| Trace {
                            name: s.name.clone(),
                            x: figure.x.clone(),
                            y: s.values.clone(),
                            style: Style::Line { width },
                        })
                        .collect(),
                })
                .collect(),
            shaded: figure.shaded.clone(),
        }
    }
}

/// The picture formats `draw` writes, chosen by the output file's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Scalable vector graphics (`.svg`).
    Svg,
    /// Portable network graphics (`.png`).
    Png,
}

impl Format {
    /// The format for `path`'s extension.
    ///
    /// # Errors
    /// Any extension other than `svg` or `png`.
    pub fn of(path: &Path) -> anyhow::Result<Self> {
        match crate::table_file::extension(path).as_deref() {
            Some("svg") => Ok(Self::Svg),
            Some("png") => Ok(Self::Png),
            _ => bail!("plot file {} must end in .svg or .png", path.display()),
        }
    }
}

const PANEL_HEIGHT: u32 = 260;
const WIDTH: u32 = 1100;

/// Draws `figure` to `out` (SVG or PNG by extension).
///
/// # Errors
/// A bad extension, a figure without panels or x values, or a write failure.
pub fn draw(figure: &Figure, out: &Path) -> anyhow::Result<()> {
    Format::of(out)?;
    if figure.panels.is_empty() || figure.x.len() < 2 {
        bail!("nothing to plot: need at least one panel and two x values");
    }
    draw_chart(&Chart::from(figure), out)
}

/// Draws `chart` to `out` (SVG or PNG by extension).
///
/// # Errors
/// A bad extension, a chart without panels or x values, or a write failure.
pub fn draw_chart(chart: &Chart, out: &Path) -> anyhow::Result<()> {
    let format = Format::of(out)?;
    let xs = chart
        .panels
        .iter()
        .flat_map(|p| p.traces.iter())
        .map(|t| t.x.len())
        .sum::<usize>();
    if chart.panels.is_empty() || xs < 2 {
        bail!("nothing to plot: need at least one panel and two x values");
    }
    let labels = font::available();
    if !labels {
        eprintln!(
            "ecam: no TrueType font found (set ECAM_FONT=/path/to/font.ttf); plot drawn without text"
        );
    }
    let height = PANEL_HEIGHT.saturating_mul(u32::try_from(chart.panels.len()).unwrap_or(8));
    let size = (WIDTH, height.saturating_add(if labels { 40 } else { 0 }));
    let written = match format {
        Format::Svg => {
            let root = SVGBackend::new(out, size).into_drawing_area();
            draw_on(&root, chart, labels)?;
            root.present().map_err(|e| anyhow!("{e}"))
        }
        Format::Png => {
            let root = BitMapBackend::new(out, size).into_drawing_area();
            draw_on(&root, chart, labels)?;
            root.present().map_err(|e| anyhow!("{e}"))
        }
    };
    written.with_context(|| format!("cannot write plot {}", out.display()))
}

/// A colour per series, readable on white.
const COLORS: [RGBColor; 5] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
];

const SHADE: RGBColor = RGBColor(255, 221, 120);

fn draw_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    figure: &Chart,
    labels: bool,
) -> anyhow::Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("drawing failed: {e}");
    root.fill(&WHITE).map_err(err)?;
    let body = if labels {
        let (top, rest) = root.split_vertically(40);
        top.titled(&figure.title, (font::FAMILY, 22)).map_err(err)?;
        rest
    } else {
        root.clone()
    };
    let areas = body.split_evenly((figure.panels.len(), 1));
    let all_x = figure
        .panels
        .iter()
        .flat_map(|p| p.traces.iter())
        .flat_map(|t| t.x.iter().copied());
    let (x_lo, x_hi) = range_of(all_x);
    let (x_lo, x_hi) = if x_hi > x_lo {
        (x_lo, x_hi)
    } else {
        (x_lo - 1.0, x_lo + 1.0)
    };
    for (i, (panel, area)) in figure.panels.iter().zip(areas.iter()).enumerate() {
        let last = i + 1 == figure.panels.len();
        let all = panel.traces.iter().flat_map(|t| t.y.iter().copied());
        let (y_lo, y_hi) = padded(range_of(all));
        let mut builder = ChartBuilder::on(area);
        builder.margin(8).margin_right(24);
        if labels {
            builder
                .x_label_area_size(if last { 40 } else { 22 })
                .y_label_area_size(80);
        }
        let mut chart = builder
            .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)
            .map_err(err)?;
        let legend = labels && panel.traces.len() > 1;
        let mut mesh = chart.configure_mesh();
        mesh.light_line_style(RGBColor(235, 235, 235));
        // Ticks computed in floating point land a hair off zero; labels
        // round anything below a billionth of the axis span to 0.
        let y_zero = (y_hi - y_lo) * 1e-9;
        let x_zero = (x_hi - x_lo) * 1e-9;
        let y_fmt = move |v: &f64| short(*v, y_zero);
        let x_fmt = move |v: &f64| short(*v, x_zero);
        if labels {
            mesh.y_desc(panel.title.as_str())
                .label_style((font::FAMILY, 13))
                .axis_desc_style((font::FAMILY, 14))
                .y_label_formatter(&y_fmt)
                .x_label_formatter(&x_fmt);
            if last {
                mesh.x_desc(figure.x_label.as_str());
            }
        } else {
            mesh.x_labels(0).y_labels(0);
        }
        mesh.draw().map_err(err)?;
        // Anything far outside the axes is pulled in to just beyond them:
        // the plotting library maps coordinates to pixels in `i32` and
        // overflows (a panic) on values many spans away; the drawing area
        // still clips what lies outside.
        let (x_span, y_span) = (x_hi - x_lo, y_hi - y_lo);
        let near_x = move |x: f64| x.clamp(x_lo - x_span, x_hi + x_span);
        let near_y = move |y: f64| y.clamp(y_lo - y_span, y_hi + y_span);
        for &(lo, hi) in &figure.shaded {
            let (lo, hi) = (near_x(lo), near_x(hi));
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(lo, y_lo), (hi, y_hi)],
                    SHADE.mix(0.35).filled(),
                )))
                .map_err(err)?;
        }
        for (k, trace) in panel.traces.iter().enumerate() {
            let color = COLORS.get(k % COLORS.len()).copied().unwrap_or(BLACK);
            let points = trace
                .x
                .iter()
                .copied()
                .zip(trace.y.iter().copied())
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .map(|(x, y)| (near_x(x), near_y(y)));
            let drawn = match trace.style {
                Style::Line { width } => chart
                    .draw_series(LineSeries::new(points, color.stroke_width(width)))
                    .map_err(err)?,
                Style::Steps => chart
                    .draw_series(LineSeries::new(
                        staircase(points.collect()),
                        color.stroke_width(2),
                    ))
                    .map_err(err)?,
                Style::Markers => chart
                    .draw_series(points.map(|p| Circle::new(p, 2, color.filled())))
                    .map_err(err)?,
            };
            if legend {
                let label = drawn.label(trace.name.as_str());
                match trace.style {
                    Style::Markers => {
                        label.legend(move |(x, y)| Circle::new((x + 9, y), 3, color.filled()))
                    }
                    _ => label.legend(move |(x, y)| {
                        PathElement::new([(x, y), (x + 18, y)], color.stroke_width(2))
                    }),
                };
            }
        }
        if legend {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(200, 200, 200))
                .label_font((font::FAMILY, 13))
                .draw()
                .map_err(err)?;
        }
    }
    Ok(())
}

/// Compact tick labels: 12000, 1.5, 0.00013 → "1.30e-4"; |v| ≤ `zero` is 0.
fn short(v: f64, zero: f64) -> String {
    let a = v.abs();
    if a <= zero {
        "0".into()
    } else if (1e-3..1e6).contains(&a) {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format!("{v:.2e}")
    }
}

/// The corners of a staircase through `points`: each y holds until the
/// next x, where the line steps vertically to the next y.
fn staircase(points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(points.len().saturating_mul(2));
    for pair in points.windows(2) {
        if let [(x0, y0), (x1, _)] = *pair {
            out.push((x0, y0));
            out.push((x1, y0));
        }
    }
    if let Some(&last) = points.last() {
        out.push(last);
    }
    out
}

fn range_of(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi { (0.0, 0.0) } else { (lo, hi) }
}

/// Largest axis bound drawn. Beyond it the span (and the tick spacing the
/// plotting library derives from it) overflows to infinity, and the library
/// then loops forever looking for ticks; points beyond it are clipped.
const AXIS_LIMIT: f64 = 1e300;

/// Adds 5 % head room, and gives a flat line a visible band.
fn padded((lo, hi): (f64, f64)) -> (f64, f64) {
    let (lo, hi) = (
        lo.clamp(-AXIS_LIMIT, AXIS_LIMIT),
        hi.clamp(-AXIS_LIMIT, AXIS_LIMIT),
    );
    let span = hi - lo;
    let pad = if span > 1e-12 * hi.abs().max(lo.abs()).max(1e-300) {
        span * 0.05
    } else {
        lo.abs().max(1.0) * 0.05
    };
    (lo - pad, hi + pad)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn huge_values_give_a_finite_axis() {
        let (lo, hi) = padded(range_of([-1e308, 1e308].into_iter()));
        assert!(lo.is_finite() && hi.is_finite() && hi > lo);
        assert!((hi - lo).is_finite());
        let (lo, hi) = padded((f64::MAX, f64::MAX));
        assert!(lo.is_finite() && hi.is_finite() && hi > lo);
    }

    #[test]
    fn format_follows_extension() {
        assert_eq!(Format::of(Path::new("a.SVG")).unwrap(), Format::Svg);
        assert_eq!(Format::of(Path::new("a.png")).unwrap(), Format::Png);
        assert!(Format::of(Path::new("a.pdf")).is_err());
    }

    #[test]
    fn flat_series_get_a_band() {
        let (lo, hi) = padded((5.0, 5.0));
        assert!(lo < 5.0 && hi > 5.0);
    }

    #[test]
    fn staircase_holds_each_value_until_the_next_x() {
        let s = staircase(vec![(0.0, 1.0), (2.0, 3.0), (5.0, 3.0)]);
        assert_eq!(
            s,
            vec![(0.0, 1.0), (2.0, 1.0), (2.0, 3.0), (5.0, 3.0), (5.0, 3.0)]
        );
        assert!(staircase(Vec::new()).is_empty());
    }

    #[test]
    fn a_figure_becomes_a_chart_of_lines() {
        let figure = Figure {
            title: "t".into(),
            x_label: "x".into(),
            x: vec![0.0, 1.0],
            panels: vec![Panel {
                title: "p".into(),
                series: vec![Series {
                    name: "s".into(),
                    values: vec![2.0, 3.0],
                }],
            }],
            shaded: vec![(0.0, 0.5)],
        };
        let chart = Chart::from(&figure);
        let trace = &chart.panels[0].traces[0];
        assert_eq!(
            (trace.x.clone(), trace.y.clone()),
            (vec![0.0, 1.0], vec![2.0, 3.0])
        );
        assert_eq!(trace.style, Style::Line { width: 2 });
        assert_eq!(chart.shaded, figure.shaded);
    }

    #[test]
    fn short_labels() {
        assert_eq!(short(12000.0, 0.0), "12000");
        assert_eq!(short(1.5, 0.0), "1.5");
        assert_eq!(short(0.0, 0.0), "0");
        assert_eq!(short(-2.7e-17, 1e-9), "0");
        assert_eq!(short(1.3e-4, 0.0), "1.30e-4");
    }
}
