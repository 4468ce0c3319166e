//! The fast lane's constants of the running cam (`lane.rs`), in a file
//! of their own: the axis' phase keeps them, the lane reads and renews
//! them, and neither needs the other for it.

use crate::steady::Steady;

/// The lane's 64-bit constants of an engagement (`Engaged::lane`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LaneConstants {
    /// On the axis' geometry.
    pub(super) cam: Steady,
    /// Where the change under way ends: on a slave-scaling ramp's target
    /// geometry, or of the engagement an offset ramp ends on (taken when
    /// the change is asked for; missing, the lane takes them itself).
    pub(super) target: Option<Steady>,
}
