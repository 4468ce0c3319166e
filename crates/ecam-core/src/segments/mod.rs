//! Cams made of segments between interpolation points, as the cam editors
//! of motion controllers design them (VDI 2143's way): each point fixes
//! the slave's position at a master position and, where the task asks,
//! its velocity, acceleration and jerk; each segment follows a law chosen
//! for its task, and the laws that can are solved to meet the points.
//!
//! - [`InterpolationPoint`], [`SegmentSpec`]: the points and the segments
//!   (law, end point, resolution) as files and requests give them;
//! - [`SegmentLaw`]: the eleven rise laws of [`crate::law`], the
//!   polynomials of degree 5 and 7 solved for the boundary values, and a
//!   velocity-to-velocity law; [`SegmentLaw::adapts`] says which values
//!   each one takes from its points;
//! - [`SegmentCam`]: the solved cam, checked (a law that cannot give what a
//!   point asks is refused, naming the point), evaluated exactly, sampled
//!   into point tables and evenly spaced buffers;
//! - [`SegmentPeaks`]: `Cv`, `Ca`, `Cj` and the peaks of every segment,
//!   from closed forms;
//! - [`ContinuityReport`]: C0–C3 at every point and at the seam;
//! - [`make_continuous`]: the free boundary values filled in from the
//!   neighbours in one step.
//!
//! ```
//! use ecam_core::segments::{InterpolationPoint, SegmentCam, SegmentLaw, SegmentSpec};
//! use ecam_core::MotionLaw;
//!
//! // Dwell, poly-5 rise into a constant-velocity zone, poly-5 back to rest.
//! let cam = SegmentCam::continuous(
//!     InterpolationPoint::new(0, 0),
//!     vec![
//!         SegmentSpec::new(SegmentLaw::Rise(MotionLaw::Cycloid), 1000, 0),
//!         SegmentSpec::new(SegmentLaw::Poly5, 2000, 1000),
//!         SegmentSpec::new(SegmentLaw::Rise(MotionLaw::ConstantVelocity), 3000, 3000),
//!         SegmentSpec::new(SegmentLaw::Poly5, 4000, 0),
//!     ],
//! )?;
//! // The free velocities were filled from the constant-velocity zone.
//! assert_eq!(cam.segments()[1].velocity, Some(2.0));
//! assert_eq!(cam.continuity().cam.to_string(), "C2");
//! # Ok::<(), ecam_core::segments::SegmentError>(())
//! ```

mod cam;
mod continuity;
mod error;
mod fill;
mod law;
mod peaks;
mod point;
pub mod poly;
mod shape;
mod solve;

pub use cam::SegmentCam;
pub use continuity::{ContinuityReport, Joint};
pub use error::SegmentError;
pub use fill::make_continuous;
pub use law::{Adapts, SegmentLaw};
pub use peaks::SegmentPeaks;
pub use point::{InterpolationPoint, Quantity, SegmentSpec};
pub use solve::MAX_SEGMENTS;
