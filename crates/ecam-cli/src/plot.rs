//! Drawing `ecam`'s plots: `ecam_plot` draws them; this says on stderr
//! when it has to do so without text.

use std::path::Path;

use ecam_plot::{Chart, Figure, Plot};

pub use ecam_plot::Format;

/// Draws `figure` to `out` (SVG or PNG by extension).
///
/// # Errors
/// As [`ecam_plot::draw`].
pub fn draw(figure: &Figure, out: &Path) -> anyhow::Result<()> {
    draw_plot(Plot::of_figure(figure, out)?)
}

/// Draws `chart` to `out` (SVG or PNG by extension).
///
/// # Errors
/// As [`ecam_plot::draw_chart`].
pub fn draw_chart(chart: Chart, out: &Path) -> anyhow::Result<()> {
    draw_plot(Plot::new(chart, out)?)
}

fn draw_plot(plot: Plot) -> anyhow::Result<()> {
    if !plot.has_text() {
        eprintln!(
            "ecam: no TrueType font found (set ECAM_FONT=/path/to/font.ttf); plot drawn without text"
        );
    }
    plot.draw()?;
    Ok(())
}
