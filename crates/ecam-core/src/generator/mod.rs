//! Table generators: what the PLC's `ECAMTBX` instruction computes.
//!
//! Each generator takes a parameter struct whose `Default` holds the
//! document's default values and returns a validated table.

pub mod flying_saw;
pub mod key_points;
pub mod rotary_cut;
pub mod s_curve;
