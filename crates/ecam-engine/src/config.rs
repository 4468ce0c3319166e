//! How an axis couples to its master: the settings chosen before engaging.
//!
//! One enum per decision (coupling, start, master alignment, slave
//! alignment), so a configuration cannot name two modes at once.

use core::num::NonZeroU64;

use crate::{MasterFilter, SyncWindow, Zoom};

/// The ceiling and default of the pulse output frequency (document 003,
/// register 6/7: "if frequency > 200K or < 0, the value is 200K").
pub const MAX_FREQUENCY_HZ: u32 = 200_000;

/// How the table repeats (or not) as the master moves on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coupling {
    /// The table repeats every cycle and the slave takes the table value of
    /// the master's place in the cycle: if the first and last slave values
    /// differ, the slave jumps at the seam (document 001 Periodic type). The
    /// jump is output as pulses under the frequency limit.
    Periodic,
    /// The table repeats and the slave offset accumulates the stroke
    /// (`slave_last − slave_first`) each cycle, forwards and backwards, so
    /// the slave is continuous at the seam (document 001 Repeat type,
    /// document 002 incremental cam).
    Repeat {
        /// Document 001: first and last less than one user unit apart are
        /// not joined. A stroke whose magnitude is below `min_stroke` pulses
        /// behaves as [`Coupling::Periodic`]; 0 and 1 join any nonzero stroke.
        min_stroke: u64,
    },
    /// Document 003 noncyclic cam: after engaging, the slave follows for
    /// `repeats + 1` cycles of master travel and then finishes, holding the
    /// end position. Seams inside are continuous (the stroke accumulates as
    /// in [`Coupling::Repeat`]). `0xFFFF` never finishes.
    OneShot {
        /// Register 14: 0 runs once, n runs n + 1 cycles, 0xFFFF forever.
        repeats: u16,
    },
    /// Document 001 Normal type: no repetition; outside the table the slave
    /// holds the nearer end value.
    Normal,
}

/// Which way a breakpoint compares the watched position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compare {
    /// Fires when the watched position is greater than or equal to the value.
    AtLeast,
    /// Fires when the watched position is less than or equal to the value.
    AtMost,
}

/// When an armed axis engages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StartMode {
    /// On the first tick after [`crate::CamAxis::arm`].
    Immediate,
    /// On a rising edge of [`crate::TickInput::start_input`] (document 003
    /// function register bit 5, the DECAM S3 start signal).
    OnRisingEdge,
    /// After the master has travelled `counts` (document 003 registers
    /// 15/16, function bit 0). Travel is summed as |change| per tick; the
    /// cam engages at the exact count, not at the tick that passes it.
    AfterDelay {
        /// Master counts (before zoom) to wait.
        counts: u64,
        /// Start counting at a rising edge of the start input (the
        /// document's behaviour) instead of at `arm()`.
        after_edge: bool,
    },
    /// When the master (unwrapped, before zoom) reaches or crosses
    /// `position` (document 003 registers 17/18, function bit 1). The cam
    /// engages exactly at `position`.
    AtMasterPosition {
        /// Master position in counts.
        position: i64,
        /// Wait for a rising edge of the start input first.
        after_edge: bool,
    },
    /// When [`crate::TickInput::watch`] (any axis' position) compares true
    /// against `value` (document 002 breakpoints with the StartCam action).
    Breakpoint {
        /// The comparison.
        compare: Compare,
        /// The threshold.
        value: i64,
    },
}

/// Which table input the master maps to at the engage instant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MasterAlign {
    /// Table input = master × zoom (then taken modulo the cycle).
    Absolute,
    /// Table input = master × zoom + offset (PLCopen `MasterOffset`).
    Offset(i64),
    /// Table input = this value at engage, then follows the master:
    /// document 002 `CamStartCount`, PLCopen relative master.
    StartAt(i64),
    /// Document 003 function bit 6: registers 27/28 hold the master position
    /// before zoom to start from; table input = value × zoom.
    StartAtUnzoomed(i64),
}

/// Where the slave output stands relative to the table at the engage instant.
///
/// Whatever the choice, a repeating cam counts its cycles (and the strokes
/// it accumulates) from the cycle the master is in when it engages, never
/// from the table's origin: the start rule of docs/engine.md.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlaveAlign {
    /// Commanded = the table value of the master's place in its cycle. On a
    /// cam with a stroke (repeat, one-shot) the start rule adds the whole
    /// strokes that put it nearest the slave: for a table that never turns
    /// back, at or ahead of the slave in the direction the cam moves it
    /// with the master going forward (less than one stroke of travel, no
    /// reverse pulse); for one that turns back, either way (document 001).
    /// Without a stroke it is the table value itself and may jump at
    /// engage; the pulses then catch up under the frequency limit
    /// (flagged as delayed).
    Absolute,
    /// Commanded = table value + offset (PLCopen `SlaveOffset`).
    Offset(i64),
    /// Bumpless: the output offset is the current slave position minus the
    /// table value (document 002 `CamOutputOffset`, PLCopen relative slave).
    Relative,
    /// Document 001, Repeat type on a single-turn master: the table value
    /// plus the whole strokes that land nearest the current slave position.
    /// Since the start rule covers every repeating cam this is the same as
    /// [`SlaveAlign::Absolute`]; the name is kept for configurations (and
    /// scenario files) that use it.
    NearestEquivalent,
    /// The commanded position is set to this value at engage (document 003
    /// function bit 6, registers 19/20).
    At(i64),
    /// A rotary (modulo) slave, beyond the documents: the table value plus
    /// `offset`, moved by whole turns as the axis' [`crate::ModuloStart`]
    /// says (see [`crate::ModuloAxis`]).
    Modulo {
        /// The modulo and the start mode.
        axis: crate::ModuloAxis,
        /// Added to the table value (PLCopen `SlaveOffset`).
        offset: i64,
    },
}

/// A PLCopen-style ramp-in: engage a moving master without a velocity jump.
///
/// Over `distance` master counts after engaging, the commanded position
/// blends from the slave's position at engage onto the cam with the quintic
/// law `10u³ − 15u⁴ + 6u⁵`, whose first and second derivatives vanish at both
/// ends: the slave starts from rest and meets the cam with its velocity and
/// acceleration. Not in the documents.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RampIn {
    /// Master travel (before zoom, either direction) to complete the blend.
    pub distance: NonZeroU64,
}

impl RampIn {
    /// PLCopen `MasterSyncPosition` and `MasterStartDistance`: the slave is
    /// in sync when the master reaches `sync_position`; the ramp-in starts
    /// `start_distance` before it, in the master's direction of travel
    /// (`forward`). Returns the start mode and ramp-in for
    /// [`AxisConfig::start`] and [`AxisConfig::ramp_in`]. With ramp-in
    /// limits ([`crate::CamAxis::set_ramp_in_limits`]) that need a longer
    /// ramp, the slave is in sync correspondingly later.
    ///
    /// ```
    /// use core::num::NonZeroU64;
    /// use ecam_engine::{RampIn, StartMode};
    /// let (start, ramp) = RampIn::sync_at(5_000, NonZeroU64::new(1_000).unwrap(), true);
    /// assert_eq!(start, StartMode::AtMasterPosition { position: 4_000, after_edge: false });
    /// assert_eq!(ramp.distance.get(), 1_000);
    /// ```
    pub fn sync_at(
        sync_position: i64,
        start_distance: NonZeroU64,
        forward: bool,
    ) -> (StartMode, Self) {
        let distance = i64::try_from(start_distance.get()).unwrap_or(i64::MAX);
        let position = if forward {
            sync_position.saturating_sub(distance)
        } else {
            sync_position.saturating_add(distance)
        };
        (
            StartMode::AtMasterPosition {
                position,
                after_edge: false,
            },
            Self {
                distance: start_distance,
            },
        )
    }
}

/// Everything that decides how an axis follows its master.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AxisConfig {
    /// Repetition and seam behaviour.
    pub coupling: Coupling,
    /// When the cam engages after arming.
    pub start: StartMode,
    /// Table input at the engage instant.
    pub master_align: MasterAlign,
    /// Output position at the engage instant.
    pub slave_align: SlaveAlign,
    /// Table input = master × num / den (document 003 registers 29/30).
    pub master_zoom: Zoom,
    /// Output = table value × num / den (document 003 registers 23/24).
    pub slave_zoom: Zoom,
    /// Document 001 single-turn master: the master input is a position in
    /// `[0, turn)` that wraps; the engine unwraps it, the cycle is the turn
    /// and a table not covering it is extended with its end values.
    pub single_turn: Option<NonZeroU64>,
    /// Pulse output limit in Hz; `<= 0` or `> 200_000` means 200 kHz.
    pub max_frequency_hz: i64,
    /// Up to four sync windows on the master position in the cycle.
    pub sync_windows: [SyncWindow; 4],
    /// Optional smooth engagement (beyond the documents).
    pub ramp_in: Option<RampIn>,
    /// How master readings become the followed position: as they are, or
    /// interpolated between the changes of a coarse master (see
    /// [`MasterFilter`]).
    pub master_filter: MasterFilter,
    /// Largest master step per tick (unwrapped, before zoom) accepted while
    /// the axis is armed or engaged; a larger one stops the cam with
    /// [`crate::EngineError::MasterStep`]. On a single-turn master a step of
    /// more than half a turn cannot be told from a step the other way
    /// round: set this below half a turn to fault instead of reversing.
    pub max_master_step: Option<NonZeroU64>,
}

impl Default for AxisConfig {
    fn default() -> Self {
        Self {
            coupling: Coupling::Periodic,
            start: StartMode::Immediate,
            master_align: MasterAlign::Absolute,
            slave_align: SlaveAlign::Absolute,
            master_zoom: Zoom::ONE,
            slave_zoom: Zoom::ONE,
            single_turn: None,
            max_frequency_hz: i64::from(MAX_FREQUENCY_HZ),
            sync_windows: [SyncWindow::OFF; 4],
            ramp_in: None,
            master_filter: MasterFilter::Direct,
            max_master_step: None,
        }
    }
}

/// Document 003's frequency rule: out of range means the ceiling.
pub(crate) fn effective_frequency(hz: i64) -> u32 {
    match u32::try_from(hz) {
        Ok(hz) if hz > 0 && hz <= MAX_FREQUENCY_HZ => hz,
        _ => MAX_FREQUENCY_HZ,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frequency_rule_of_document_003() {
        assert_eq!(effective_frequency(0), 200_000);
        assert_eq!(effective_frequency(-5), 200_000);
        assert_eq!(effective_frequency(200_001), 200_000);
        assert_eq!(effective_frequency(i64::MAX), 200_000);
        assert_eq!(effective_frequency(1), 1);
        assert_eq!(effective_frequency(200_000), 200_000);
    }
}
