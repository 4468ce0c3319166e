//! A move at constant velocity in whole counts over a number of control
//! cycles: the `MoveTo` of the motion-processor face (an axis driven to a
//! target, document 002's simulated move) and of the motion-controller
//! face (a master driven to a target), and the master moves of `ecam
//! simulate` scenarios (by time: [`LinearMove::position_after`]).
//!
//! After cycle `k` of `n` the position is `from + (to − from) × k / n`,
//! the integer division rounding towards `from`: the move never passes
//! the straight line, never turns back, and ends exactly on `to`.

use core::num::{NonZeroU32, NonZeroU64};

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
        Self::position_after(
            self.from,
            self.to,
            u64::from(self.done),
            NonZeroU64::from(self.cycles),
        )
    }

    /// The position `elapsed` units (cycles, microseconds) into a move
    /// from `from` to `to` that takes `span` of them: `from + (to − from)
    /// × elapsed / span`, truncated toward `from`; the target from `span`
    /// on. This is the move itself, for callers that know the time rather
    /// than step (the simulator's master).
    ///
    /// One 64-bit multiply and division when the product fits (every
    /// realistic move), the exact 128-bit route otherwise with the same
    /// result; a product beyond even 128 bits (a span near 2^64 units over
    /// the whole `i64` range) gives the target.
    #[inline]
    pub fn position_after(from: i64, to: i64, elapsed: u64, span: NonZeroU64) -> i64 {
        if elapsed >= span.get() {
            return to;
        }
        let narrow = (
            to.checked_sub(from),
            i64::try_from(elapsed),
            i64::try_from(span.get()),
        );
        if let (Some(delta), Ok(elapsed), Ok(span)) = narrow
            && let Some(step) = delta.checked_mul(elapsed).map(|p| p / span)
            && let Some(position) = from.checked_add(step)
        {
            return position;
        }
        let delta = i128::from(to) - i128::from(from);
        delta
            .checked_mul(i128::from(elapsed))
            .and_then(|p| i64::try_from(i128::from(from) + p / i128::from(span.get())).ok())
            .unwrap_or(to)
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

    #[test]
    fn a_move_is_the_same_in_64_and_128_bits() {
        let along = |from, to, elapsed, span| {
            LinearMove::position_after(from, to, elapsed, NonZeroU64::new(span).unwrap())
        };
        let wide = |from: i64, to: i64, elapsed: u64, span: u64| {
            let delta = i128::from(to) - i128::from(from);
            i64::try_from(i128::from(from) + delta * i128::from(elapsed) / i128::from(span))
                .unwrap_or(to)
        };
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for _ in 0..20_000 {
            let scale = next() % 64;
            let from = (next() as i64) >> scale;
            let to = (next() as i64) >> (next() % 64);
            let span = (next() >> (next() % 64)).max(1);
            let elapsed = next() % span;
            // Keep the reference itself inside i128.
            if (i128::from(to) - i128::from(from)).unsigned_abs() < 1 << 64 {
                assert_eq!(
                    along(from, to, elapsed, span),
                    wide(from, to, elapsed, span)
                );
            }
        }
        assert_eq!(along(-5, 5, 1, 3), -2, "truncates toward the start");
        assert_eq!(along(-5, 5, 3, 3), 5, "the target at the end");
        assert_eq!(along(-5, 5, 4, 3), 5, "and after it");
        // A product beyond even 128 bits: the move's target (one count off).
        assert_eq!(along(i64::MIN, i64::MAX, u64::MAX - 1, u64::MAX), i64::MAX);
    }
}
