//! A rotary (modulo) slave: a knife or a turret whose position wraps at a
//! modulo (360° in pulses), beyond the documents (TwinCAT's modulo slave
//! with the start modes of its `MC_CamIn`).
//!
//! The axis keeps one accumulated position (an `i64` of pulses, never
//! wrapped, so nothing is lost over a year of turns) and reports the
//! position in the turn, `0..modulo`, beside it. A cam table for such an
//! axis holds positions in the turn; which turn the slave goes to is the
//! start mode's choice, made exactly in integers:
//!
//! | [`ModuloStart`] | at engage the slave goes to the table value … |
//! |---|---|
//! | `Absolute` | in the turn the slave is in now (it moves less than one turn, either way) |
//! | `Relative` | added to the slave's position (the table is relative to the start) |
//! | `EndlessPositive` | at or ahead of the slave: it only moves forwards |
//! | `EndlessNegative` | at or behind the slave: it only moves backwards |
//! | `Nearest` | in the turn nearest the slave: at most half a turn either way |
//!
//! A periodic table whose end and start differ makes the slave jump at the
//! seam; on a modulo axis a jump of whole turns is no motion at all, so the
//! endless and nearest modes drop the whole turns of that jump (the slave
//! goes on, forwards for `EndlessPositive`, backwards for
//! `EndlessNegative`, the shorter way for `Nearest`), while `Absolute` and
//! `Relative` keep the jump as the table has it.

use core::num::NonZeroU64;

use crate::CouplingError;

/// Largest modulo accepted: keeps every turn product far from overflow.
const MAX_MODULO: u64 = 1 << 62;

/// How a cam on a modulo slave picks the turn (TwinCAT `MC_CamIn` start
/// modes for a modulo slave).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ModuloStart {
    /// The table value in the slave's current turn.
    #[default]
    Absolute,
    /// The table value added to the slave's position at engage.
    Relative,
    /// The equivalent position at or ahead of the slave; seams run on forwards.
    EndlessPositive,
    /// The equivalent position at or behind the slave; seams run on backwards.
    EndlessNegative,
    /// The equivalent position nearest the slave; seams take the shorter way.
    Nearest,
}

/// A modulo slave: the modulo in pulses and the start mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ModuloAxis {
    modulo: NonZeroU64,
    start: ModuloStart,
}

/// Where a modulo slave stands.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ModuloPosition {
    /// The position in the turn, `0..modulo`.
    pub position: i64,
    /// Whole turns: accumulated = turns × modulo + position.
    pub turns: i64,
}

impl ModuloAxis {
    /// A slave wrapping every `modulo` pulses, engaging as `start` says.
    ///
    /// # Errors
    /// [`CouplingError::BadModulo`] for 0 or more than 2^62.
    pub const fn new(modulo: u64, start: ModuloStart) -> Result<Self, CouplingError> {
        match NonZeroU64::new(modulo) {
            Some(m) if modulo <= MAX_MODULO => Ok(Self { modulo: m, start }),
            _ => Err(CouplingError::BadModulo),
        }
    }

    /// The modulo in pulses.
    pub const fn modulo(&self) -> u64 {
        self.modulo.get()
    }

    /// The start mode.
    pub const fn start(&self) -> ModuloStart {
        self.start
    }

    /// The same axis with another start mode.
    #[must_use]
    pub const fn with_start(self, start: ModuloStart) -> Self {
        Self { start, ..self }
    }

    fn m(&self) -> i128 {
        i128::from(self.modulo.get())
    }

    /// The accumulated position as a place in the turn and whole turns.
    ///
    /// ```
    /// use ecam_engine::{ModuloAxis, ModuloStart};
    /// let knife = ModuloAxis::new(36_000, ModuloStart::Absolute)?;
    /// let p = knife.locate(-100);
    /// assert_eq!((p.position, p.turns), (35_900, -1));
    /// # Ok::<(), ecam_engine::CouplingError>(())
    /// ```
    pub fn locate(&self, accumulated: i64) -> ModuloPosition {
        let m = self.m();
        let a = i128::from(accumulated);
        ModuloPosition {
            // Both fit: |position| < modulo <= 2^62, |turns| <= |a|.
            position: a.rem_euclid(m) as i64,
            turns: a.div_euclid(m) as i64,
        }
    }

    /// The output offset of an engagement whose table value (after slave
    /// zoom) is `on_table`, with the slave at `slave_now` and the cam's
    /// `offset` (PLCopen `SlaveOffset`): the target is the table value
    /// plus the offset, moved by whole turns as the start mode says.
    pub(crate) fn engage_offset(&self, on_table: i128, slave_now: i128, offset: i128) -> i128 {
        let m = self.m();
        let target = on_table.saturating_add(offset);
        let at = match self.start {
            // The table is relative to where the slave stands.
            ModuloStart::Relative => return slave_now.saturating_add(offset),
            ModuloStart::Absolute => slave_now
                .div_euclid(m)
                .saturating_mul(m)
                .saturating_add(target.rem_euclid(m)),
            ModuloStart::EndlessPositive => {
                slave_now.saturating_add((target.saturating_sub(slave_now)).rem_euclid(m))
            }
            ModuloStart::EndlessNegative => {
                slave_now.saturating_sub((slave_now.saturating_sub(target)).rem_euclid(m))
            }
            ModuloStart::Nearest => slave_now.saturating_add(nearest(target - slave_now, m)),
        };
        at.saturating_sub(on_table)
    }

    /// Whole turns to add to a seam jump of `jump` pulses (the table's own
    /// step at the seam) so that the slave goes on as the start mode says.
    pub(crate) fn seam_turns(&self, jump: f64) -> i128 {
        let m = self.modulo.get() as f64;
        // The jump's place in one turn, 0 <= r < m (no_std: no rem_euclid).
        let r = jump - m * libm::floor(jump / m);
        let wanted = match self.start {
            ModuloStart::Absolute | ModuloStart::Relative => return 0,
            ModuloStart::EndlessPositive => r,
            ModuloStart::EndlessNegative => {
                if r > 0.0 {
                    r - m
                } else {
                    0.0
                }
            }
            ModuloStart::Nearest => match r {
                r if 2.0 * r > m => r - m,
                r => r,
            },
        };
        let turns = libm::round((wanted - jump) / m);
        if turns.is_finite() && turns.abs() < 9.0e18 {
            turns as i128
        } else {
            0
        }
    }
}

/// `d` moved by whole `m` into `[-m/2, m/2)` (ties go forwards).
fn nearest(d: i128, m: i128) -> i128 {
    let r = d.rem_euclid(m);
    if 2 * r > m { r - m } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(start: ModuloStart) -> ModuloAxis {
        ModuloAxis::new(360, start).unwrap()
    }

    #[test]
    fn each_start_mode_picks_its_turn() {
        // Slave at 3 turns + 300, table value 50.
        let s = 3 * 360 + 300;
        let at = |start| 50 + axis(start).engage_offset(50, s, 0);
        assert_eq!(at(ModuloStart::Absolute), 3 * 360 + 50);
        assert_eq!(at(ModuloStart::EndlessPositive), 4 * 360 + 50);
        assert_eq!(at(ModuloStart::EndlessNegative), 3 * 360 + 50);
        assert_eq!(at(ModuloStart::Nearest), 4 * 360 + 50);
        assert_eq!(at(ModuloStart::Relative), s + 50);
        // Already there: no motion for any mode but relative.
        let here = |start| 300 + axis(start).engage_offset(300, s, 0);
        for start in [
            ModuloStart::Absolute,
            ModuloStart::EndlessPositive,
            ModuloStart::EndlessNegative,
            ModuloStart::Nearest,
        ] {
            assert_eq!(here(start), s, "{start:?}");
        }
        // Negative positions wrap the same way.
        assert_eq!(
            50 + axis(ModuloStart::EndlessNegative).engage_offset(50, -10, 0),
            -310
        );
        assert_eq!(
            770 + axis(ModuloStart::Absolute).engage_offset(770, -10, 5),
            -360 + 55
        );
    }

    #[test]
    fn seams_drop_whole_turns_the_way_the_mode_says() {
        // A knife table 0..360 periodic: the seam jumps back one turn.
        assert_eq!(axis(ModuloStart::EndlessPositive).seam_turns(-360.0), 1);
        assert_eq!(axis(ModuloStart::Nearest).seam_turns(-360.0), 1);
        assert_eq!(axis(ModuloStart::EndlessNegative).seam_turns(-360.0), 1);
        assert_eq!(axis(ModuloStart::Absolute).seam_turns(-360.0), 0);
        // A jump of 300 back: forwards 60, or back 300, or the shorter 60.
        assert_eq!(axis(ModuloStart::EndlessPositive).seam_turns(-300.0), 1);
        assert_eq!(axis(ModuloStart::EndlessNegative).seam_turns(-300.0), 0);
        assert_eq!(axis(ModuloStart::Nearest).seam_turns(-300.0), 1);
        assert_eq!(axis(ModuloStart::Nearest).seam_turns(100.0), 0);
    }

    #[test]
    fn locate_and_bad_modulo() {
        let a = axis(ModuloStart::Absolute);
        assert_eq!(
            a.locate(725),
            ModuloPosition {
                position: 5,
                turns: 2
            }
        );
        assert_eq!(
            ModuloAxis::new(0, ModuloStart::Absolute),
            Err(CouplingError::BadModulo)
        );
        assert!(ModuloAxis::new(1 << 63, ModuloStart::Absolute).is_err());
    }
}
