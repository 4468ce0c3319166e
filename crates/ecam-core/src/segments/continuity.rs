//! Continuity at every point where two segments meet.

use alloc::vec::Vec;

use super::cam::SegmentCam;
use crate::CamCurve;
use crate::table::Continuity;

/// How one point joins the segment arriving to the one leaving.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Joint {
    /// The point (the seam is the last point, joined to point 0 of the next cycle).
    pub point: usize,
    /// Its master position (counts).
    pub master: i64,
    /// True for the seam: the last point joined to the first of the next
    /// cycle, the stroke carried over (a repeat/incremental cam).
    pub seam: bool,
    /// `C0` velocity jumps, `C1` acceleration jumps, `C2` jerk jumps,
    /// `C3` none does (position always meets: the segments share the point).
    pub class: Continuity,
    /// Leaving minus arriving velocity, pulses/count.
    pub velocity_jump: f64,
    /// Leaving minus arriving acceleration, pulses/count².
    pub acceleration_jump: f64,
    /// Leaving minus arriving jerk, pulses/count³.
    pub jerk_jump: f64,
}

/// The continuity of a whole segment cam.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ContinuityReport {
    /// Every point between two segments, in master order, then the seam.
    pub joints: Vec<Joint>,
    /// The weakest point between two segments (`C3` for a single segment).
    pub cam: Continuity,
    /// The seam's class.
    pub seam: Continuity,
}

/// A jump counts when it exceeds this fraction of the larger side or of the
/// cam's own peak of that derivative (the laws meet at a point to ~1e-12).
const JUMP_TOLERANCE: f64 = 1e-7;

impl SegmentCam {
    /// Continuity at every point between two segments, and at the seam.
    pub fn continuity(&self) -> ContinuityReport {
        report(self)
    }
}

fn report(cam: &SegmentCam) -> ContinuityReport {
    let n = cam.segment_count();
    let peaks = cam.peaks();
    let scale = |f: fn(&super::SegmentPeaks) -> f64| {
        peaks
            .iter()
            .map(f)
            .filter(|p| p.is_finite())
            .fold(0.0, f64::max)
    };
    let scales = (
        scale(|p| p.peak_velocity),
        scale(|p| p.peak_acceleration),
        scale(|p| p.peak_jerk),
    );
    let joint = |point: usize, left: usize, right: usize, seam: bool| {
        let (l, r) = (cam.segment_at(left, 1.0), cam.segment_at(right, 0.0));
        let jumps = (r.v - l.v, r.a - l.a, r.j - l.j);
        let counts = |jump: f64, a: f64, b: f64, peak: f64| {
            jump.abs() > JUMP_TOLERANCE * a.abs().max(b.abs()).max(peak)
        };
        let class = if counts(jumps.0, l.v, r.v, scales.0) {
            Continuity::C0
        } else if counts(jumps.1, l.a, r.a, scales.1) {
            Continuity::C1
        } else if counts(jumps.2, l.j, r.j, scales.2) {
            Continuity::C2
        } else {
            Continuity::C3
        };
        Joint {
            point,
            master: cam.segments()[left].master,
            seam,
            class,
            velocity_jump: jumps.0,
            acceleration_jump: jumps.1,
            jerk_jump: jumps.2,
        }
    };
    let mut joints: Vec<Joint> = (1..n).map(|p| joint(p, p - 1, p, false)).collect();
    let seam = joint(n, n - 1, 0, true);
    let weakest = joints
        .iter()
        .map(|j| j.class)
        .min()
        .unwrap_or(Continuity::C3);
    joints.push(seam);
    ContinuityReport {
        joints,
        cam: weakest,
        seam: seam.class,
    }
}
