//! Interpolation points and the segments between them, as files and
//! requests write them.

use super::law::SegmentLaw;

/// A point of the cam: where the slave is at a master position and, where
/// the task asks, with which velocity, acceleration and jerk.
///
/// Units: master counts and slave pulses; velocity in pulses per count (the
/// slave/master ratio), acceleration in pulses/count², jerk in
/// pulses/count³. A value left out is free: the laws that adapt to it take
/// 0 (rest), and [`make_continuous`](super::make_continuous) fills it in
/// from the neighbouring segments.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterpolationPoint {
    /// Master position (counts).
    pub master: i64,
    /// Slave position (pulses).
    pub slave: i64,
    /// Velocity ratio (pulses/count), if the task fixes it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<f64>,
    /// Acceleration (pulses/count²), if the task fixes it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub acceleration: Option<f64>,
    /// Jerk (pulses/count³), if the task fixes it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub jerk: Option<f64>,
}

impl InterpolationPoint {
    /// A point at (`master`, `slave`) with every boundary value free.
    pub const fn new(master: i64, slave: i64) -> Self {
        Self {
            master,
            slave,
            velocity: None,
            acceleration: None,
            jerk: None,
        }
    }

    /// The value of `quantity`, if fixed.
    pub fn get(&self, quantity: Quantity) -> Option<f64> {
        match quantity {
            Quantity::Velocity => self.velocity,
            Quantity::Acceleration => self.acceleration,
            Quantity::Jerk => self.jerk,
        }
    }

    /// Fixes (or frees, with `None`) `quantity`.
    pub fn set(&mut self, quantity: Quantity, value: Option<f64>) {
        match quantity {
            Quantity::Velocity => self.velocity = value,
            Quantity::Acceleration => self.acceleration = value,
            Quantity::Jerk => self.jerk = value,
        }
    }
}

/// One segment as a file lists it: the law it follows to its end point,
/// which it carries (as a key point carries its curve).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentSpec {
    /// The law from the previous point to this one.
    pub law: SegmentLaw,
    /// Master position of the end point (counts).
    pub master: i64,
    /// Slave position of the end point (pulses).
    pub slave: i64,
    /// Velocity at the end point (pulses/count), if fixed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<f64>,
    /// Acceleration at the end point (pulses/count²), if fixed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub acceleration: Option<f64>,
    /// Jerk at the end point (pulses/count³), if fixed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub jerk: Option<f64>,
    /// Table points this segment gets when sampled (1..=512); unset shares
    /// what the total leaves.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub resolution: Option<u16>,
}

impl SegmentSpec {
    /// A segment along `law` to (`master`, `slave`), its end values free.
    pub const fn new(law: SegmentLaw, master: i64, slave: i64) -> Self {
        Self {
            law,
            master,
            slave,
            velocity: None,
            acceleration: None,
            jerk: None,
            resolution: None,
        }
    }

    /// The same segment with its end velocity fixed.
    pub const fn with_velocity(mut self, velocity: f64) -> Self {
        self.velocity = Some(velocity);
        self
    }

    /// The end point.
    pub const fn end(&self) -> InterpolationPoint {
        InterpolationPoint {
            master: self.master,
            slave: self.slave,
            velocity: self.velocity,
            acceleration: self.acceleration,
            jerk: self.jerk,
        }
    }

    /// The same segment ending at `point` (position and boundary values).
    pub const fn with_end(mut self, point: InterpolationPoint) -> Self {
        self.master = point.master;
        self.slave = point.slave;
        self.velocity = point.velocity;
        self.acceleration = point.acceleration;
        self.jerk = point.jerk;
        self
    }
}

/// A boundary value of a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Quantity {
    /// Velocity ratio, pulses/count.
    Velocity,
    /// Acceleration, pulses/count².
    Acceleration,
    /// Jerk, pulses/count³.
    Jerk,
}

impl Quantity {
    /// All three, lowest derivative first.
    pub const ALL: [Quantity; 3] = [Self::Velocity, Self::Acceleration, Self::Jerk];

    /// Its name in messages and files.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Velocity => "velocity",
            Self::Acceleration => "acceleration",
            Self::Jerk => "jerk",
        }
    }

    /// Its unit.
    pub const fn unit(self) -> &'static str {
        match self {
            Self::Velocity => "pulses/count",
            Self::Acceleration => "pulses/count²",
            Self::Jerk => "pulses/count³",
        }
    }

    /// Which derivative it is (1, 2, 3).
    pub(crate) const fn order(self) -> i32 {
        match self {
            Self::Velocity => 1,
            Self::Acceleration => 2,
            Self::Jerk => 3,
        }
    }
}

impl core::fmt::Display for Quantity {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}
