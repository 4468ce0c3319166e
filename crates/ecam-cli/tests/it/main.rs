//! Integration tests of the `ecam` binary, one test binary (one link):
//! each module drives the real binary for one area, as a user would.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

mod common;

mod conventions;
mod docs;
mod docs_commands;
mod ethercat;
mod impulses;
mod install;
mod law;
mod limits;
mod mc_run;
mod messages;
mod plc_examples;
mod plc_rotary_knife;
mod plc_run;
mod plc_starts;
mod plots_readable;
mod pmd_run;
mod safe_motion;
mod serve;
mod serve_cam_writes;
mod serve_ethercat;
mod serve_limits;
mod serve_live;
mod serve_load;
mod serve_safety;
mod serve_soak;
mod simulate;
mod table;
mod table_design;
mod table_segments;
mod table_truth;
