//! `MoveTo`: an axis driven linearly to a target over a number of cycles
//! (the motion processor face's simulated move, here for the master).

/// A constant-velocity move, in unwrapped counts: on a single-turn axis the
/// controller wraps each position it is given, so a move may cross turns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct LinearMove {
    from: i64,
    to: i64,
    cycles: u32,
    done: u32,
}

impl LinearMove {
    /// A move from `from` to `to` over `cycles` (at least 1) cycles.
    pub(crate) fn new(from: i64, to: i64, cycles: u32) -> Self {
        Self {
            from,
            to,
            cycles: cycles.max(1),
            done: 0,
        }
    }

    /// Advances one cycle: the new position (exactly `to` at the end) and
    /// whether the move has arrived.
    pub(crate) fn step(&mut self) -> (i64, bool) {
        self.done = self.done.saturating_add(1).min(self.cycles);
        // i128: a span of up to 2^65 times at most 2^32 cycles cannot overflow.
        let span = i128::from(self.to) - i128::from(self.from);
        let position =
            i128::from(self.from) + span * i128::from(self.done) / i128::from(self.cycles);
        (
            i64::try_from(position).unwrap_or(self.to),
            self.done >= self.cycles,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrives_exactly_over_the_extremes() {
        let mut m = LinearMove::new(i64::MIN, i64::MAX, 3);
        let (_, done) = m.step();
        assert!(!done);
        m.step();
        assert_eq!(m.step(), (i64::MAX, true));
        assert_eq!(m.step(), (i64::MAX, true));
        let mut m = LinearMove::new(0, 100, 4);
        assert_eq!(m.step(), (25, false));
    }
}
