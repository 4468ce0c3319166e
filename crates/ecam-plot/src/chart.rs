//! What a plot shows: panels of series over one shared x axis.
//!
//! A [`Figure`] is the simple form, one x vector for every series (a
//! simulation trace); a [`Chart`] the general one, each [`Trace`] with its
//! own x values and [`Style`] (a design curve sampled densely under the few
//! points of the table that samples it). A figure is drawn as the chart
//! whose traces all share its x.

/// One line in a panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend name.
    pub name: String,
    /// One y value per x of the figure.
    pub values: Vec<f64>,
}

/// One panel: a y axis with its series.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// The y quantity, with its unit, e.g. "velocity (pulse/count)".
    pub title: String,
    /// The lines drawn in this panel.
    pub series: Vec<Series>,
}

/// Panels stacked over one shared x axis.
#[derive(Clone, Debug, PartialEq)]
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
    /// A small dot at each point, no line (a table's points over its design,
    /// or samples whose values between points are not known).
    Markers,
    /// Dirac impulses: at each x an arrow from 0 (up for a positive y, down
    /// for a negative one), the largest reaching towards the panel's edge
    /// and the others in proportion, labelled with the trace's tag and y,
    /// the impulse's area (e.g. `Δa −0.0042`, the acceleration step behind
    /// a jerk impulse). y is in the unit of the quantity that steps, not of
    /// the panel, so impulses do not take part in the panel's y range.
    Impulses,
}

/// One drawn series with its own x values.
#[derive(Clone, Debug, PartialEq)]
pub struct Trace {
    /// Legend name.
    pub name: String,
    /// x values, one per y.
    pub x: Vec<f64>,
    /// y values.
    pub y: Vec<f64>,
    /// How it is drawn.
    pub style: Style,
    /// Impulses only: the text before each point's value in its label
    /// (`Δv`, `seam Δa`); missing ones are `Δ`.
    pub tags: Vec<String>,
}

impl Trace {
    /// A trace of `style` with no tags.
    pub fn new(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>, style: Style) -> Self {
        Self {
            name: name.into(),
            x,
            y,
            style,
            tags: Vec::new(),
        }
    }
}

/// One panel of a [`Chart`]: a y axis with its traces.
#[derive(Clone, Debug, PartialEq)]
pub struct ChartPanel {
    /// The y quantity, with its unit.
    pub title: String,
    /// The traces, drawn in order (later ones on top).
    pub traces: Vec<Trace>,
}

/// Panels stacked over one shared x axis, each trace with its own x values.
#[derive(Clone, Debug, PartialEq)]
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
                        .map(|s| {
                            Trace::new(
                                s.name.clone(),
                                figure.x.clone(),
                                s.values.clone(),
                                Style::Line { width },
                            )
                        })
                        .collect(),
                })
                .collect(),
            shaded: figure.shaded.clone(),
        }
    }
}
