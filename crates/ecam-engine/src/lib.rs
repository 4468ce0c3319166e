//! # ecam-engine: the cam runtime
//!
//! Runs a slave axis against a master through any [`ecam_core::CamCurve`],
//! one [`CamAxis::tick`] per control cycle: plain input in
//! ([`TickInput`]), plain output out ([`TickOutput`]): commanded slave
//! position, pulses and direction under a frequency limit, the pulse
//! backlog, sync windows, state, flags and events. `#![no_std]`, no
//! allocation and no panic in `tick`, bounded work per call.
//!
//! Positions are `i64` counts. Which cycle the master is in, the stroke a
//! repeat cam has accumulated and both zooms are exact integer arithmetic,
//! so the commanded slave is a pure function of the master position and
//! the engage instant: a cam that runs for a year drifts by zero pulses.
//!
//! The PLC (document 003 `DECAM`) and motion-processor (document 002) faces
//! build on [`CamAxis`]; Rust users may prefer the PLCopen-shaped
//! [`plcopen`] module. Beyond the documents, [`SlaveAxis`] sums a cam, a
//! gear and a superimposed move on one slave, with phasing, print-mark
//! registration, a direction guard and a modulo (rotary) slave, and
//! [`DigitalCamSwitch`] drives cam-switch tracks; [`plcopen_slave`] is
//! their PLCopen face. Use something else when you need a trajectory
//! generator (point-to-point moves): this crate only couples axes.
//!
//! ```
//! use ecam_core::PointTable;
//! use ecam_engine::{AxisConfig, CamAxis, Coupling, SlaveAlign, TickInput};
//!
//! // Document 002's incremental cam: three values over 100 master counts.
//! let table = PointTable::from_pairs(&[(0, 0), (50, 100), (100, 200)])?;
//! let config = AxisConfig {
//!     coupling: Coupling::Repeat { min_stroke: 1 },
//!     slave_align: SlaveAlign::Relative, // a start never bumps the slave
//!     ..AxisConfig::default()
//! };
//! let mut axis = CamAxis::new(table, config)?;
//! axis.arm()?;
//! axis.tick(&TickInput::at(0, 1000));
//! assert_eq!(axis.tick(&TickInput::at(100, 1000)).slave, 200);
//! let out = axis.tick(&TickInput::at(101, 1000));
//! assert_eq!(out.slave, 202);          // the table continues past its end
//! assert_eq!(out.emitted, 202);        // every pulse went out
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![no_std]
#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used))]

#[cfg(test)]
extern crate std;

mod axis;
mod blend;
mod cam_part;
mod cam_switch;
mod coast;
mod config;
mod coupling;
mod coupling_error;
mod direction_guard;
pub mod drive;
mod error;
mod gear;
mod input;
mod master;
mod modulo;
mod offset_ramp;
mod output;
mod phasing;
pub mod plcopen;
pub mod plcopen_blocks;
pub mod plcopen_slave;
pub mod plcopen_slave_blocks;
mod pulse;
mod ramp;
mod ramp_in;
mod registration;
mod scaling;
mod slave_axis;
mod speed;
mod start;
mod start_rule;
mod steady;
mod stop;
mod superimposed;
mod switch;
mod sync;
mod timed_move;
mod tracker;
mod trapezoid;
mod turn_position;
mod zoom;

pub use axis::{AfterPass, CamAxis};
pub use blend::min_blend_distance;
pub use cam_part::CamPart;
pub use cam_switch::{
    CamSwitch, DigitalCamSwitch, SwitchDirection, SwitchMode, TRACKS, TrackOptions,
};
pub use config::{
    AxisConfig, Compare, Coupling, MAX_FREQUENCY_HZ, MasterAlign, RampIn, SlaveAlign, StartMode,
};
pub use coupling_error::CouplingError;
pub use direction_guard::{DirectionGuard, GuardDirection, GuardResume, GuardStatus};
pub use error::EngineError;
pub use gear::{GearIn, GearInPos, GearOut, GearRamp, GearState, GearStatus};
pub use input::TickInput;
pub use master::{TimeBase, Unwrap32};
pub use modulo::{ModuloAxis, ModuloPosition, ModuloStart};
pub use offset_ramp::OffsetChange;
pub use output::{AxisState, Events, TickOutput};
pub use phasing::{Phasing, PhasingMode, PhasingStatus};
pub use ramp_in::{RampDirection, RampInLimits};
pub use registration::{LatchSource, RegistrationConfig, RegistrationStatus};
pub use slave_axis::{Commands, SlaveAxis, SlaveConfig, SlaveInput, SlaveOutput};
pub use stop::StopKind;
pub use superimposed::{MoveSuperimposed, SuperimposedStatus};
pub use switch::{MissedActivation, SwitchAt};
pub use sync::SyncWindow;
pub use tracker::{MasterFilter, MasterPosition, MasterTracker};
pub use trapezoid::MoveLimits;
pub use zoom::Zoom;
