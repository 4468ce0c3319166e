//! Drawing a [`Chart`] to an SVG or PNG file with plotters.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::{Chart, Figure, PlotError, Style, font};

/// The picture formats `draw` writes, chosen by the output file's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Scalable vector graphics (`.svg`).
    Svg,
    /// Portable network graphics (`.png`).
    Png,
}

impl Format {
    /// The format for `path`'s extension, in any case.
    ///
    /// # Errors
    /// [`PlotError::Extension`] for any extension other than `svg` or `png`.
    pub fn of(path: &Path) -> Result<Self, PlotError> {
        match ecam_core::io::extension(path).as_deref() {
            Some("svg") => Ok(Self::Svg),
            Some("png") => Ok(Self::Png),
            _ => Err(PlotError::Extension {
                path: path.to_path_buf(),
            }),
        }
    }
}

const PANEL_HEIGHT: u32 = 260;
const WIDTH: u32 = 1100;

/// A chart checked and ready to be drawn to a file.
#[derive(Debug)]
pub struct Plot {
    chart: Chart,
    out: PathBuf,
    format: Format,
    text: bool,
}

impl Plot {
    /// Checks `chart` and the picture format of `out` (SVG or PNG by
    /// extension).
    ///
    /// # Errors
    /// A bad extension, or a chart without panels or x values.
    pub fn new(chart: Chart, out: &Path) -> Result<Self, PlotError> {
        let format = Format::of(out)?;
        let xs = chart
            .panels
            .iter()
            .flat_map(|p| p.traces.iter())
            .map(|t| t.x.len())
            .sum::<usize>();
        if chart.panels.is_empty() || xs < 2 {
            return Err(PlotError::Empty);
        }
        Ok(Self {
            chart,
            out: out.to_path_buf(),
            format,
            text: font::available(),
        })
    }

    /// As [`Plot::new`], for the chart of `figure`.
    ///
    /// # Errors
    /// A bad extension, or a figure without panels or two x values.
    pub fn of_figure(figure: &Figure, out: &Path) -> Result<Self, PlotError> {
        Format::of(out)?;
        if figure.panels.is_empty() || figure.x.len() < 2 {
            return Err(PlotError::Empty);
        }
        Self::new(Chart::from(figure), out)
    }

    /// Draws the chart and writes the file.
    ///
    /// # Errors
    /// A drawing or write failure.
    pub fn draw(&self) -> Result<(), PlotError> {
        let (chart, out, labels) = (&self.chart, self.out.as_path(), self.text);
        let height = PANEL_HEIGHT.saturating_mul(u32::try_from(chart.panels.len()).unwrap_or(8));
        let size = (WIDTH, height.saturating_add(if labels { 40 } else { 0 }));
        let written = match self.format {
            Format::Svg => {
                let root = SVGBackend::new(out, size).into_drawing_area();
                draw_on(&root, chart, labels)?;
                root.present().map_err(|e| e.to_string())
            }
            Format::Png => {
                let root = BitMapBackend::new(out, size).into_drawing_area();
                draw_on(&root, chart, labels)?;
                root.present().map_err(|e| e.to_string())
            }
        };
        written.map_err(|message| PlotError::Write {
            path: out.to_path_buf(),
            message,
        })
    }
}

/// Draws `figure` to `out` (SVG or PNG by extension).
///
/// # Errors
/// A bad extension, a figure without panels or x values, or a write failure.
pub fn draw(figure: &Figure, out: &Path) -> Result<(), PlotError> {
    Plot::of_figure(figure, out)?.draw()
}

/// Draws `chart` to `out` (SVG or PNG by extension).
///
/// # Errors
/// A bad extension, a chart without panels or x values, or a write failure.
pub fn draw_chart(chart: &Chart, out: &Path) -> Result<(), PlotError> {
    Plot::new(chart.clone(), out)?.draw()
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
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| PlotError::Drawing {
        message: e.to_string(),
    };
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
        // Impulses carry the size of a step, not a value of the panel's
        // quantity: they only ask for 0 to be on the axis.
        let has_impulses = panel.traces.iter().any(|t| t.style == Style::Impulses);
        let all = panel
            .traces
            .iter()
            .filter(|t| t.style != Style::Impulses)
            .flat_map(|t| t.y.iter().copied())
            .chain(has_impulses.then_some(0.0));
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
                Style::Impulses => {
                    // y is the step's size, shown as a label, not a place
                    // on the axis: not pulled in like the other values.
                    let arrows: Vec<(f64, f64)> = trace
                        .x
                        .iter()
                        .copied()
                        .zip(trace.y.iter().copied())
                        .filter(|(x, y)| x.is_finite() && y.is_finite())
                        .map(|(x, y)| (near_x(x), y))
                        .collect();
                    let head = (y_hi - y_lo) * 0.07;
                    let half = (x_hi - x_lo) * 0.004;
                    let style = color.stroke_width(2);
                    // Arrow heads and labels first: the shaft's series is
                    // the one the legend names.
                    chart
                        .draw_series(arrows.iter().map(|&(x, size)| {
                            let (tip, back) = arrow_ends(size, y_lo, y_hi, head);
                            PathElement::new([(x - half, back), (x, tip), (x + half, back)], style)
                        }))
                        .map_err(err)?;
                    // Labels only while they stay readable.
                    if labels && arrows.len() <= MAX_IMPULSE_LABELS {
                        let font = (font::FAMILY, 12).into_font().color(&color);
                        chart
                            .draw_series(arrows.iter().map(|&(x, size)| {
                                let (tip, back) = arrow_ends(size, y_lo, y_hi, head);
                                let at = if size < 0.0 { back } else { tip };
                                Text::new(
                                    format!("   Δ {}", short(size, 0.0)),
                                    (x, at),
                                    font.clone(),
                                )
                            }))
                            .map_err(err)?;
                    }
                    chart
                        .draw_series(arrows.iter().map(|&(x, size)| {
                            let (tip, _) = arrow_ends(size, y_lo, y_hi, head);
                            PathElement::new([(x, 0.0), (x, tip)], style)
                        }))
                        .map_err(err)?
                }
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

/// Impulses labelled with their size up to this many per panel; more
/// would overlap.
const MAX_IMPULSE_LABELS: usize = 24;

/// Where an impulse's arrow ends (`tip`, at the panel's edge on the side of
/// its sign) and where its head's barbs start (`back`).
fn arrow_ends(size: f64, y_lo: f64, y_hi: f64, head: f64) -> (f64, f64) {
    if size < 0.0 {
        (y_lo, y_lo + head)
    } else {
        (y_hi, y_hi - head)
    }
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
    use crate::{Panel, Series};

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
    fn empty_charts_are_refused_before_anything_is_written() {
        let out = Path::new("never-written.svg");
        let chart = Chart {
            title: "t".into(),
            x_label: "x".into(),
            panels: Vec::new(),
            shaded: Vec::new(),
        };
        assert!(matches!(
            Plot::new(chart.clone(), out),
            Err(PlotError::Empty)
        ));
        assert!(matches!(
            Plot::new(chart, Path::new("a.pdf")),
            Err(PlotError::Extension { .. })
        ));
        assert!(!out.exists());
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
