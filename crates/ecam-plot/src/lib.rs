//! # ecam-plot: pictures of cams and simulation runs
//!
//! Stacked panels sharing one x axis, drawn to SVG or PNG with
//! [plotters](https://docs.rs/plotters): a cam table as displacement,
//! velocity, acceleration and jerk over the master ([`cam_table`]), a
//! simulation trace as whatever series over time its caller collects
//! ([`Figure`]). Shaded x ranges mark the synchronised zone of a rotary cut
//! or the times a sync window output was on.
//!
//! Use it to look at a design or a run; it draws files, it does not show
//! windows, and it is not a general plotting library (one layout, one
//! colour scheme).
//!
//! Labels are drawn with DejaVu Sans, compiled into the crate (its licence
//! is `fonts/LICENSE-DejaVu.txt`): a PNG looks the same on every machine
//! and needs no font installed. An SVG keeps its labels as text naming
//! `DejaVu Sans, sans-serif`, so a viewer without DejaVu Sans draws them in
//! its own sans-serif.
//!
//! ```
//! use ecam_plot::{Figure, Panel, Series, draw};
//!
//! let figure = Figure {
//!     title: "a ramp".into(),
//!     x_label: "time (s)".into(),
//!     x: vec![0.0, 1.0, 2.0],
//!     panels: vec![Panel {
//!         title: "slave (pulses)".into(),
//!         series: vec![Series { name: "commanded".into(), values: vec![0.0, 5.0, 20.0] }],
//!     }],
//!     shaded: vec![(0.5, 1.5)],
//! };
//! let out = std::env::temp_dir().join(format!("ecam-plot-doc-{}.svg", std::process::id()));
//! draw(&figure, &out)?;
//! assert!(std::fs::read_to_string(&out)?.starts_with("<svg"));
//! std::fs::remove_file(&out)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A table read with `ecam_core::io` is drawn through [`cam_table`]:
//!
//! ```
//! use ecam_core::io::{AnyTable, TableFile};
//! use ecam_plot::cam_table;
//!
//! let text = "master,slave\n0,0\n100,20\n200,80\n300,100\n";
//! let chart = cam_table::chart(&TableFile::from_csv(text)?, None, "t.csv");
//! assert_eq!(chart.panels.len(), 4); // displacement, velocity, acceleration, jerk
//! assert!(chart.title.contains("estimated from the points"));
//! # Ok::<(), ecam_core::io::FormatError>(())
//! ```

pub mod cam_table;
mod chart;
mod draw;
mod error;
mod font;
mod labels;

pub use chart::{Chart, ChartPanel, Figure, Panel, Series, Style, Trace};
pub use draw::{Format, Plot, draw, draw_chart};
pub use error::PlotError;
