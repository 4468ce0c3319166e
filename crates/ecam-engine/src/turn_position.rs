//! Activation positions on a single-turn master (document 001
//! `SetSingleTurn`): a start or switch position is a place in the turn, so
//! it comes round once per turn. The engine follows the unwrapped master,
//! so each check asks for the unwrapped position of that place nearest
//! the master's last position in the direction it moves; a pass across
//! the wrap point then counts like any other pass, forwards or backwards.

use core::num::NonZeroU64;

/// The unwrapped position of activation `position` to check a move from
/// `from` against: `position` itself without a turn; with one, the first
/// position at or after `from` (`forward`) or at or before it (backwards)
/// that lies at `position` modulo the turn.
pub(crate) fn nearest(position: i64, turn: Option<NonZeroU64>, from: i64, forward: bool) -> i64 {
    let Some(turn) = turn.and_then(|t| i64::try_from(t.get()).ok()) else {
        return position;
    };
    let place = position.rem_euclid(turn);
    let from_place = from.rem_euclid(turn);
    if forward {
        from.saturating_add((place - from_place).rem_euclid(turn))
    } else {
        from.saturating_sub((from_place - place).rem_euclid(turn))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_place_comes_round_once_per_turn() {
        let turn = NonZeroU64::new(360);
        assert_eq!(nearest(10, None, 1000, true), 10);
        assert_eq!(nearest(10, turn, 350, true), 370);
        assert_eq!(nearest(10, turn, 370, true), 370);
        assert_eq!(nearest(10, turn, 371, true), 730);
        assert_eq!(nearest(10, turn, 371, false), 370);
        assert_eq!(nearest(10, turn, 5, false), -350);
        assert_eq!(nearest(-350, turn, 0, true), 10);
    }
}
