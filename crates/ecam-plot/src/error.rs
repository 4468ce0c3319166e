//! What can go wrong drawing a plot.

use std::fmt;
use std::path::PathBuf;

/// A plot that could not be drawn.
#[derive(Debug)]
pub enum PlotError {
    /// The output path's extension names no picture format.
    Extension {
        /// The path given.
        path: PathBuf,
    },
    /// The chart has no panels, or fewer than two x values in all.
    Empty,
    /// plotters failed while drawing.
    Drawing {
        /// plotters' message.
        message: String,
    },
    /// The picture could not be written.
    Write {
        /// The output file.
        path: PathBuf,
        /// plotters' message.
        message: String,
    },
}

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Extension { path } => {
                write!(f, "plot file {} must end in .svg or .png", path.display())
            }
            Self::Empty => f.write_str("nothing to plot: need at least one panel and two x values"),
            Self::Drawing { message } => write!(f, "drawing failed: {message}"),
            Self::Write { path, message } => {
                write!(f, "cannot write plot {}: {message}", path.display())
            }
        }
    }
}

impl std::error::Error for PlotError {}
