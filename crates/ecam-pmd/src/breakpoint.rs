//! Breakpoints and event actions: how document 002 starts and stops cams.
//!
//! The breakpoint word of `SetBreakpoint` packs three fields. Document 002
//! shows two words, `0x191` ("activate cam when actual position of axis 2
//! ≥ 1000") and `0x131` ("disable cam when actual position of axis 2 ≥ 1600
//! … smooth stop"); the layout that makes both comments true is
//!
//! | bits  | field        | codes |
//! |-------|--------------|-------|
//! | 3:0   | source axis  | numbered from 0 (the comments' "axis 2" is code 1) |
//! | 7:4   | action       | 0 none, 1 Update, 2 abrupt stop, 3 smooth stop, 9 StartCam |
//! | 15:8  | trigger      | 0 disabled, 1 ≥ actual, 2 ≤ actual, 3 ≥ commanded, 4 ≤ commanded, 5 commanded crossed, 6 actual crossed, 7 time ≥ value |
//!
//! The action codes are the PMD C-Motion ones. PMD's own headers number
//! the position triggers the other way round (1/2 commanded, 3/4 actual);
//! we follow the document's comments, which only work with 1 = ≥ actual.

use crate::PmdError;

/// What a breakpoint compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Trigger {
    /// 1: actual position of the source axis ≥ the breakpoint value.
    ActualAtLeast,
    /// 2: actual position ≤ value.
    ActualAtMost,
    /// 3: commanded position ≥ value.
    CommandedAtLeast,
    /// 4: commanded position ≤ value.
    CommandedAtMost,
    /// 5: commanded position crosses the value (either direction) after the breakpoint is set.
    CommandedCrossed,
    /// 6: actual position crosses the value.
    ActualCrossed,
    /// 7: the processor's time (cycles) ≥ value.
    Time,
}

/// What happens when a breakpoint or event fires.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// 0: nothing besides the event bit.
    None,
    /// 1: `Update` the axis (profile mode, stop mode).
    Update,
    /// 2: abrupt stop: a cam or a simulated move holds its position at once.
    AbruptStop,
    /// 3: smooth stop: a cam stops at the next end of its table, either
    /// direction; a simulated move (no deceleration) at once.
    SmoothStop,
    /// 9: `StartCam` (document 002).
    StartCam,
}

impl Action {
    /// Decodes an action code.
    ///
    /// # Errors
    /// [`PmdError::NotSimulated`] for the motor and loop actions 4–8,
    /// [`PmdError::OutOfRange`] for codes with no meaning.
    pub fn decode(code: i64) -> Result<Self, PmdError> {
        match code {
            0 => Ok(Self::None),
            1 => Ok(Self::Update),
            2 => Ok(Self::AbruptStop),
            3 => Ok(Self::SmoothStop),
            9 => Ok(Self::StartCam),
            4..=8 => Err(PmdError::NotSimulated {
                what: "action",
                code,
            }),
            _ => Err(PmdError::OutOfRange {
                what: "action",
                value: code,
                allowed: "0 none, 1 Update, 2 abrupt stop, 3 smooth stop or 9 StartCam",
            }),
        }
    }
}

/// A decoded, enabled breakpoint word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BreakpointWord {
    /// Axis whose position is watched (from 0).
    pub source_axis: u8,
    /// What happens when it fires.
    pub action: Action,
    /// What is compared.
    pub trigger: Trigger,
}

impl BreakpointWord {
    /// Decodes `word` for a processor with `axis_count` axes; `Ok(None)`
    /// means trigger 0 (breakpoint disabled).
    ///
    /// # Errors
    /// [`PmdError::OutOfRange`] for bits above 15, an unknown source axis,
    /// action or trigger; [`PmdError::NotSimulated`] for status triggers 8–11
    /// and the motor actions.
    pub fn decode(word: i64, axis_count: u8) -> Result<Option<Self>, PmdError> {
        let bad = |allowed| PmdError::OutOfRange {
            what: "breakpoint word",
            value: word,
            allowed,
        };
        let word = u16::try_from(word)
            .map_err(|_| bad("16 bits: 3:0 source axis, 7:4 action, 15:8 trigger"))?;
        let source_axis = (word & 0xF) as u8;
        let action = Action::decode(i64::from((word >> 4) & 0xF))?;
        let trigger = match word >> 8 {
            0 => return Ok(None),
            1 => Trigger::ActualAtLeast,
            2 => Trigger::ActualAtMost,
            3 => Trigger::CommandedAtLeast,
            4 => Trigger::CommandedAtMost,
            5 => Trigger::CommandedCrossed,
            6 => Trigger::ActualCrossed,
            7 => Trigger::Time,
            code @ 8..=11 => {
                return Err(PmdError::NotSimulated {
                    what: "status trigger",
                    code: i64::from(code),
                });
            }
            _ => return Err(bad("trigger (bits 15:8) must be 0 to 7")),
        };
        if source_axis >= axis_count {
            return Err(bad("source axis (bits 3:0) past the last axis"));
        }
        Ok(Some(Self {
            source_axis,
            action,
            trigger,
        }))
    }
}

/// One of an axis' two breakpoints.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Breakpoint {
    /// `SetBreakpointValue`.
    pub value: i64,
    /// The armed word, `None` when disabled (it disarms itself when it fires).
    pub word: Option<BreakpointWord>,
    /// For the "crossed" triggers: whether the watched position was below
    /// the value when the breakpoint was set.
    pub was_below: bool,
}

impl Breakpoint {
    /// Whether it fires for the given source positions and time.
    pub fn fires(&self, actual: i64, commanded: i64, time: i64) -> bool {
        let Some(word) = self.word else { return false };
        let v = self.value;
        match word.trigger {
            Trigger::ActualAtLeast => actual >= v,
            Trigger::ActualAtMost => actual <= v,
            Trigger::CommandedAtLeast => commanded >= v,
            Trigger::CommandedAtMost => commanded <= v,
            Trigger::CommandedCrossed => (commanded < v) != self.was_below,
            Trigger::ActualCrossed => (actual < v) != self.was_below,
            Trigger::Time => time >= v,
        }
    }
}

/// Events `SetEventAction` can attach an action to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// 0: immediate — the action runs when the command is given.
    Immediate,
}

impl Event {
    /// Decodes an event code.
    ///
    /// # Errors
    /// [`PmdError::NotSimulated`] for limit, motion-error and foldback
    /// events (1–4), [`PmdError::OutOfRange`] beyond.
    pub fn decode(code: i64) -> Result<Self, PmdError> {
        match code {
            0 => Ok(Self::Immediate),
            1..=4 => Err(PmdError::NotSimulated {
                what: "event",
                code,
            }),
            _ => Err(PmdError::OutOfRange {
                what: "event",
                value: code,
                allowed: "0 immediate",
            }),
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn document_words_mean_what_their_comments_say() {
        let start = BreakpointWord::decode(0x191, 4).unwrap().unwrap();
        assert_eq!(
            start,
            BreakpointWord {
                source_axis: 1,
                action: Action::StartCam,
                trigger: Trigger::ActualAtLeast
            }
        );
        let stop = BreakpointWord::decode(0x131, 4).unwrap().unwrap();
        assert_eq!(stop.action, Action::SmoothStop);
        assert_eq!(stop.trigger, Trigger::ActualAtLeast);
        assert_eq!(stop.source_axis, 1);
    }

    #[test]
    fn disabled_and_bad_words() {
        assert_eq!(BreakpointWord::decode(0x091, 4).unwrap(), None);
        assert!(BreakpointWord::decode(0x195, 4).is_err());
        assert!(BreakpointWord::decode(0x1A1, 4).is_err());
        assert!(BreakpointWord::decode(0x1491, 4).is_err());
        assert!(BreakpointWord::decode(0x10000, 4).is_err());
        assert!(matches!(
            BreakpointWord::decode(0x841, 4),
            Err(PmdError::NotSimulated { .. })
        ));
    }

    #[test]
    fn crossing_fires_in_either_direction() {
        let word = BreakpointWord::decode(0x601, 4).unwrap();
        let bp = Breakpoint {
            value: 100,
            word,
            was_below: true,
        };
        assert!(!bp.fires(99, 0, 0));
        assert!(bp.fires(100, 0, 0));
        let bp = Breakpoint {
            was_below: false,
            ..bp
        };
        assert!(!bp.fires(100, 0, 0));
        assert!(bp.fires(99, 0, 0));
    }
}
