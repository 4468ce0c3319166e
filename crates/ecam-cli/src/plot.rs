//! Drawing `ecam`'s plots with `ecam_plot` (its font is embedded).

use std::path::Path;

use ecam_plot::{Chart, Figure, Plot};

pub use ecam_plot::Format;

/// Draws `figure` to `out` (SVG or PNG by extension).
///
/// # Errors
/// As [`ecam_plot::draw`].
pub fn draw(figure: &Figure, out: &Path) -> anyhow::Result<()> {
    Plot::of_figure(figure, out)?.draw()?;
    Ok(())
}

/// Draws `chart` to `out` (SVG or PNG by extension).
///
/// # Errors
/// As [`ecam_plot::draw_chart`].
pub fn draw_chart(chart: Chart, out: &Path) -> anyhow::Result<()> {
    Plot::new(chart, out)?.draw()?;
    Ok(())
}
