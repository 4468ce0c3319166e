//! What comes out of one tick.

use crate::EngineError;

/// Where an axis is in its life.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum AxisState {
    /// Not coupled; the slave holds (pending pulses still drain).
    #[default]
    Idle,
    /// Waiting for the start condition.
    Armed,
    /// The start came; waiting out the delay in master counts.
    Delaying,
    /// Following the cam.
    Running,
    /// Following the cam until the end of the current cycle.
    Stopping,
    /// A one-shot ended or an end-of-cycle stop completed; the slave holds.
    /// [`crate::CamAxis::arm`] starts again.
    Finished,
    /// Out of the cam, the slave moving on at the velocity it had (PLCopen
    /// `MC_CamOut`, [`crate::CamAxis::cam_out_at_velocity`]) or
    /// decelerating to rest ([`crate::CamAxis::stop_decelerating`]).
    Velocity,
}

impl AxisState {
    /// Following the master (running or stopping).
    pub const fn is_engaged(self) -> bool {
        matches!(self, Self::Running | Self::Stopping)
    }

    /// Armed, delaying, running or stopping (document 003 flag bit 0), or
    /// moving at velocity after a cam-out: the axis commands the slave.
    pub const fn is_active(self) -> bool {
        matches!(
            self,
            Self::Armed | Self::Delaying | Self::Running | Self::Stopping | Self::Velocity
        )
    }
}

/// Things that happened during this tick only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Events {
    /// The cam engaged.
    pub engaged: bool,
    /// The master crossed a cycle boundary (either direction), or a
    /// one-shot completed its last cycle.
    pub cycle_completed: bool,
    /// A one-shot reached its natural end (PLCopen `EndOfProfile`).
    pub finished: bool,
    /// An immediate or end-of-cycle stop took effect (also after a fault or
    /// an output inhibit).
    pub stopped: bool,
    /// A periodic cam whose first and last slave values differ crossed its
    /// seam: the slave jumps by the difference (document 001 Periodic type).
    /// The jump goes out under the frequency limit, never as one burst.
    pub seam_jump: bool,
    /// A table queued with [`crate::CamAxis::queue_curve`] took over at the
    /// seam just crossed, or one handed over with
    /// [`crate::CamAxis::switch_curve`] took over at its master position
    /// or at once.
    pub table_switched: bool,
    /// The master passed an activation position (a start or switch at a
    /// master position) backwards; what followed is the axis'
    /// [`crate::MissedActivation`] policy.
    pub activation_missed: bool,
}

impl Events {
    /// Adds what `other` reports to this.
    pub fn merge(&mut self, other: Self) {
        self.engaged |= other.engaged;
        self.cycle_completed |= other.cycle_completed;
        self.finished |= other.finished;
        self.stopped |= other.stopped;
        self.seam_jump |= other.seam_jump;
        self.table_switched |= other.table_switched;
        self.activation_missed |= other.activation_missed;
    }
}

/// Everything an axis reports after a tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TickOutput {
    /// Life-cycle state after this tick.
    pub state: AxisState,
    /// Master position used this tick (unwrapped, before zoom).
    pub master: i64,
    /// Table input in the cycle, after master zoom (floor): document 003
    /// registers 25/26; sync windows compare this.
    pub master_in_cycle: i64,
    /// The same place in master counts before zoom (registers 27/28).
    pub master_in_cycle_raw: i64,
    /// Cycles completed since engaging (negative when the master went back).
    pub cycle: i64,
    /// Commanded slave position, after zoom and offsets (registers 19/20).
    pub slave: i64,
    /// Table value plus accumulated stroke, before slave zoom and output
    /// offset (registers 21/22).
    pub slave_unzoomed: i64,
    /// d(slave)/d(master) here, after both zooms (0 when not following).
    pub velocity_ratio: f64,
    /// Pulses emitted this tick, signed (negative = reverse).
    pub pulses: i64,
    /// Direction of the last pulses (kept while none flow).
    pub direction_forward: bool,
    /// Cumulative emitted position (D8140.. counters: take `as i32`).
    pub emitted: i64,
    /// Commanded minus emitted: pulses owed, never dropped.
    pub backlog: i64,
    /// Document 003 flag bit 2: the backlog is not zero.
    pub pulse_delayed: bool,
    /// Bit `i` set while sync window `i` holds the master.
    pub sync: u8,
    /// Any sync window active (document 003 flag bit 10).
    pub in_sync: bool,
    /// Document 003 flag bit 0: armed, delaying, running or stopping.
    pub initialised: bool,
    /// Running, any ramp-in and any table-switch blend complete (PLCopen
    /// `InSync`).
    pub following: bool,
    /// Active or pulses still owed (PLC M8147..M8150 BUSY).
    pub busy: bool,
    /// This tick's events.
    pub events: Events,
    /// Document 002 `CamInputOffset`: table input minus zoomed master.
    pub input_offset: i64,
    /// Document 002 `CamOutputOffset`: commanded minus the zoomed table
    /// value in the cycle (includes accumulated strokes).
    pub output_offset: i64,
    /// An activation position was passed backwards since the last arm,
    /// engage or switch (the status of `events.activation_missed`).
    pub activation_missed: bool,
    /// Set on the tick a runtime fault stopped the cam.
    pub fault: Option<EngineError>,
}
