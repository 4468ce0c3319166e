//! Cam tables: the shapes a cam is stored in.

mod point;

pub use point::{CamPoint, PointTable};
