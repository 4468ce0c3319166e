//! Table generators: what the PLC's `ECAMTBX` instruction computes.
//!
//! Each generator has a module with its `Params` (whose `Default` holds the
//! document's default values), a `generate` function returning a validated
//! table, and its `Generated` results. The options the parameters choose
//! from ([`AccelCurve`], [`CamPlacement`], key points'
//! [`CurveType`](key_points::CurveType)) have a name and a code; every
//! parameter is described once in [`schema`], which the command line, the
//! HTTP API, the designer page and ECAMTBX read.

mod accel_curve;
mod choice_serde;
mod cut_params;
mod design_curve;
mod exact;
pub mod flying_saw;
pub mod function;
pub mod key_points;
mod motion_path;
mod placement;
pub mod rotary_cut;
pub mod s_curve;
mod sampling;
pub mod schema;
pub mod segments;
mod sync_zone;

pub use accel_curve::AccelCurve;
pub use cut_params::CutParams;
pub use design_curve::DesignCurve;
pub use exact::ExactCurve;
pub use placement::CamPlacement;
pub use schema::{Field, FieldKind, Generator};
