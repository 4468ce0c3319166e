//! Drawing a [`Chart`] to an SVG or PNG file with plotters.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::{Chart, Figure, PlotError, Style, Trace, font, labels};

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

/// Height of the strip above each panel that holds its legend: legends
/// sit outside the data, never on it.
const LEGEND_HEIGHT: u32 = 20;
/// Room right of the plot, pixels: the labels of impulses at the last
/// master (a seam) go there when the plot is crowded.
const RIGHT_MARGIN: i32 = 96;
/// Width of the y axis' label area (tick labels and the rotated title).
const Y_LABEL_AREA: u32 = 80;
/// Font sizes: title, axis titles, tick labels, legend, impulse labels.
const TITLE_SIZE: f64 = 20.0;
const AXIS_TITLE_SIZE: f64 = 14.0;
const TICK_SIZE: f64 = 13.0;
const LEGEND_SIZE: f64 = 13.0;
const IMPULSE_LABEL_SIZE: f64 = 12.0;
/// Shortest arrow drawn, pixels: a small impulse still shows.
const MIN_ARROW: i32 = 12;
/// Impulses closer than this on average, pixels, are too many to label.
const DENSE_SPACING: i32 = 16;
/// Pixels kept free beyond the longest arrow's head, for a label.
const LABEL_ROOM: i32 = 22;

/// The largest font size not above `size` at which `text` is at most
/// `room` pixels wide (down to 8 px): a title never runs off the picture.
fn fitting<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    size: f64,
    room: u32,
) -> f64 {
    let mut size = size;
    while size > 8.0 {
        let font: TextStyle = (font::FAMILY, size).into_font().into();
        match area.estimate_text_size(text, &font) {
            Ok((w, _)) if w > room => size -= 1.0,
            _ => break,
        }
    }
    size
}

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
        let size = fitting(root, &figure.title, TITLE_SIZE, WIDTH - 20);
        top.titled(&figure.title, (font::FAMILY, size))
            .map_err(err)?;
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
        let (legend_area, area) = if labels {
            let (legend, rest) = area.split_vertically(LEGEND_HEIGHT);
            (Some(legend), rest)
        } else {
            (None, area.clone())
        };
        // Impulses carry the size of a step, not a value of the panel's
        // quantity: they only ask for 0 to be on the axis.
        let has_impulses = panel.traces.iter().any(|t| t.style == Style::Impulses);
        let values = panel
            .traces
            .iter()
            .filter(|t| t.style != Style::Impulses)
            .flat_map(|t| t.y.iter().copied());
        let (lo, hi) = range_of(values.chain(has_impulses.then_some(0.0)));
        // Arrows need room on their side of 0: a panel whose curves stay
        // above 0 gets room below it for negative impulses, and so on.
        let signs = |negative: bool| {
            panel
                .traces
                .iter()
                .filter(|t| t.style == Style::Impulses)
                .flat_map(|t| t.y.iter())
                .any(|y| (*y < 0.0) == negative && *y != 0.0)
        };
        let lo = if signs(true) { lo.min(-0.6 * hi) } else { lo };
        let hi = if signs(false) { hi.max(-0.6 * lo) } else { hi };
        // A panel whose curves are all zero (a design's jerk between its
        // impulses) has no scale to show: a band around 0, labelled 0 only.
        let flat_zero = lo == 0.0 && hi == 0.0;
        let (y_lo, y_hi) = if flat_zero {
            (-1.0, 1.0)
        } else {
            padded((lo, hi))
        };
        let mut builder = ChartBuilder::on(&area);
        builder.margin(8).margin_top(4).margin_right(RIGHT_MARGIN);
        if labels {
            builder
                .x_label_area_size(if last { 40 } else { 22 })
                .y_label_area_size(Y_LABEL_AREA);
        }
        let mut chart = builder
            .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)
            .map_err(err)?;
        let (plot_x, plot_y) = chart.plotting_area().get_pixel_range();
        let mut mesh = chart.configure_mesh();
        mesh.light_line_style(RGBColor(235, 235, 235));
        // Ticks computed in floating point land a hair off zero; labels
        // round anything below a billionth of the axis span to 0.
        let y_zero = (y_hi - y_lo) * 1e-9;
        let x_zero = (x_hi - x_lo) * 1e-9;
        let y_fmt = move |v: &f64| {
            if flat_zero && v.abs() > y_zero {
                String::new()
            } else {
                short(*v, y_zero)
            }
        };
        let x_fmt = move |v: &f64| short(*v, x_zero);
        if labels {
            let room = u32::try_from(plot_y.end - plot_y.start).unwrap_or(0);
            let desc = fitting(root, &panel.title, AXIS_TITLE_SIZE, room);
            mesh.y_desc(panel.title.as_str())
                .label_style((font::FAMILY, TICK_SIZE))
                .axis_desc_style((font::FAMILY, desc))
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
        let plot = labels::Rect {
            x: plot_x.start,
            y: plot_y.start,
            w: plot_x.end - plot_x.start,
            h: plot_y.end - plot_y.start,
        };
        let mut legend = Vec::new();
        for (k, trace) in panel.traces.iter().enumerate() {
            let color = COLORS.get(k % COLORS.len()).copied().unwrap_or(BLACK);
            legend.push((trace.name.clone(), trace.style, color));
            let points = trace
                .x
                .iter()
                .copied()
                .zip(trace.y.iter().copied())
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .map(|(x, y)| (near_x(x), near_y(y)));
            match trace.style {
                Style::Line { width } => {
                    chart
                        .draw_series(LineSeries::new(points, color.stroke_width(width)))
                        .map_err(err)?;
                }
                Style::Steps => {
                    chart
                        .draw_series(LineSeries::new(
                            staircase(points.collect()),
                            color.stroke_width(2),
                        ))
                        .map_err(err)?;
                }
                Style::Markers => {
                    chart
                        .draw_series(points.map(|p| Circle::new(p, 2, color.filled())))
                        .map_err(err)?;
                }
                Style::Impulses => {
                    let zero = chart.backend_coord(&(x_lo, 0.0)).1;
                    let arrows = impulse_arrows(trace, zero, plot, |x| {
                        chart.backend_coord(&(near_x(x), 0.0)).0
                    });
                    let room = labels::Rect {
                        w: plot.w + RIGHT_MARGIN - 8,
                        ..plot
                    };
                    // Too many to label (a point table's every corner):
                    // thin arrows, and the legend says how many.
                    let dense = arrows.len() as i32 * DENSE_SPACING > plot.w;
                    if let (true, Some(entry)) = (dense, legend.last_mut()) {
                        let largest = trace.y.iter().fold(0.0_f64, |m, y| m.max(y.abs()));
                        entry.0 = format!(
                            "{} ({} impulses, largest ±{})",
                            trace.name,
                            arrows.len(),
                            short(largest, 0.0)
                        );
                    }
                    draw_impulses(root, &arrows, color, labels && !dense, room, dense)
                        .map_err(err)?;
                }
            }
        }
        if let Some(strip) = legend_area.filter(|_| legend.len() > 1) {
            draw_legend(root, &strip, plot.x, &legend).map_err(err)?;
        }
    }
    Ok(())
}

/// One impulse as drawn: its arrow in pixels and its label's text.
struct ImpulseArrow {
    arrow: labels::Arrow,
    text: String,
}

/// The arrows of an impulse trace over a zero line at pixel row `zero`:
/// the largest impulse reaches almost to the plot's edge, the others in
/// proportion (at least [`MIN_ARROW`] pixels).
fn impulse_arrows(
    trace: &Trace,
    zero: i32,
    plot: labels::Rect,
    column: impl Fn(f64) -> i32,
) -> Vec<ImpulseArrow> {
    let impulses: Vec<(usize, f64, f64)> = trace
        .x
        .iter()
        .zip(&trace.y)
        .enumerate()
        .filter(|(_, (x, y))| x.is_finite() && y.is_finite())
        .map(|(k, (x, y))| (k, *x, *y))
        .collect();
    let largest = impulses.iter().fold(0.0_f64, |m, (_, _, y)| m.max(y.abs()));
    // Room is left beyond the longest arrow for its label.
    let up_room = zero - plot.y - LABEL_ROOM;
    let down_room = plot.y + plot.h - zero - LABEL_ROOM;
    impulses
        .into_iter()
        .map(|(k, x, size)| {
            let room = if size < 0.0 { down_room } else { up_room }.max(MIN_ARROW);
            let share = if largest > 0.0 {
                size.abs() / largest
            } else {
                1.0
            };
            let len = ((room as f64 * share).round() as i32).clamp(MIN_ARROW, room);
            let tip = if size < 0.0 { zero + len } else { zero - len };
            let tag = trace.tags.get(k).map_or("Δ", String::as_str);
            ImpulseArrow {
                arrow: labels::Arrow {
                    x: column(x),
                    base_y: zero,
                    tip_y: tip,
                    text_w: 0,
                    text_h: 0,
                },
                text: format!("{tag} {}", short(size, 0.0)),
            }
        })
        .collect()
}

/// Draws `arrows` in `color`, and their labels where
/// [`labels::place`] finds room.
fn draw_impulses<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    arrows: &[ImpulseArrow],
    color: RGBColor,
    text: bool,
    plot: labels::Rect,
    thin: bool,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (style, head) = if thin {
        (color.mix(0.6).stroke_width(1), 3)
    } else {
        (color.stroke_width(2), 4)
    };
    for a in arrows {
        let (x, base, tip) = (a.arrow.x, a.arrow.base_y, a.arrow.tip_y);
        let back = if tip < base {
            tip + 2 * head
        } else {
            tip - 2 * head
        };
        root.draw(&PathElement::new([(x, base), (x, tip)], style))?;
        root.draw(&PathElement::new(
            [(x - head, back), (x, tip), (x + head, back)],
            style,
        ))?;
    }
    if !text {
        return Ok(());
    }
    let font = (font::FAMILY, IMPULSE_LABEL_SIZE).into_font().color(&color);
    let measured: Vec<labels::Arrow> = arrows
        .iter()
        .map(|a| {
            let (w, h) = root.estimate_text_size(&a.text, &font).unwrap_or((0, 0));
            labels::Arrow {
                text_w: i32::try_from(w).unwrap_or(i32::MAX),
                text_h: i32::try_from(h).unwrap_or(i32::MAX),
                ..a.arrow
            }
        })
        .collect();
    for (a, at) in arrows.iter().zip(labels::place(&measured, plot)) {
        if let Some(at) = at {
            root.draw(&Text::new(a.text.as_str(), at, font.clone()))?;
        }
    }
    Ok(())
}

/// Draws the legend of one panel in its strip above the plot: each
/// trace's symbol and name, side by side from the plot's left edge.
fn draw_legend<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    strip: &DrawingArea<DB, Shift>,
    left: i32,
    entries: &[(String, Style, RGBColor)],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (_, ys) = strip.get_pixel_range();
    let y = (ys.start + ys.end) / 2;
    let font: TextStyle = (font::FAMILY, LEGEND_SIZE).into_font().into();
    let mut x = left;
    for (name, style, color) in entries {
        let (name, color) = (name.as_str(), *color);
        match *style {
            Style::Markers => {
                root.draw(&Circle::new((x + 9, y), 3, color.filled()))?;
            }
            Style::Impulses => {
                let s = color.stroke_width(2);
                root.draw(&PathElement::new([(x + 9, y + 6), (x + 9, y - 6)], s))?;
                root.draw(&PathElement::new(
                    [(x + 5, y - 1), (x + 9, y - 6), (x + 13, y - 1)],
                    s,
                ))?;
            }
            _ => {
                root.draw(&PathElement::new(
                    [(x, y), (x + 18, y)],
                    color.stroke_width(2),
                ))?;
            }
        }
        let (w, h) = root.estimate_text_size(name, &font)?;
        let h = i32::try_from(h).unwrap_or(0);
        root.draw(&Text::new(name, (x + 24, y - h / 2), font.clone()))?;
        x += 24 + i32::try_from(w).unwrap_or(0) + 18;
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
    // A flat line gets a band of ±5 % of its own value (of 1 at 0): an
    // absolute band would dwarf a small value in the panel's units.
    let pad = if span > 1e-12 * hi.abs().max(lo.abs()).max(1e-300) {
        span * 0.05
    } else if lo != 0.0 {
        lo.abs() * 0.05
    } else {
        0.05
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
