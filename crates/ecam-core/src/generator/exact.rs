//! The exact curve behind a generated table, whichever kind it is.

use alloc::vec::Vec;

use super::DesignCurve;
use crate::segments::SegmentCam;
use crate::table::steps::{Corner, Corners};
use crate::{Kinematics, SegmentProfile};

/// What a generator knows exactly about the table it sampled: the S-curve,
/// rotary cut and flying saw their [`DesignCurve`], the key points their
/// [`SegmentProfile`] (laws between key points), the segments generator its
/// [`SegmentCam`]. Plots draw it, the steps rule reads its corners
/// ([`crate::table::steps`]).
#[derive(Clone, Debug, PartialEq)]
pub enum ExactCurve {
    /// A design of ramps and constant-velocity pieces.
    Design(DesignCurve),
    /// Key points joined by motion laws.
    Profile(SegmentProfile),
    /// Interpolation points joined by laws solved for their boundary values.
    Segments(SegmentCam),
}

impl ExactCurve {
    /// About `total` samples to draw the curve with, spread over its pieces
    /// (at least 8 per piece), both sides of every corner included so that
    /// each step shows as a vertical edge.
    pub fn samples(&self, total: usize) -> Vec<(f64, Kinematics)> {
        let per = |pieces: usize| (total / pieces.max(1)).clamp(8, total.max(8));
        match self {
            Self::Design(d) => d.sample_pieces(per(d.piece_count())),
            Self::Profile(p) => p.sample_pieces(per(p.segments().len())),
            Self::Segments(c) => c.sample_segments(per(c.segments().len())),
        }
    }

    /// The curve's key places to mark on a plot: a profile's key points, a
    /// segment cam's interpolation points (a design has none beyond its
    /// table's points).
    pub fn key_points(&self) -> Vec<(f64, f64)> {
        match self {
            Self::Design(_) => Vec::new(),
            Self::Profile(p) => p
                .key_points()
                .map(|k| (k.master as f64, k.slave as f64))
                .collect(),
            Self::Segments(c) => c
                .points()
                .iter()
                .map(|p| (p.master as f64, p.slave as f64))
                .collect(),
        }
    }
}

impl Corners for ExactCurve {
    fn corners(&self) -> Vec<Corner> {
        match self {
            Self::Design(d) => d.corners(),
            Self::Profile(p) => p.corners(),
            Self::Segments(c) => c.corners(),
        }
    }
}
