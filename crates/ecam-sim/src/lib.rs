//! # ecam-sim: the engine run in simulated time
//!
//! A scenario file names a cam (any `[table]` source of `ecam-design`), the
//! engine's configuration, a master motion, a start and a stop
//! ([`Scenario`], every key in `docs/simulate.md`). [`simulate`] ticks an
//! [`ecam_engine::CamAxis`] through it at the scenario's control cycle,
//! hands each tick's [`Row`] and engine output to the caller (to write a
//! trace, draw a plot, or check an invariant) and returns a [`Summary`].
//!
//! A scenario with couplings beyond the cam (`[modulo]`,
//! `[direction_guard]`, `[registration]`, `[cam_switches]`, `[[plcopen]]`
//! steps) runs on an [`ecam_engine::SlaveAxis`]; [`simulate`] hands the
//! caller the axis' sum as a cam's output, [`simulate_couplings`] every
//! coupling's status.
//!
//! This is what `ecam simulate` runs, with the trace CSV it writes
//! ([`TraceWriter`]) and the picture it draws ([`TracePlot`]); the command
//! line only reads its arguments and wires them.
//!
//! When not to use it: to drive a real axis, call `ecam-engine`'s `tick`
//! from your own control loop (the simulation holds the whole master
//! motion up front and allocates); to emulate the PLC or motion-processor
//! faces, use `ecam-plc` or `ecam-pmd`.
//!
//! ```
//! use std::path::Path;
//! use ecam_sim::{Scenario, simulate};
//!
//! // Document 002's linear table: input 101 gives output 202.
//! let scenario = Scenario::parse(
//!     r#"
//!     tick_us = 1000
//!     [table]
//!     uniform = [0, 100, 200]
//!     counts = 100
//!     [cam]
//!     kind = "repeat"
//!     [start]
//!     slave_align = "relative"
//!     [master]
//!     moves = [[0.101, 101]]
//!     "#,
//!     Path::new("."),
//! )?;
//! let mut rows = 0;
//! let summary = simulate(&scenario, |_row, _out, _traced| {
//!     rows += 1;
//!     Ok::<(), std::io::Error>(())
//! })?;
//! assert_eq!((summary.final_master, summary.final_slave), (101, 202));
//! assert_eq!(summary.state, "running");
//! assert_eq!(rows, summary.ticks);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod coupled;
mod couplings;
mod couplings_error;
mod error;
#[doc(hidden)]
pub mod fuzz;
mod plot;
mod scenario;
mod simulate;
mod steps;
mod summary;
mod trace;
mod trigger;

pub use coupled::{CouplingTick, simulate_couplings};
pub use couplings::{CamSwitches, Couplings, Marks, SwitchAxis};
pub use couplings_error::CouplingsError;
pub use error::{ScenarioError, SimulateError};
pub use plot::{PLOT_POINTS, TracePlot};
pub use scenario::{MasterMove, Scenario, StopAt};
pub use simulate::simulate;
pub use steps::{Block, PlcopenStep};
pub use summary::Summary;
pub use trace::{HEADER, Row, TraceError, TraceWriter, state_name};
pub use trigger::StopTrigger;
