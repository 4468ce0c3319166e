//! A cam checked against its drive: what the slave's motor must do to
//! follow the cam at a machine speed, and the fastest machine speed the
//! drive's limits allow.
//!
//! Given the slave's mechanics ([`Mechanics`]: motor and load inertia, gear
//! ratio, friction and a constant load torque, slave pulses per motor
//! revolution) and the drive's limits ([`DriveLimits`]: motor speed, peak
//! and RMS torque, optionally the slave's jerk), [`check`] takes the cam's
//! motion over one cycle ([`Motion`]: exact samples of its velocity,
//! acceleration and jerk per master count) and reports ([`DriveReport`]):
//!
//! - at a master speed `f` (counts/s, constant): the motor's peak speed,
//!   peak and RMS torque over the cycle and the peak jerk, each against its
//!   limit;
//! - for every limit, the highest master speed it allows, which one binds
//!   first, and that speed in machine cycles per minute.
//!
//! The formulas (`docs/design.md`, "Checking a cam against its drive"):
//! with `U` slave pulses per motor revolution, a slave velocity ratio `v`
//! (pulses/count) is a motor speed `n = 60·v·f/U` rpm; an acceleration `a`
//! (pulses/count²) a motor acceleration `α = 2π·a·f²/U` rad/s²; the motor
//! torque is `T = J·α + (T_f·sgn v + T_L)/i` N·m with `J = J_m + J_L/i²`
//! kg·m² (`i` motor revolutions per load revolution, `T_f` friction and
//! `T_L` load torque at the load); `T_rms² = (1/β)∫T² dm` over the cycle's
//! `β` counts (at a constant master speed, time is proportional to the
//! master). Torque is `A·f² + B` at every point, so each limit gives the
//! highest speed in closed form: `f² ≤ (T_peak ∓ B)/|A|` pointwise,
//! `mean(A²)·f⁴ + 2·mean(AB)·f² + mean(B²) ≤ T_rms²`, `max|v|·60·f/U ≤ n_max`,
//! `max|j|·f³ ≤ jerk_max`.

mod check;
mod motion;
mod spec;

pub use check::{AtSpeed, DriveReport, Limit, LimitSpeed, check};
pub use motion::Motion;
pub use spec::{Drive, DriveError, DriveLimits, Mechanics};
