//! One point of a point table: a master position and the slave position
//! there. Its own file so that the table ([`point`](super::point)) and its
//! float copy ([`lines`](super::lines)) both use it without using each
//! other.

/// One point of a point table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CamPoint {
    /// Master position, in master counts.
    pub master: i64,
    /// Slave position, in slave pulses.
    pub slave: i64,
}

impl CamPoint {
    /// A point at `(master, slave)`.
    pub const fn new(master: i64, slave: i64) -> Self {
        Self { master, slave }
    }
}
