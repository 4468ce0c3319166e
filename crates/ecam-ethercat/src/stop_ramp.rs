//! How a line stops: from the velocity it had when the stop began to rest
//! over the stop time, the velocity falling linearly, in whole counts. The
//! cam line's virtual master (`line.rs`) and each drive following a pulse
//! output (`follow.rs`) stop this way.

/// A deceleration to rest over a number of cycles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct StopRamp {
    from: i64,
    /// Counts per cycle when the stop began.
    speed: i64,
    cycles: u32,
    /// Cycles stepped (`step`).
    done: u32,
}

impl StopRamp {
    /// A stop from `from` at `speed` counts per cycle, at rest after
    /// `cycles` cycles (at once for 0).
    pub(crate) const fn new(from: i64, speed: i64, cycles: u32) -> Self {
        Self {
            from,
            speed,
            cycles,
            done: 0,
        }
    }

    /// The position after `k` cycles: exact integers (the travel
    /// `speed × (k n − k (k + 1) / 2) / n` rounded down), monotonic, and
    /// at rest from cycle `n` on; saturating at the ends of `i64`.
    pub(crate) fn position(&self, k: u32) -> i64 {
        let n = i128::from(self.cycles.max(1));
        let k = i128::from(k.min(self.cycles));
        let travelled = i128::from(self.speed) * (k * n - k * (k + 1) / 2);
        let travelled = travelled.div_euclid(n);
        self.from
            .saturating_add(i64::try_from(travelled).unwrap_or(if travelled < 0 {
                i64::MIN
            } else {
                i64::MAX
            }))
    }

    /// Advances one cycle and gives the position then.
    pub(crate) fn step(&mut self) -> i64 {
        self.done = self.done.saturating_add(1).min(self.cycles);
        self.position(self.done)
    }

    /// Every cycle of the ramp has been stepped.
    pub(crate) fn over(&self) -> bool {
        self.done >= self.cycles
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stop_ramp_is_exact_and_reaches_rest() {
        let ramp = StopRamp::new(100, 7, 10);
        let positions: Vec<i64> = (0..=12).map(|k| ramp.position(k)).collect();
        assert!(positions.windows(2).all(|w| w[1] >= w[0]), "{positions:?}");
        // 7 · (10·10 − 55) / 10 = 31.5 → 31 counts of braking distance.
        assert_eq!(positions[10], 131);
        assert_eq!(positions[12], 131, "at rest after the ramp");
        // The first step is nearly the running speed.
        assert_eq!(positions[1] - positions[0], 6);
        let back = StopRamp::new(100, -7, 10);
        assert_eq!(back.position(10), 100 - 32);
    }

    #[test]
    fn stepping_walks_the_ramp_and_ends() {
        let mut ramp = StopRamp::new(0, 5, 3);
        let steps = [ramp.step(), ramp.step(), ramp.step()];
        assert_eq!(
            steps,
            [ramp.position(1), ramp.position(2), ramp.position(3)]
        );
        assert!(ramp.over());
        assert!(StopRamp::new(0, 5, 0).over());
    }

    #[test]
    fn an_overlong_travel_saturates_instead_of_turning_back() {
        let ramp = StopRamp::new(i64::MAX - 10, i64::MAX, 4);
        assert_eq!(ramp.position(4), i64::MAX);
    }
}
