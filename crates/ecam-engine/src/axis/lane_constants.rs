//! The fast lane's constants of the running cam (`lane.rs`), in a file
//! of their own: the axis' phase keeps them, the lane reads and renews
//! them, and neither needs the other for it.

use crate::steady::Steady;

/// The lane's 64-bit constants of an engagement (`Engaged::lane`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LaneConstants {
    /// On the axis' geometry.
    pub(super) cam: Steady,
    /// On a slave-scaling ramp's target geometry, while one runs.
    pub(super) target: Option<Steady>,
}
