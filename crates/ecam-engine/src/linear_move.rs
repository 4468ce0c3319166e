//! A move at constant velocity in whole counts over a number of control
//! cycles: the `MoveTo` of the motion-processor face (an axis driven to a
//! target, document 002's simulated move) and of the motion-controller
//! face (a master driven to a target).
//!
//! After cycle `k` of `n` the position is `from + (to − from) × k / n`,
//! the integer division rounding towards `from`: the move never passes
//! the straight line, never turns back, and ends exactly on `to`.

use core::num::NonZeroU32;

/// A constant-velocity move from one position to another.
///
/// ```
/// use core::num::NonZeroU32;
/// use ecam_engine::LinearMove;
///
/// let mut m = LinearMove::new(0, 10, NonZeroU32::new(3).unwrap());
/// assert_eq!([m.step(), m.step(), m.step()], [3, 6, 10]);
/// assert!(m.finished());
/// assert_eq!(m.step(), 10); // it stays there
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LinearMove {
    from: i64,
    to: i64,
    cycles: NonZeroU32,
    done: u32,
}

impl LinearMove {
    /// A move from `from` to `to` over `cycles` control cycles.
    pub const fn new(from: i64, to: i64, cycles: NonZeroU32) -> Self {
        Self {
            from,
            to,
            cycles,
            done: 0,
        }
    }

    /// Advances one cycle and gives the new position (exactly the target
    /// at the end, and there after it).
    pub fn step(&mut self) -> i64 {
        self.done = self.done.saturating_add(1).min(self.cycles.get());
        // i128: a span below 2^65 times at most 2^32 cycles cannot overflow.
        let span = i128::from(self.to) - i128::from(self.from);
        let position =
            i128::from(self.from) + span * i128::from(self.done) / i128::from(self.cycles.get());
        i64::try_from(position).unwrap_or(self.to)
    }

    /// The move has arrived.
    pub fn finished(&self) -> bool {
        self.done >= self.cycles.get()
    }

    /// Where the move goes.
    pub fn target(&self) -> i64 {
        self.to
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrives_exactly_over_the_extremes() {
        let three = NonZeroU32::new(3).unwrap();
        let mut m = LinearMove::new(i64::MIN, i64::MAX, three);
        m.step();
        assert!(!m.finished());
        m.step();
        assert_eq!(m.step(), i64::MAX);
        assert!(m.finished());
        assert_eq!(m.step(), i64::MAX);
        let mut m = LinearMove::new(0, 100, NonZeroU32::new(4).unwrap());
        assert_eq!(m.step(), 25);
    }

    #[test]
    fn rounds_towards_the_start_either_way() {
        let three = NonZeroU32::new(3).unwrap();
        let mut up = LinearMove::new(0, 10, three);
        assert_eq!([up.step(), up.step(), up.step()], [3, 6, 10]);
        let mut down = LinearMove::new(0, -10, three);
        assert_eq!([down.step(), down.step(), down.step()], [-3, -6, -10]);
    }
}
