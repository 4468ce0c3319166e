//! # ecam-plc: the LX3V PLC face
//!
//! What a user of the LX3VP electronic-cam PLC (document 003) programs:
//! device memory (D, M, X, Y, C, T, V/Z and the special registers), an
//! instruction-list program and the scan cycle that runs it, simulated
//! hardware (pulse outputs Y0–Y3, PLSY/DPLSY, high-speed counters, loopback
//! wires), the `DECAM` register block and `ECAMTBX` table generation.
//!
//! Use it to run IL programs in simulated time (the `ecam plc run` command
//! is a thin layer over [`sim::run`], `ecam serve` runs the same [`Plc`] in
//! real time); it is not a real-time controller by itself.
//!
//! - **Load and run**: [`Program::parse`] checks a program whole (every
//!   error names its file and line); [`Plc::new`] loads it; [`Plc::scan`]
//!   runs one program scan, [`Plc::hardware_tick`] advances the hardware;
//!   [`sim::run`] alternates both in simulated time.
//! - **Device memory**: [`Devices`] (through [`Plc::devices`]) reads and
//!   writes every [`Device`]; [`View`] names a value the way tools do
//!   (`DD100`, `DE106`, `D2001.1`, `T0`); [`Retention`] says what survives a
//!   power cycle; [`special`] lists the special devices.
//! - **Hardware**: [`Wire`] feeds a pulse output into a counter input
//!   ([`Hardware::add_wire`]); [`Hardware::emitted`] is each output's
//!   position.
//! - **E-cam**: [`decam`] holds the DECAM register block's offsets and
//!   flags, writes a point table into it ([`decam::load_table`]) and runs
//!   one DECAM on its own ([`decam::Decam`]); [`ecamtbx`] generates tables.
//! - **Errors**: a program that does not load is a [`ParseError`] (its
//!   parts in [`error`]); an instruction that fails at run time is an
//!   [`OperationError`] with the FX code that goes to D8067.
//!
//! ```
//! use ecam_plc::{Device, Plc, Program, Wire, sim};
//! // Y1 drives 1000 pulses at 10 kHz into X0, counted by C235.
//! let source = "LD M8000\nOUT C235 K1000\nDPLSY K10000 K1000 Y1\nLD C235\nOUT Y7\n";
//! let mut plc = Plc::new(Program::parse(source, "loop.il")?)?;
//! plc.hardware_mut().add_wire(Wire::parse("Y1:X0")?);
//! sim::run(&mut plc, sim::Timing::default(), sim::RunLength::Millis(200), |_| {})?;
//! assert_eq!(plc.devices().counter(235), Ok(1000));
//! assert_eq!(plc.devices().bit(Device::Y(7)), Ok(true));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used))]

// The faces a user programs against keep their namespaces (the DECAM
// register block, ECAMTBX, simulated time, the special devices, the parts
// of a parse error); everything else a user needs is re-exported below,
// and the machinery behind it (the IL syntax tree, the interpreter, the
// pulse trains and counters) stays private.
pub mod decam;
pub mod ecamtbx;
pub mod error;
#[doc(hidden)]
pub mod fuzz;
pub mod sim;
pub mod special;
pub mod watchdog;

mod device;
mod devices;
mod hardware;
mod il;
mod index_register;
mod interpreter;
mod operation_error;
mod remote_write;
mod scan;
mod timers;
mod view;

// Loading and running a program.
pub use il::{ParseError, Program};
pub use interpreter::LineError;
pub use scan::Plc;

// Device memory.
pub use device::{
    C_32BIT_FIRST, C_COUNT, C_LATCHED, D_COUNT, D_LATCHED, Device, DeviceError, M_COUNT, M_LATCHED,
    Retention, SPECIAL_FIRST, XY_COUNT,
};
pub use devices::Devices;
pub use index_register::{INDEX_COUNT, IndexReg};
pub use timers::{T_COUNT, Timers};
pub use view::{Value, View, ViewError};

// Simulated hardware.
pub use hardware::{Hardware, OutputOwner, Wire, WireError};

// Run-time errors of instructions.
pub use operation_error::{CODE_CALL_NESTING, CODE_DEVICE_RANGE, CODE_OPERAND, OperationError};

// Writes from outside the program into its cam blocks.
pub use remote_write::{WriteRefusal, check_register_writes, check_table_load};
