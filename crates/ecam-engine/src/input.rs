//! What goes into one tick.

/// The readings of one control cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TickInput {
    /// Master position in counts, already unwrapped (see [`crate::Unwrap32`],
    /// [`crate::TimeBase`]); for a single-turn master the raw turn position.
    pub master: i64,
    /// Fraction of a count above `master`, in 1/2^32 of a count: an exact
    /// time base between its counts ([`crate::TimeBase::fraction`]), or a
    /// master read from an interpolating encoder. 0 for whole counts.
    pub master_fraction: u32,
    /// Level of the external start signal (document 003 S3 / function bit 5).
    pub start_input: bool,
    /// Position watched by a [`crate::StartMode::Breakpoint`] start (any axis).
    pub watch: i64,
    /// Time since the last tick in µs (the pulse frequency limit uses it).
    pub dt_us: u32,
    /// `false` inhibits the pulse output (PLC M8145/M8146/M8152/M8153):
    /// the cam stops immediately and no pulses go out; the backlog is kept.
    pub output_enabled: bool,
}

impl Default for TickInput {
    fn default() -> Self {
        Self {
            master: 0,
            master_fraction: 0,
            start_input: false,
            watch: 0,
            dt_us: 0,
            output_enabled: true,
        }
    }
}

impl TickInput {
    /// A tick at `master` after `dt_us`, other inputs at rest.
    pub fn at(master: i64, dt_us: u32) -> Self {
        Self {
            master,
            dt_us,
            ..Self::default()
        }
    }
}
