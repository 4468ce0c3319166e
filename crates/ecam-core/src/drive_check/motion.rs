//! The cam's motion over one cycle, as the drive check reads it.

use alloc::vec::Vec;

use crate::Kinematics;

/// Samples `(master, kinematics)` of one cycle in master order, the
/// derivatives per count. Two samples at one master are the two sides of a
/// point where the cam steps (a segment cam's samples,
/// [`SegmentCam::sample_segments`](crate::segments::SegmentCam::sample_segments)):
/// a velocity step there is an impulse of acceleration (and of torque), an
/// acceleration step an impulse of jerk.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    pub(crate) samples: Vec<(f64, Kinematics)>,
    /// Masters where the velocity steps.
    pub(crate) velocity_steps: Vec<f64>,
    /// Masters where the acceleration steps.
    pub(crate) acceleration_steps: Vec<f64>,
}

/// A step counts when it exceeds this share of the motion's own peak.
const STEP_TOLERANCE: f64 = 1e-7;

impl Motion {
    /// The motion these samples describe (sorted by master; NaN masters dropped).
    pub fn from_samples(mut samples: Vec<(f64, Kinematics)>) -> Self {
        samples.retain(|(m, _)| m.is_finite());
        samples.sort_by(|a, b| a.0.total_cmp(&b.0));
        let peak = |f: fn(&Kinematics) -> f64| {
            samples
                .iter()
                .map(|(_, k)| f(k).abs())
                .filter(|x| x.is_finite())
                .fold(0.0, f64::max)
        };
        let (pv, pa) = (peak(|k| k.v), peak(|k| k.a));
        let mut velocity_steps = Vec::new();
        let mut acceleration_steps = Vec::new();
        for w in samples.windows(2) {
            let ((m0, k0), (m1, k1)) = (w[0], w[1]);
            if m0 != m1 {
                continue;
            }
            if (k1.v - k0.v).abs() > STEP_TOLERANCE * pv {
                velocity_steps.push(m0);
            } else if (k1.a - k0.a).abs() > STEP_TOLERANCE * pa {
                acceleration_steps.push(m0);
            }
        }
        Self {
            samples,
            velocity_steps,
            acceleration_steps,
        }
    }

    /// Master span of the samples (one cycle), counts.
    pub fn span(&self) -> f64 {
        match (self.samples.first(), self.samples.last()) {
            (Some(a), Some(b)) => b.0 - a.0,
            _ => 0.0,
        }
    }

    /// Where the velocity steps (impulses of torque).
    pub fn velocity_steps(&self) -> &[f64] {
        &self.velocity_steps
    }
}
