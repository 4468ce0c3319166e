//! The cam's motion over one cycle, as the drive check reads it.

use alloc::vec::Vec;

use crate::Kinematics;
use crate::table::steps::{acceleration_step_counts, velocity_step_counts};

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

impl Motion {
    /// The motion these samples describe (sorted by master; NaN masters
    /// dropped). Whether a step counts follows the one rule of
    /// [`table::steps`](crate::table::steps): it moves the slave by half a
    /// pulse over the longer stretch beside its corner (here, the distance
    /// to the neighbouring corner or the cycle's end).
    pub fn from_samples(mut samples: Vec<(f64, Kinematics)>) -> Self {
        samples.retain(|(m, _)| m.is_finite());
        samples.sort_by(|a, b| a.0.total_cmp(&b.0));
        let corners: Vec<usize> = samples
            .windows(2)
            .enumerate()
            .filter(|(_, w)| w[0].0 == w[1].0)
            .map(|(i, _)| i)
            .collect();
        let (first, last) = match (samples.first(), samples.last()) {
            (Some(a), Some(b)) => (a.0, b.0),
            _ => (0.0, 0.0),
        };
        let mut velocity_steps = Vec::new();
        let mut acceleration_steps = Vec::new();
        for (j, &i) in corners.iter().enumerate() {
            let ((m, before), (_, after)) = (samples[i], samples[i + 1]);
            let previous = j
                .checked_sub(1)
                .and_then(|k| corners.get(k))
                .map_or(first, |&k| samples[k].0);
            let next = corners.get(j + 1).map_or(last, |&k| samples[k].0);
            let reach = (m - previous).max(next - m);
            if velocity_step_counts(after.v - before.v, reach) {
                velocity_steps.push(m);
            }
            if acceleration_step_counts(after.a - before.a, reach) {
                acceleration_steps.push(m);
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

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    fn k(v: f64, a: f64) -> Kinematics {
        Kinematics {
            s: 0.0,
            v,
            a,
            j: 0.0,
        }
    }

    #[test]
    fn steps_count_by_the_tables_rule_not_by_a_share_of_the_peak() {
        // Two segments meeting at 600 of a 1200-count cycle: a difference
        // of floating-point noise is no step (a share of the peak counted
        // it, and the drive check reported an infinite torque for a C2
        // cam); a real step of velocity and one of acceleration are.
        let noise = Motion::from_samples(vec![
            (0.0, k(0.0, 0.0)),
            (600.0, k(1.5, 0.0)),
            (600.0, k(1.5 + 1e-6, 1e-9)),
            (1200.0, k(0.0, 0.0)),
        ]);
        assert!(noise.velocity_steps().is_empty());
        assert!(noise.acceleration_steps.is_empty());
        let real = Motion::from_samples(vec![
            (0.0, k(0.0, 0.0)),
            (600.0, k(1.5, 0.0)),
            (600.0, k(1.0, 0.01)),
            (1200.0, k(0.0, 0.0)),
        ]);
        assert_eq!(real.velocity_steps(), [600.0]);
        assert_eq!(real.acceleration_steps, [600.0]);
    }
}
