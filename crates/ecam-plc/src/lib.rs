//! # ecam-plc: the LX3V PLC face
//!
//! What a user of the LX3VP electronic-cam PLC (document 003) programs:
//! device memory (D, M, X, Y, C and the special registers), an
//! instruction-list interpreter with the scan cycle, simulated hardware
//! (pulse outputs Y0–Y3, PLSY/DPLSY, high-speed counters, loopback wires),
//! the `DECAM` register block and `ECAMTBX` table generation.
//!
//! Use it to run IL programs in simulated time (the `ecam plc run` command is
//! a thin layer over [`sim::run`]); it is not a real-time controller.
//!
//! ```
//! use ecam_plc::{Plc, il, sim};
//! // Y1 drives 1000 pulses at 10 kHz into X0, counted by C235.
//! let source = "LD M8000\nOUT C235 K1000\nDPLSY K10000 K1000 Y1\nLD C235\nOUT Y7\n";
//! let mut plc = Plc::new(il::parse(source, "loop.il").unwrap()).unwrap();
//! plc.hardware_mut().add_wire(ecam_plc::Wire::parse("Y1:X0").unwrap());
//! sim::run(&mut plc, sim::Timing::default(), sim::RunLength::Millis(200), |_| {}).unwrap();
//! assert_eq!(plc.devices().counter(235), Ok(1000));
//! assert_eq!(plc.devices().bit(ecam_plc::Device::Y(7)), Ok(true));
//! ```
#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used))]

// The faces a user programs against keep their namespaces (the DECAM
// register block, ECAMTBX, the instruction list, simulated time, the
// special devices); the machinery behind them is private and what a user
// needs of it is re-exported below.
pub mod decam;
pub mod ecamtbx;
#[doc(hidden)]
pub mod fuzz;
pub mod il;
pub mod sim;
pub mod special;

mod devices;
mod hardware;
mod interpreter;
mod operation_error;
mod remote_write;
mod scan;
mod timers;
mod view;

pub use devices::{
    C_32BIT_FIRST, C_COUNT, C_LATCHED, D_COUNT, D_LATCHED, Device, DeviceError, Devices, M_COUNT,
    M_LATCHED, Retention, SPECIAL_FIRST, XY_COUNT,
};
pub use hardware::{
    Counters, HIGH_SPEED_COUNTERS, Hardware, OutputOwner, PULSE_OUTPUTS, PulseTrain, Wire,
    WireError, record_pulses,
};
pub use interpreter::MAX_STEPS_PER_SCAN;
pub use operation_error::{
    CODE_CALL_NESTING, CODE_DEVICE_RANGE, CODE_OPERAND, CODE_SCAN_LIMIT, OperationError,
};
pub use remote_write::WriteRefusal;
pub use scan::Plc;
pub use timers::{T_COUNT, Timers, timer_clock};
pub use view::{Value, View, ViewError};
