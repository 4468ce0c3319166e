//! A switch prepared when it was asked for (`plan.rs` prepares it, the
//! fast lane, `lane.rs`, puts it in place): what the running axis keeps
//! of it, in a file of its own so that the axis' phase, the lane and the
//! planner each use it without using one another.

use crate::Zoom;
use crate::blend::Blend;
use crate::coupling::{Engagement, Geometry};
use crate::steady::Steady;

use super::landing::Landing;

/// A prepared switch: for the switch or the seam table waiting in
/// `Engaged::underway`.
#[derive(Clone, Debug)]
pub(super) enum Plan {
    /// A position or at-once switch (or master-scaling change), by the
    /// master position it takes effect at.
    Switch {
        /// The old cam's constants it was prepared from.
        old: Steady,
        landings: [Option<(i64, Prepared)>; 2],
    },
    /// A table queued for the seam, crossing the end (`[0]`) or the start
    /// (`[1]`) of cycle `from_k`.
    Seam {
        old: Steady,
        from_k: i128,
        landings: [Option<Prepared>; 2],
    },
}

/// One prepared landing: where the cam stands after the switch.
#[derive(Clone, Debug)]
pub(super) struct Prepared {
    pub(super) engagement: Engagement,
    pub(super) geometry: Geometry,
    pub(super) cursor: ecam_core::Cursor,
    pub(super) master_zoom: Option<Zoom>,
    pub(super) blend: Option<Blend>,
    /// The new engagement's 64-bit constants (the lane follows it with them).
    pub(super) constants: Steady,
}

impl Prepared {
    /// A landing the lane can take: no error anywhere and constants in 64 bits.
    pub(super) fn of(landing: Result<Landing, crate::EngineError>) -> Option<Self> {
        let landing = landing.ok()?;
        let constants = landing.engagement.steady(&landing.geometry)?;
        Some(Self {
            engagement: landing.engagement,
            geometry: landing.geometry,
            cursor: landing.cursor,
            master_zoom: landing.master_zoom,
            blend: landing.blend.ok()?,
            constants,
        })
    }
}

impl Plan {
    /// The landing prepared for a switch taking effect at master `at`
    /// from a cam with constants `old`.
    pub(super) fn switch_landing(&self, old: &Steady, at: i64) -> Option<(usize, &Prepared)> {
        match self {
            Self::Switch {
                old: from,
                landings,
            } if from.same(old) => landings
                .iter()
                .enumerate()
                .find_map(|(i, l)| l.as_ref().filter(|(a, _)| *a == at).map(|(_, p)| (i, p))),
            _ => None,
        }
    }

    /// The landing prepared for the seam of cycle `from_k` crossed
    /// `forward` (or backwards) from a cam with constants `old`.
    pub(super) fn seam_landing(
        &self,
        old: &Steady,
        from_k: i128,
        forward: bool,
    ) -> Option<(usize, &Prepared)> {
        match self {
            Self::Seam {
                old: from,
                from_k: k,
                landings,
            } if *k == from_k && from.same(old) => {
                let i = usize::from(!forward);
                landings.get(i)?.as_ref().map(|p| (i, p))
            }
            _ => None,
        }
    }

    /// Landing `i` of the plan.
    pub(super) fn landing(&self, i: usize) -> Option<&Prepared> {
        match self {
            Self::Switch { landings, .. } => landings.get(i)?.as_ref().map(|(_, p)| p),
            Self::Seam { landings, .. } => landings.get(i)?.as_ref(),
        }
    }
}
