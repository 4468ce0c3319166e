//! # ecam-design: cam tables from generators, expressions and files
//!
//! The design side of ecam, as its front ends (the `ecam` command line, the
//! designer page behind `ecam serve`, scenario files) use it:
//!
//! - run a table generator **by name** with its parameters as key/value
//!   pairs ([`from_toml`], [`from_json`], or [`find`] + [`generate`] with
//!   [`Values`] read by [`read_toml`] or built from flags), getting a
//!   [`Generated`] table with its exact derivatives, sync zone and extra
//!   outputs; every parameter's key, kind and default come from
//!   [`ecam_core::generator::schema`];
//! - the arithmetic users type: cam functions of the master `x`
//!   ([`MasterFunction`], [`function_table`]) and numbers such as `5/3` or
//!   `3*pi` ([`number`], [`Number`]);
//! - the `[table]` of a scenario file ([`load_table`]): points, an evenly
//!   spaced table, a table file, an expression or a generator;
//! - what `ecam table show` reports about a table file ([`TableReport`]:
//!   peaks of the design and the table, the rounding note, figures in
//!   machine units, steps), as text or JSON;
//! - the designer page's JSON API ([`laws_json`], [`law_curves_json`],
//!   [`generators_json`], [`key_points_json`], [`generate_json`],
//!   [`table_check_json`], [`table_read_json`], [`table_convert_json`],
//!   [`limits_json`]): JSON in, JSON out, no sockets.
//!
//! When not to use it: to generate a table from typed parameters, call
//! the generators of [`ecam_core::generator`] directly (no allocation of
//! key/value maps, no `std`, no error strings); to run a cam, use
//! `ecam-engine`; to simulate a scenario, `ecam-sim`.
//!
//! ```
//! use ecam_core::CamCurve;
//! use serde_json::json;
//!
//! // The rotary-cut demo: a 1000-pulse knife over a 3183-count sheet.
//! let g = ecam_design::from_json(
//!     "rotary-cut",
//!     json!({"master": 3183, "slave": 1000, "sync": 333, "ratio": "5/3"}),
//! )?;
//! assert_eq!(g.name, "rotary-cut");
//! assert_eq!((g.table.master_last(), g.table.slave_last()), (3183, 1000));
//! assert!(g.sync.is_some());
//!
//! // The PLC editor's sine cam, sampled at 361 masters.
//! let sine = ecam_design::function_table("1000*sin(2*pi*x/36000)", 0, 36000, 361)?;
//! assert_eq!(sine.points()[90].slave, 1000);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod designer;
mod drive;
mod error;
mod expr;
#[doc(hidden)]
pub mod fuzz;
mod generate;
mod machine;
mod params;
mod report;
mod segment_view;
mod table_api;
mod table_source;

pub use designer::{
    DEFAULT_LAW_POINTS, MAX_DESIGN_POINTS, MAX_LAW_POINTS, generate_json, generate_json_within,
    generators_json, key_points_json, law_curves_json, laws_json, segments_continuous_json,
};
pub use drive::{check_table, drive_check_json, motion_of, motion_of_cam, read_drive};
pub use error::{DriveFileError, ExprError, GenerateError, TableSourceError};
pub use expr::{MasterFunction, number};
pub use generate::{
    Generated, default_values, find, from_json, from_json_within, from_toml, from_toml_within,
    function_table, function_table_within, generate, generate_within, parse_key, parse_key_lines,
    parse_point_flag, parse_segment_flag,
};
pub use machine::{AtSpeed, Machine, Peaks, Source, Unit, short};
pub use params::{Number, Param, Values, ValuesSeed, Word, read_toml};
pub use report::TableReport;
pub use segment_view::{segments_json, segments_text};
pub use table_api::{limits_json, table_check_json, table_convert_json, table_read_json};
pub use table_source::{load as load_table, load_within as load_table_within, resolve};
