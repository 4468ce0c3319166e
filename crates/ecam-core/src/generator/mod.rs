//! Table generators: what the PLC's `ECAMTBX` instruction computes.
//!
//! Each generator takes a parameter struct whose `Default` holds the
//! document's default values and returns a validated table.

pub mod accel_curve;
pub mod cut_params;
pub mod design_curve;
pub mod flying_saw;
pub mod key_points;
mod motion_path;
pub mod placement;
pub mod rotary_cut;
pub mod s_curve;
mod sampling;
mod sync_zone;
